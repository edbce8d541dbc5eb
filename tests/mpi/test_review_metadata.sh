#!/usr/bin/env bash
# Review of 8b228c5 (issue #31): interfere-mpi clash (by body pairs) on review_make_metadata_scene.py's
# scene, whose bodies use every field the flat body records abbreviate behind flags and repeated meshes
# (classes): K = 1..4 reports equal to one process (compare_reports.py, core_runs included) and the
# CSV byte for byte. Usage: test_review_metadata.sh INTERFERE INTERFERE_MPI
source "$(dirname "$0")/common.sh"
export INTERFERE_MPI_CHECK_REPORT_EDIT=1  # (a07cf4d: rank 0 also builds the report's text the slow way and compares)
"$py" "$here/review_make_metadata_scene.py" "$work" || exit 1
(cd "$work" && "$cli" clash --scene scene.json --json single.json --csv single.csv --quiet >/dev/null 2>&1)
src=$?
for k in 1 2 3 4; do
  for group in none pair; do
    (cd "$work" && "$cli" clash --scene scene.json --group-by $group --json single_$group.json --csv single_$group.csv --quiet >/dev/null 2>&1)
    (cd "$work" && timeout 300 "${mpirun_[@]}" -n $k "$mpi" clash --scene scene.json --group-by $group --json mpi$k.json \
       --csv mpi$k.csv --quiet >/dev/null 2>mpi$k.err)
    rc=$?
    check test "$rc" = "$src"
    check "$py" "$here/compare_reports.py" "$work/single_$group.json" "$work/mpi$k.json"
    check cmp -s "$work/single_$group.csv" "$work/mpi$k.csv"
    echo "metadata scene K=$k group-by $group: rc=$rc (single $src)"
  done
done
exit $fail
