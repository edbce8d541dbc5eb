#!/usr/bin/env bash
# Regenerates the viewer screenshots of the bundled examples in docs/images/ (issue #25, item 4):
# each example run with --html, the page opened in Debian's headless Chromium by
# tests/viewer/check_page.mjs (which also checks it: no console error, ready, rows) and photographed.
# Needs a build with the viewer (tools/demo.sh or tools/test.sh made one) and chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
I=./build/apps/cli/interfere
E=data/examples
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
shot() {  # page expectations-json output.png
  echo "$2" > "$W/expect.json"
  node tests/viewer/check_page.mjs "$1" "$W/expect.json" --screenshot "$3" > "$W/check.log" || { cat "$W/check.log"; exit 1; }
  echo "docs/images/$(basename "$3")"
}
# The demo's clash: the tilted pin through the plate (exit 1: they clash).
$I clash --scene $E/scene.json --html "$W/clash.html" -q > /dev/null || [ $? -eq 1 ]
shot "$W/clash.html" '{"rows": 1, "clickRow": 0}' docs/images/demo_clash.png
# The bearing example: 16 roller/partner pairs over 50 frames.
$I bearing --params $E/bearing.parameters --html "$W/bearing.html" -q > /dev/null || [ $? -eq 1 ]
shot "$W/bearing.html" '{"frames": 50}' docs/images/bearing.png
# The casing's features, the assembly-feature faces of process step P2 in red.
if $I features $E/casing.step --process $E/casing_process.json --step P2 --html "$W/features.html" -q > /dev/null; then
  shot "$W/features.html" '{"rows": 0}' docs/images/casing_features.png
fi
# A STEP assembly as a scene with a 15 mm clearance test (the demo's last step).
if $I clash tests/cli/data/assembly.step --clearance 15 --html "$W/scene.html" -q > /dev/null; then
  shot "$W/scene.html" '{"clickRow": 0}' docs/images/assembly_scene.png
fi
