#!/usr/bin/env bash
# The Slurm batch script of docs/mpi.md (issue #31, item 6: "a Slurm batch script example") run as
# written, taken from the page itself so that the page and the test cannot drift apart, on this
# machine: Slurm is not installed here, so a stand-in `srun` starts the job with mpirun on
# $SLURM_NTASKS ranks (dropping srun's own options such as --cpu-bind) and `module` does nothing.
# The report it writes must equal `interfere clash --scene` on the same scene (compare_reports.py).
# This checks the script's command line and its use of the Slurm variables, not Slurm itself.
# Usage: run_slurm_example.sh INTERFERE INTERFERE_MPI DOCS_MPI_MD
source "$(dirname "$0")/common.sh"
doc=$(realpath "$3")
"$py" "$here/make_scenes.py" "$work" >/dev/null || exit 1
# the fenced block that holds the #SBATCH lines
"$py" - "$doc" "$work/job.sh" <<'PY' || exit 1
import re, sys
text = open(sys.argv[1]).read()
blocks = re.findall(r"^```[^\n]*\n(.*?)^```", text, re.S | re.M)
jobs = [b for b in blocks if "#SBATCH" in b]
if len(jobs) != 1:
    sys.exit(f"expected one block with #SBATCH lines in {sys.argv[1]}, found {len(jobs)}")
open(sys.argv[2], "w").write(jobs[0])
PY
mkdir -p "$work/bin"
ln -s "$mpi" "$work/bin/interfere-mpi"
cat > "$work/bin/srun" <<'SH'
#!/usr/bin/env bash
# stand-in for Slurm's srun: its options dropped, the program started on $SLURM_NTASKS ranks
while [ $# -gt 0 ] && [ "${1#-}" != "$1" ]; do shift; done
exec mpirun --allow-run-as-root --oversubscribe -n "$SLURM_NTASKS" "$@"
SH
printf '#!/bin/sh\nexit 0\n' > "$work/bin/module"
chmod +x "$work/bin/srun" "$work/bin/module"
d="$work/tiny"
cp "$d/scene.json" "$d/product.json"
(cd "$d" && "$cli" clash --scene product.json --json single.json --quiet >/dev/null 2>&1)
(cd "$d" && PATH="$work/bin:$PATH" SLURM_NTASKS=2 SLURM_CPUS_PER_TASK=1 bash "$work/job.sh" >job.out 2>&1)
rc=$?
if [ "$rc" != 1 ]; then  # (the scene clashes: exit status 1, as `interfere clash`)
  echo "FAILED: the batch script exited $rc, expected 1"; cat "$d/job.out"; exit 1
fi
"$py" "$here/compare_reports.py" "$d/single.json" "$d/report.json" || { echo "FAILED: reports differ"; exit 1; }
"$py" -c 'import json,sys; r=json.load(open(sys.argv[1])); sys.exit(r["mpi"]["ranks"] != 2)' "$d/report.json" ||
  { echo "FAILED: the report does not say 2 ranks"; exit 1; }
echo "slurm example (stand-in srun, 2 ranks): report equal to the single process"
