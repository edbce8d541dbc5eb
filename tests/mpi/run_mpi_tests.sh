#!/usr/bin/env bash
# interfere-mpi against `interfere clash --scene` (issue #31, item 5): generated scenes (many tiny
# bodies; one huge body pair that dominates; the tiny scene with a motion file, 6 frames; an FE
# model with 4 displacement steps beside mesh bodies) on
# K = 1..4 ranks give reports equal to the single-process one (compare_reports.py: apart from
# timings, threads and the mpi section; core_runs included) and equal CSV tables; bad input: a rank that
# cannot read a body ends the job with exit 2, that rank's message and no report; ranks that see
# different inputs (checksum) exit 2; more ranks than bodies warn.
# Usage: run_mpi_tests.sh INTERFERE INTERFERE_MPI
source "$(dirname "$0")/common.sh"
# rank 0 also writes each report through its parsed document and stops (exit 2, "the report's text
# edit differs") unless that equals the text edit it writes otherwise (merge.cpp report_with_mpi)
export INTERFERE_MPI_CHECK_REPORT_EDIT=1
"$py" "$here/make_scenes.py" "$work" || exit 1

same() {  # scene dir, extra args...
  local d=$1; shift
  (cd "$d" && "$cli" clash --scene scene.json "$@" --json single.json --csv single.csv --quiet >/dev/null 2>&1)
  for k in 1 2 3 4; do
    (cd "$d" && "${mpirun_[@]}" -n $k "$mpi" clash --scene scene.json "$@" --json mpi$k.json --csv mpi$k.csv --quiet >/dev/null 2>"mpi$k.err")
    local rc=$?
    check test "$rc" = 1  # (both scenes clash: exit status 1, as `interfere clash`)
    check "$py" "$here/compare_reports.py" "$d/single.json" "$d/mpi$k.json"
    check cmp -s "$d/single.csv" "$d/mpi$k.csv"
    echo "$(basename "$d") $* K=$k: rc=$rc"
  done
}
same "$work/tiny"
same "$work/huge"
same "$work/tiny" --motion motion.csv --frames-csv frames.csv
same "$work/fe"  # (FE displacement steps, the reference configuration, designed contacts)
same "$work/repeats"  # (one file in many entries, repeated joints: core_runs as one process's)
# Options as `interfere clash --scene`: clash tests on the command line, FE options.
same "$work/tiny" --test "near: all clearance 0.2" --test "all hard"
same "$work/fe" --scale 2 --no-reference
check "$py" -c 'import json,sys; r=json.load(open(sys.argv[1])); sys.exit(r["summary"]["core_runs"] != 2)' "$work/repeats/single.json"

# A STEP assembly (instances sharing meshes, the nominal-fit rule) beside two mesh files, with a
# baseline (statuses carried) and grouping by location: K = 2, 3 (skipped in a build without STEP).
mkdir -p "$work/step"
cp "$here/../fuzz/corpus/read_step/assembly.step" "$here/../../data/examples/plate.stl" "$here/../../data/examples/pin.obj" "$work/step/"
cat > "$work/step/scene.json" <<'JSON'
{"units": "mm", "bodies": [{"file": "assembly.step", "id": "asm"}, {"file": "plate.stl", "id": "plate"},
  {"file": "pin.obj", "id": "pin", "transform": [1, 0, 0, 30, 0, 1, 0, 30, 0, 0, 1, 5]}]}
JSON
if (cd "$work/step" && "$cli" clash --scene scene.json --json base.json --quiet >/dev/null 2>&1; test $? = 1); then
  (cd "$work/step" && "$cli" clash --scene scene.json --baseline base.json --group-by location --json single.json --quiet >/dev/null 2>&1)
  for k in 2 3; do
    (cd "$work/step" && "${mpirun_[@]}" -n $k "$mpi" clash --scene scene.json --baseline base.json --group-by location --json mpi$k.json --quiet >/dev/null 2>&1)
    check "$py" "$here/compare_reports.py" "$work/step/single.json" "$work/step/mpi$k.json"
    echo "step --baseline --group-by location K=$k"
  done
  # Zero-clearance fits (08528bf: pairs of instances on coincident B-Rep faces are contacts of kind
  # zero_clearance_fit, also where the tessellations do not meet: the lifted cover is 1e-6 mm off
  # the plate, so their broad boxes need not overlap): the same report at K = 1..3, with the fits.
  mkdir -p "$work/fits"
  cp "$here/../cli/data/bolted_joint.step" "$here/../cli/data/bolted_joint_lifted.step" "$work/fits/"
  cat > "$work/fits/scene.json" <<'JSON'
{"units": "mm", "bodies": [{"file": "bolted_joint.step", "id": "j"},
  {"file": "bolted_joint_lifted.step", "id": "l", "transform": [1, 0, 0, 500, 0, 1, 0, 0, 0, 0, 1, 0]}]}
JSON
  (cd "$work/fits" && "$cli" clash --scene scene.json --json single.json --csv single.csv --quiet >/dev/null 2>&1)
  check test "$("$py" -c 'import json,sys; print(sum(c["kind"] == "zero_clearance_fit" for c in json.load(open(sys.argv[1]))["clashes"]) > 0)' "$work/fits/single.json")" = True
  for k in 1 2 3; do
    (cd "$work/fits" && "${mpirun_[@]}" -n $k "$mpi" clash --scene scene.json --json mpi$k.json --csv mpi$k.csv --quiet >/dev/null 2>&1)
    check "$py" "$here/compare_reports.py" "$work/fits/single.json" "$work/fits/mpi$k.json"
    check cmp -s "$work/fits/single.csv" "$work/fits/mpi$k.csv"
    echo "step zero-clearance fits K=$k"
  done
