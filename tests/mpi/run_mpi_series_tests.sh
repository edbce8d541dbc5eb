#!/usr/bin/env bash
# `interfere-mpi clash --distribute frames` against `interfere clash --scene` (issue #31, item 3;
# docs/mpi.md, "Time series"): motion frames and FE load steps split across K = 1..4 ranks in blocks
# give the single process's report (compare_reports.py: apart from timings, threads and the mpi
# section; core_runs included) and byte-equal --csv, --frames-csv and --frame-pairs-csv tables.
# Scenes (make_series.py): the tiny scene with make_scenes.py's 6-frame motion (clashes that move on
# their bodies keep their ids from frame 0: the blocks are run again from further back, mpi.reruns
# > 0), with a 12-frame motion of rigid clusters (no border needs history: mpi.reruns = 0), an FE
# model with 4 and with 12 load steps (also --scale 2 --no-reference). A static scene with --distribute
# frames goes by pairs (warning); a bad --distribute value: exit 2; usage errors name the flag (CLI11).
# Usage: run_mpi_series_tests.sh INTERFERE INTERFERE_MPI
source "$(dirname "$0")/common.sh"
"$py" "$here/make_scenes.py" "$work" || exit 1
"$py" "$here/make_series.py" "$work/series" || exit 1
mpi_key() {  # report, python expression on m (its mpi section)
  "$py" -c 'import json,sys; m=json.load(open(sys.argv[1]))["mpi"]; print(eval(sys.argv[2]))' "$1" "$2"
}

frames() {  # scene dir, reruns expected at K >= 2 (zero, some or any), extra args...
  local d=$1 reruns=$2; shift 2
  (cd "$d" && "$cli" clash --scene scene.json "$@" --json single.json --csv single.csv --frames-csv single_f.csv \
     --frame-pairs-csv single_p.csv --quiet >/dev/null 2>&1)
  local src=$?
  for k in 1 2 3 4; do
    (cd "$d" && "${mpirun_[@]}" -n $k "$mpi" clash --scene scene.json "$@" --distribute frames --json mpi$k.json --csv mpi$k.csv \
       --frames-csv mpi${k}_f.csv --frame-pairs-csv mpi${k}_p.csv --quiet >/dev/null 2>"mpi$k.err")
    local rc=$?
    same_frames_outputs "$d" "$k" "$src" "$rc"
    check test "$(mpi_key "$d/mpi$k.json" 'm["distribute"], m["ranks"]')" = "('frames', $k)"
    local n
    n=$(mpi_key "$d/mpi$k.json" 'm["reruns"]')
    if [ "$k" -ge 2 ]; then
      if [ "$reruns" = zero ]; then check test "$n" = 0; elif [ "$reruns" = some ]; then check test "$n" -gt 0; fi
    fi
    echo "$(basename "$d") $* frames K=$k: rc=$rc reruns=$n"
  done
}
s=$work/series
frames "$s/tiny" some --motion motion.csv       # (ids carried from frame 0: blocks run again from further back)
frames "$s/tiny" zero --motion cluster.csv      # (rigid clusters: every border holds at one frame back)
frames "$work/fe" zero                          # (4 load steps, the reference configuration, designed contacts)
frames "$s/fe12" some                           # (12 steps: the ids of the pushed body's clash carry a few steps)
frames "$s/fe12" any --scale 2 --no-reference

# A static scene: nothing to split by frames, the job goes by body pairs (a warning), the same report.
(cd "$work/tiny" && "$cli" clash --scene scene.json --json single.json --quiet >/dev/null 2>&1)
(cd "$work/tiny" && "${mpirun_[@]}" -n 2 "$mpi" clash --scene scene.json --distribute frames --json static.json >/dev/null 2>static.err)
check test $? = 1
check grep -q "the scene has no frames: distributed by body pairs" "$work/tiny/static.err"
check "$py" "$here/compare_reports.py" "$work/tiny/single.json" "$work/tiny/static.json"
check test "$(mpi_key "$work/tiny/static.json" 'm.get("distribute", "pairs")')" = pairs
echo "static scene with --distribute frames: by pairs"

# A bad value: exit 2, the flag named, nothing written.
(cd "$work/tiny" && "${mpirun_[@]}" -n 2 "$mpi" clash --scene scene.json --distribute steps --json bad.json >/dev/null 2>bad.err)
check test $? = 2
check grep -q "^interfere: error: --distribute: 'steps' is not pairs or frames" "$work/tiny/bad.err"
check test ! -e "$work/tiny/bad.json"
echo "bad --distribute: exit 2"

# The command line (CLI11, apps/mpi/args.cpp): a missing value, a bad number, a file on the command
# line: exit 2, the flag named; a pairs report's "mpi" section validates against docs/schema.
for bad in "--scene|--scene: 1 required" "--scene scene.json --clearance x|--clearance: 'x' is not a finite number >= 0" \
           "--scene scene.json more.stl|'more.stl': interfere-mpi takes no input files" \
           "--scene scene.json --test|--test: 1 required"; do
  args=${bad%%|*} want=${bad#*|}
  # shellcheck disable=SC2086
  (cd "$work/tiny" && "${mpirun_[@]}" -n 2 "$mpi" clash $args >/dev/null 2>args.err)
  check test $? = 2
  check grep -q -- "^interfere: error: $want" "$work/tiny/args.err"
  echo "usage error ($args): exit 2"
done
check "$py" -c 'import json,os,sys; sys.path.insert(0, os.path.join(sys.argv[1], "..", "cli")); import report_schema; report_schema.validate(json.load(open(sys.argv[2])), sys.argv[2])' "$here" "$work/tiny/static.json"
exit $fail
