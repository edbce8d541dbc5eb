#!/usr/bin/env bash
# interfere-mpi sweep against `interfere sweep` (issue #31, item 3): docs/cli.md's example (plate.stl,
# the paper's machine probe_paper_machine.json, probe_path.csv: 6 pose points through the machine's
# inverse kinematics) and a denser copy of its path (4 points per step: 21 points), path points in
# blocks per rank, K = 1..4: the same CSV byte for byte, the same --hits-obj geometry, the same JSON
# apart from seconds (also the "timings") and the "mpi" section (compare_reports.py) and the same summary; with and
# without the check between points (a segment at a block border owned by the earlier rank), a
# requested clearance, straight pose motion, a joint path, the paper's machine by --d1/--d2; 2 points on 4 ranks
# (idle ranks, a warning); bad input exits 2 with the message (a bad path file, a missing one,
# options not offered), nothing written.
# Usage: run_mpi_sweep_tests.sh INTERFERE INTERFERE_MPI DATA_EXAMPLES_DIR
source "$(dirname "$0")/common.sh"
ex=$(realpath "$3")
cd "$work" || exit 1
cp "$ex"/plate.stl "$ex"/probe_paper_machine.json "$ex"/probe_path.csv .
# The denser path: 3 poses between each two of probe_path.csv's (tip linear, axis normalised).
"$py" - probe_path.csv > dense.csv <<'PY'
import math, sys
lines = [l.strip() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
head, rows = lines[0], [[float(v) for v in l.split(",")] for l in lines[1:]]
print(head)
def out(r):
    a = r[3:6]; n = math.sqrt(sum(x * x for x in a))
    print(",".join("%.9f" % v for v in r[:3] + [x / n for x in a]))
for i, r in enumerate(rows):
    out(r)
    if i + 1 < len(rows):
        for s in (1, 2, 3):
            out([a + s / 4 * (b - a) for a, b in zip(r, rows[i + 1])])
PY
grep -v '^#' probe_path.csv | sed -n '1,3p' > two.csv
common=(--workpiece plate.stl --probe-radius 5 --probe-length 40)
robot=(--robot probe_paper_machine.json)

same() {  # name, ranks..., -- extra args...
  local name=$1; shift
  local ks=()
  while test "$1" != "--"; do ks+=("$1"); shift; done
  shift
  "$cli" sweep "${common[@]}" "$@" --csv "$name.single.csv" --json "$name.single.json" --hits-obj "$name.single.obj" \
    >"$name.single.txt" 2>/dev/null
  local want=$?
  check test -s "$name.single.json"
  for k in "${ks[@]}"; do
    "${mpirun_[@]}" -n "$k" "$mpi" sweep "${common[@]}" "$@" --csv "$name.mpi$k.csv" --json "$name.mpi$k.json" \
      --hits-obj "$name.mpi$k.obj" >"$name.mpi$k.txt" 2>"$name.mpi$k.err"
    local rc=$?
    check test "$rc" = "$want"
    check cmp -s "$name.single.csv" "$name.mpi$k.csv"
    check cmp -s "$name.single.obj" "$name.mpi$k.obj"
    # (the sweep report's "timings" are seconds too: zeroed in the copies compared)
    "$py" -c "import json,sys
for f in sys.argv[1:]:
    r = json.load(open(f)); r['timings'] = {k: 0 for k in r['timings']}; json.dump(r, open(f + '.cmp', 'w'))" \
      "$name.single.json" "$name.mpi$k.json"
    check "$py" "$here/compare_reports.py" "$name.single.json.cmp" "$name.mpi$k.json.cmp"
    check "$py" -c "import json,sys; m=json.load(open(sys.argv[1]))['mpi']; sys.exit(not (m['ranks']==$k and len(m['per_rank'])==$k))" "$name.mpi$k.json"
    check cmp -s <(grep -v '^(' "$name.mpi$k.txt") "$name.single.txt"  # (the summary, less "(K ranks)")
    echo "sweep $name $* K=$k: rc=$rc (single $want)"
  done
}
same example 1 2 3 4 -- "${robot[@]}" --path probe_path.csv
same dense 1 2 3 4 -- "${robot[@]}" --path dense.csv --clearance 3
same discrete 2 3 -- "${robot[@]}" --path dense.csv --no-continuous
same pose 1 3 4 -- "${robot[@]}" --path dense.csv --interpolate pose --max-clearance 20
same paper 2 4 -- --d1 30 --d2 120 --path dense.csv --depth 10
# A joint path (the paper machine's joint values of the dense run, as interfere sweep reported them).
"$py" - dense.single.json probe_paper_machine.json > joints.csv <<'PY'
import json, sys
r, m = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
print(",".join(j["name"] for j in m["joints"]))
for p in r["points"]:
    print(",".join("%.12g" % v for v in p["joints"]))
PY
same joints 1 2 4 -- "${robot[@]}" --path joints.csv
same idle 4 -- "${robot[@]}" --path two.csv
check grep -q "ranks idle" idle.mpi4.err
# (the example collides: the comparisons above saw clash rows and colliding segments at block borders)
check grep -q ",clash$" dense.single.csv
check "$py" -c "import json,sys; sys.exit(not json.load(open(sys.argv[1]))['summary']['colliding_segments'])" dense.single.json

# Bad input: every rank finds it, exit 2 and the message naming the file, nothing written.
printf 'px,py,pz,ax,ay,az\n0,0,20,0,0,-1\n10,0,zero,0,0,-1\n' > bad.csv
"${mpirun_[@]}" -n 2 "$mpi" sweep "${common[@]}" "${robot[@]}" --path bad.csv --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "bad.csv" bad.err
check test ! -e bad.json
"${mpirun_[@]}" -n 2 "$mpi" sweep "${common[@]}" "${robot[@]}" --path missing.csv --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "missing.csv" bad.err
check test ! -e bad.json
for flag in "--replan-tilt 20" "--replanned-path r.csv" "--paper-levels" "--html v.html"; do
  # shellcheck disable=SC2086
  "${mpirun_[@]}" -n 2 "$mpi" sweep "${common[@]}" "${robot[@]}" --path probe_path.csv $flag --json bad.json >/dev/null 2>bad.err
  check test $? = 2
  check grep -q "^interfere: error: ${flag%% *}: not offered" bad.err
  check test ! -e bad.json
done
"${mpirun_[@]}" -n 2 "$mpi" sweep "${common[@]}" "${robot[@]}" --path probe_path.csv --json nofolder/r.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --json nofolder/r.json: no folder" bad.err
exit $fail
