#!/usr/bin/env bash
# Review of 92c0a27 (issue #31, item 3): `interfere-mpi clash --distribute frames` against
# `interfere clash --scene` on review_make_border_series.py's adversarial series: clashes at the
# blocks' borders for every K, an id carried from frame 0 to the end (reruns chained back to frame 0),
# a one-frame clash, one id in two separate frames, two clashes of one pair whose nearest-location
# matching crosses, a verdict changing every frame; K = 1..8 on 9 frames (every border position) and
# K = 1..6 on 3 frames and K = 1..3 on 1 frame (K larger than the frames: idle ranks); with a
# baseline report, grouping by location and none, --fail-on. Oracle: the one process's report
# (compare_reports.py) and its CSV tables byte for byte; the exit status.
# Usage: test_review_series_borders.sh INTERFERE INTERFERE_MPI
source "$(dirname "$0")/common.sh"
"$py" "$here/review_make_border_series.py" "$work" || exit 1
d=$work/border
series() {  # motion file, largest K, extra arguments (to both)...
  local m=$1 kmax=$2
  shift 2
  (cd "$d" && "$cli" clash --scene scene.json --motion "$m" "$@" --json single.json --csv single.csv --frames-csv single_f.csv \
     --frame-pairs-csv single_p.csv --quiet >/dev/null 2>single.err)
  local src=$?
  check "$py" -c 'import json,sys; r=json.load(open(sys.argv[1])); c=r["summary"]; sys.exit(0 if c.get("clashes", 0) >= 2 else 1)' "$d/single.json"
  for k in $(seq 1 "$kmax"); do
    (cd "$d" && timeout 300 "${mpirun_[@]}" -n "$k" "$mpi" clash --scene scene.json --motion "$m" "$@" --distribute frames \
       --json mpi$k.json --csv mpi$k.csv --frames-csv mpi${k}_f.csv --frame-pairs-csv mpi${k}_p.csv --quiet >/dev/null 2>"mpi$k.err")
    local rc=$?
    same_frames_outputs "$d" "$k" "$src" "$rc"
    local n
    n=$("$py" -c 'import json,sys; m=json.load(open(sys.argv[1]))["mpi"]; print(m["reruns"], m["rounds"])' "$d/mpi$k.json" 2>/dev/null)
    echo "$m $* K=$k: rc=$rc (single $src) reruns/rounds=$n"
  done
}
series motion9.csv 8
series motion3.csv 6
series motion1.csv 3
# the report's other paths: a baseline (an earlier run's report: new, active and resolved clashes), grouping
# by location, exit status by --fail-on
(cd "$d" && "$cli" clash --scene scene.json --motion motion3.csv --json baseline.json --quiet >/dev/null 2>&1)
series motion9.csv 5 --baseline baseline.json
series motion9.csv 4 --group-by location --group-distance 2 --fail-on contact,clearance
series motion9.csv 3 --group-by none
exit $fail