else
  echo "step: skipped (no STEP reader in this build)"
fi

# An option of `interfere clash` that interfere-mpi does not offer: exit 2, the reason, no work.
(cd "$work/tiny" && "${mpirun_[@]}" -n 2 "$mpi" clash --scene scene.json --json v.json --html v.html >/dev/null 2>notoffered.err)
rc=$?
check test "$rc" = 2
check grep -q -- "--html: not offered by interfere-mpi" "$work/tiny/notoffered.err"
check test ! -e "$work/tiny/v.json"
echo "not offered (--html): rc=$rc"

# The CLI's conventions (issue #30, item 5): --help with the exit statuses and --version on stdout, exit 0;
# a usage error with the "interfere: error:" prefix, exit 2.
"${mpirun_[@]}" -n 1 "$mpi" --help >"$work/help.txt" 2>&1
check test $? = 0
check grep -q "^Exit status: 0 clear" "$work/help.txt"
"${mpirun_[@]}" -n 2 "$mpi" clash --version >"$work/version.txt" 2>&1
check test $? = 0
check grep -q "^interfere-mpi [0-9]" "$work/version.txt"
check test "$(grep -c '^interfere-mpi ' "$work/version.txt")" = 1
(cd "$work/tiny" && "${mpirun_[@]}" -n 2 "$mpi" clash --scene scene.json --bogus >/dev/null 2>bogus.err)
check test $? = 2
check grep -q "^interfere: error: unknown option --bogus" "$work/tiny/bogus.err"
echo "conventions: help, version, error prefix"

# A rank that cannot read a body: exit 2, its message, no report.
(cd "$work/broken" && "${mpirun_[@]}" -n 3 "$mpi" clash --scene scene.json --json out.json >/dev/null 2>err.txt)
rc=$?
check test "$rc" = 2
check grep -q "interfere: error: rank [0-9]*: bad.stl:4: malformed number" "$work/broken/err.txt"
check test ! -e "$work/broken/out.json"
echo "broken: rc=$rc"

# A rank out of memory (--memory-limit 4: 4 MB of address space a rank beyond its start, less than
# a 40,000-triangle body needs): exit 2, that rank's message, no report, no hang.
(cd "$work/huge" && "${mpirun_[@]}" -n 2 "$mpi" clash --scene scene.json --json oom.json --memory-limit 4 >/dev/null 2>oom.err)
rc=$?
check test "$rc" = 2
check grep -q "^interfere: error: rank [0-9]*: .*out of memory" "$work/huge/oom.err"
check test ! -e "$work/huge/oom.json"
echo "out of memory: rc=$rc"

# Ranks that see different inputs (here: different command lines): exit 2, no report.
(cd "$work/tiny" && "${mpirun_[@]}" -n 1 "$mpi" clash --scene scene.json --json x.json : -n 1 "$mpi" clash --scene scene.json --json y.json >/dev/null 2>mismatch.err)
rc=$?
check test "$rc" = 2
check grep -q "sees other inputs than rank 0" "$work/tiny/mismatch.err"
check test ! -e "$work/tiny/x.json"
echo "checksum mismatch: rc=$rc"

# Entries whose files are missing (each rank checks only its share of the entries, every K-th):
# exit 2 and the message of one process (the first missing file in file order), no report.
cat > "$work/broken/missing.json" <<'JSON'
{"bodies": [{"file": "ok1.stl", "id": "ok1"}, {"file": "ok2.stl", "id": "ok2"}, {"file": "gone1.stl", "id": "g1"},
            {"file": "sub/gone2.stl", "id": "g2"}]}
JSON
(cd "$work/broken" && "$cli" clash --scene missing.json --json m.json >/dev/null 2>missing1.err)
check test $? = 2
check grep -q "^interfere: error: missing.json: bodies\[2\].file: file 'gone1.stl' not found" "$work/broken/missing1.err"
for k in 2 3 4; do
  (cd "$work/broken" && "${mpirun_[@]}" -n $k "$mpi" clash --scene missing.json --json m.json >/dev/null 2>missing$k.err)
  rc=$?
  check test "$rc" = 2
  check test "$(grep '^interfere: error' "$work/broken/missing$k.err")" = "$(grep '^interfere: error' "$work/broken/missing1.err")"
  check test ! -e "$work/broken/m.json"
done
echo "missing files: rc=$rc"

# More ranks than bodies: a warning, and the report.
cat > "$work/broken/two.json" <<'JSON'
{"bodies": [{"file": "ok1.stl", "id": "ok1"}, {"file": "ok2.stl", "id": "ok2"}]}
JSON
(cd "$work/broken" && "${mpirun_[@]}" -n 3 "$mpi" clash --scene two.json --json two.json.out >/dev/null 2>two.err)
rc=$?
check test "$rc" = 1
check grep -q "3 ranks for 2 bodies: 1 ranks stay idle" "$work/broken/two.err"
check test -s "$work/broken/two.json.out"
echo "more ranks than bodies: rc=$rc"
exit $fail
