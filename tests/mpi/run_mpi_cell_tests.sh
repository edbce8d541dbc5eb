#!/usr/bin/env bash
# interfere-mpi cell against `interfere cell` (issue #31, item 3): the bundled probe cell
# (examples/probe) along a denser copy of its joint path (3 points per step of path.csv: 43
# points) and along the path itself, path points in blocks per rank, K = 1..4: the same CSV byte for
# byte and the same JSON apart from seconds and the "mpi" section (compare_reports.py), with and
# without --between samples (a segment at a block border owned by the earlier rank), --poses,
# --depth, and a cell with a clearance (clearance rows, min_distance); 2 points on 4 ranks (idle
# ranks, a warning); a probe pose path (--pose-path, inverse kinematics solved whole on every
# rank; --ik-start collision-free, --write-joints byte-equal); bad input exits 2 with the message
# (a bad path file, an unreachable pose, options not offered).
# Usage: run_mpi_cell_tests.sh INTERFERE INTERFERE_MPI EXAMPLES_PROBE_DIR
source "$(dirname "$0")/common.sh"
ex=$(realpath "$3")
cd "$work" || exit 1
cp "$ex"/cell.json "$ex"/arm6r.urdf "$ex"/workpiece.obj "$ex"/clamp.obj "$ex"/path.csv "$ex"/paper_path.csv .
cp -r "$ex"/meshes . 2>/dev/null
# The denser path: 2 points between each two of path.csv's (linear in the joints), 43 points.
"$py" - path.csv > dense.csv <<'PY'
import sys
lines = [l.strip() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
head, rows = lines[0], [[float(v) for v in l.split(",")] for l in lines[1:]]
print(head)
for i, r in enumerate(rows):
    print(",".join("%.9f" % v for v in r))
    if i + 1 < len(rows):
        for s in (1, 2):
            print(",".join("%.9f" % (a + s / 3 * (b - a)) for a, b in zip(r, rows[i + 1])))
PY
"$py" - cell.json > clear.json <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["clearance"] = 15
print(json.dumps(c))
PY
grep -v '^#' path.csv | head -1 > two.csv; grep -v '^#' path.csv | sed -n '2,3p' >> two.csv

same() {  # name, cell, ranks..., -- extra args...
  local name=$1 cell=$2; shift 2
  local ks=()
  while test "$1" != "--"; do ks+=("$1"); shift; done
  shift
  "$cli" cell "$cell" "$@" --csv "$name.single.csv" --json "$name.single.json" >"$name.single.txt" 2>/dev/null
  local want=$?
  check test -s "$name.single.json"
  for k in "${ks[@]}"; do
    "${mpirun_[@]}" -n "$k" "$mpi" cell "$cell" "$@" --csv "$name.mpi$k.csv" --json "$name.mpi$k.json" \
      >"$name.mpi$k.txt" 2>"$name.mpi$k.err"
    local rc=$?
    check test "$rc" = "$want"
    check cmp -s "$name.single.csv" "$name.mpi$k.csv"
    check "$py" "$here/compare_reports.py" "$name.single.json" "$name.mpi$k.json"
    check "$py" -c "import json,sys; m=json.load(open(sys.argv[1]))['mpi']; sys.exit(not (m['ranks']==$k and len(m['per_rank'])==$k))" "$name.mpi$k.json"
    check cmp -s <(grep -v '^(' "$name.mpi$k.txt") "$name.single.txt"  # (the summary, less "(K ranks)")
    echo "cell $name $* K=$k: rc=$rc (single $want)"
  done
}
same points cell.json 1 2 3 4 -- --path dense.csv
same between cell.json 1 2 3 4 -- --path dense.csv --between 2 --poses
same depth cell.json 2 3 -- --path path.csv --between 1 --depth
same clearance clear.json 1 2 3 4 -- --path dense.csv --between 3
same idle cell.json 4 -- --path two.csv --between 2
same ik cell.json 1 2 3 -- --pose-path paper_path.csv --between 1
same ikstart cell.json 3 -- --pose-path paper_path.csv --ik-start collision-free --write-joints ikstart.joints.csv
"$cli" cell cell.json --pose-path paper_path.csv --ik-start collision-free --write-joints single.joints.csv >/dev/null 2>&1
check test -s ikstart.joints.csv
check cmp -s single.joints.csv ikstart.joints.csv
check grep -q "ranks idle" idle.mpi4.err
# (the example collides: the comparisons above saw clash rows at a block's points and samples)
check grep -q ",clash," between.single.csv

# Bad input: every rank finds it, exit 2 and the message naming the file, nothing written.
printf 'shoulder_pan,shoulder_lift,elbow,wrist_1,wrist_2,wrist_3\n0,0,0,0,0,zero\n' > bad.csv
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --path bad.csv --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "bad.csv" bad.err
check test ! -e bad.json
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --path missing.csv --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "missing.csv" bad.err
check test ! -e bad.json
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --continuous --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --continuous: not offered" bad.err
printf 'px,py,pz,ax,ay,az\n400,0,10,0,0,-1\n# too far\n9000,0,10,0,0,-1\n' > far.csv
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --pose-path far.csv --json bad.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "far.csv:4:.*unreachable" bad.err
check test ! -e bad.json
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --pose-path paper_path.csv --path path.csv >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --pose-path excludes --path" bad.err
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --html v.html >/dev/null 2>bad.err
check test $? = 2
check grep -q "not offered" bad.err
"${mpirun_[@]}" -n 2 "$mpi" cell cell.json --json nofolder/r.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --json nofolder/r.json: no folder" bad.err
exit $fail
