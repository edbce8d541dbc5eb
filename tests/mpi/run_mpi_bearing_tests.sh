#!/usr/bin/env bash
# interfere-mpi bearing against `interfere bearing --assembly` (issue #31, items 3 and 5): the bundled
# bearing example's frames in blocks per rank, K = 1..4 (also 3 frames on 4 ranks: an idle rank, a
# warning), generated motion and a motion file: the same CSV byte for byte and the same JSON apart
# from timing, threads, seconds and the "mpi" section (which validates against
# docs/schema/bearing.schema.json); bad input exits 2 with the message (outputs checked first).
# Usage: run_mpi_bearing_tests.sh INTERFERE INTERFERE_MPI ASSEMBLY.json
source "$(dirname "$0")/common.sh"
asm=$(realpath "$3")
export HERE=$here
cd "$work" || exit 1

same_json() {  # single.json mpi.json ranks
  "$py" - "$@" <<'PY'
import json, os, sys
sys.path.insert(0, os.path.join(os.environ["HERE"], "..", "cli"))
import report_schema  # (the "mpi" section against docs/schema/bearing.schema.json)
a, b = (json.load(open(p)) for p in sys.argv[1:3])
try:
    report_schema.validate(b, sys.argv[2])
except AssertionError as e:
    print(e)
    sys.exit(1)
m = b.pop("mpi", None)
ok = m is not None and m["ranks"] == int(sys.argv[3]) and len(m["per_rank"]) == int(sys.argv[3])
for r in (a, b):
    for k in ("timing", "threads", "seconds", "timings_s"):
        r.pop(k, None)
    r.get("options", {}).pop("threads", None)
    r.get("result", {}).pop("timing", None)
if a != b or not ok:
    print("JSON differs:", sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k)), "mpi ok" if ok else "mpi section wrong")
    sys.exit(1)
PY
}

same() {  # name, extra args...
  local name=$1; shift
  "$cli" bearing --assembly "$asm" "$@" --out "$name.single.csv" --json "$name.single.json" >/dev/null 2>&1
  local want=$?
  for k in 1 2 3 4; do
    "${mpirun_[@]}" -n $k "$mpi" bearing --assembly "$asm" "$@" --out "$name.mpi$k.csv" --json "$name.mpi$k.json" \
      >/dev/null 2>"$name.mpi$k.err"
    local rc=$?
    check test "$rc" = "$want"  # (the example clashes: exit status 1 as `interfere bearing`)
    check cmp -s "$name.single.csv" "$name.mpi$k.csv"
    check same_json "$name.single.json" "$name.mpi$k.json" $k
    echo "bearing $name $* K=$k: rc=$rc (single $want)"
  done
}
same default                       # (12 frames: blocks of 12, 6, 4 and 3 frames)
same seeded --frames 5 --seed 7 --clearance 0.5
same few --frames 3                # (K = 4: one rank idle)
check grep -q "ranks idle" few.mpi4.err
# A motion file: five frames moving the first bearing's cage along x (a part a frame does not list
# keeps its previous pose, initially its rest pose).
"$py" - "$asm" > motion.csv <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))["bearings"][0]["id"]
print("frame,body,r00,r01,r02,tx,r10,r11,r12,ty,r20,r21,r22,tz")
for f in range(5):
    print("%d,%s/cage,1,0,0,%g,0,1,0,0,0,0,1,0" % (f, b, 0.01 * f))
PY
"$cli" bearing --assembly "$asm" --motion motion.csv --out probe.csv >/dev/null 2>&1
if test -s probe.csv; then  # (exit status 3: the cage moved off its pocket line gives undecided rows)
  same motion --motion motion.csv
else
  echo "FAILED: the motion file was not accepted by interfere bearing"; fail=1
fi

# Bad input: every rank finds it, exit 2 and the message, nothing written.
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly missing.json --out bad.csv >/dev/null 2>bad.err
check test $? = 2
check grep -q "missing.json" bad.err
check test ! -e bad.csv
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly "$asm" --frames 0 --out bad.csv >/dev/null 2>bad.err
check test $? = 2
check grep -q -- "--frames" bad.err
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly "$asm" --html v.html >/dev/null 2>bad.err
check test $? = 2
check grep -q "not offered" bad.err
# Outputs checked before any work (the folder must exist), options read with CLI11: a missing value
# and a bad number name their flag; exit 2, nothing written.
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly "$asm" --out nofolder/rows.csv --json ok.json >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --out nofolder/rows.csv: no folder" bad.err
check test ! -e ok.json
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly "$asm" --frames >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --frames:" bad.err
"${mpirun_[@]}" -n 2 "$mpi" bearing --assembly "$asm" --clearance wide >/dev/null 2>bad.err
check test $? = 2
check grep -q "^interfere: error: --clearance: 'wide' is not a finite number" bad.err
exit $fail
