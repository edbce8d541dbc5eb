# What the MPI test scripts share (tests/mpi/*.sh; issue #31), sourced first thing with the
# script's own arguments (`source "$(dirname "$0")/common.sh"`, $1 INTERFERE and $2 INTERFERE_MPI):
#   cli, mpi   the two executables' absolute paths
#   py         the Python with numpy (/usr/bin/python3)
#   here       this folder (tests/mpi)
#   work       a fresh temporary folder, removed on exit
#   mpirun_    mpirun as root, oversubscribed (more ranks than cores), with the shared-memory
#              transport's single-copy mechanism off (containers)
#   fail, check CMD...   CMD run; on failure "FAILED: CMD" printed and fail=1 (the script ends with exit $fail)
#   same_frames_outputs DIR K SRC RC   a --distribute frames run on K ranks (mpiK.json, mpiK.csv,
#              mpiK_f.csv, mpiK_p.csv in DIR, exit status RC) against the one process's (single*, SRC)
set -uo pipefail
cli=$(realpath "$1") mpi=$(realpath "$2")
py=/usr/bin/python3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mpirun_=(mpirun --allow-run-as-root --oversubscribe)
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
fail=0
check() { if "$@"; then :; else echo "FAILED: $*"; fail=1; fi; }

same_frames_outputs() {
  local d=$1 k=$2 src=$3 rc=$4
  check test "$rc" = "$src"
  check "$py" "$here/compare_reports.py" "$d/single.json" "$d/mpi$k.json"
  check cmp -s "$d/single.csv" "$d/mpi$k.csv"
  check cmp -s "$d/single_f.csv" "$d/mpi${k}_f.csv"
  check cmp -s "$d/single_p.csv" "$d/mpi${k}_p.csv"
}
