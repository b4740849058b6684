#!/usr/bin/env bash
# kill.sh <signorini> <scene.prm> <ranks> <mpiexec>
# No lost output after a kill: a run of many load steps (VTU, contact CSV,
# statistics) is killed with SIGKILL once some steps are on disk, while it
# writes a file if it can be caught at it (kill_during_write.py); every
# result file left must be complete and parseable (check_files.py). Then a
# 2-step run in the same directory removes the killed run's files (the
# count is printed) and leaves exactly its own complete results.
set -u
exe="$1"; prm="$2"; np="$3"; mpiexec="${4:-mpiexec}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
# exec: in the background the pid is then the run's (mpirun's) own.
run() {
  if [ "$np" -gt 1 ]; then
    exec "$mpiexec" -n "$np" --allow-run-as-root "$exe" "$1"
  else
    exec "$exe" "$1"
  fi
}
run "$prm" > killed.txt 2>&1 &
pid=$!
/usr/bin/python3 "$here/kill_during_write.py" "$pid" results 8 "$np"
caught=$?
wait "$pid" 2>/dev/null
[ $caught -eq 0 ] || { tail -5 killed.txt; exit 1; }
/usr/bin/python3 "$here/check_files.py" results || exit 1

# Files of this program's patterns the next run must remove (regular files,
# temporary names included).
stale="$(find results -maxdepth 1 -type f -regextype posix-extended -regex \
  '.*/(((solution|contact_surface)_[0-9]+\.[0-9]+\.vtu|(solution|contact_surface)_[0-9]+\.pvtu|(solution|contact_surface)\.pvd|contact_[0-9]+\.csv|statistics\.csv|newton_history\.csv)(\.tmp)?|parameters\.prm\.tmp)' | wc -l)"
/usr/bin/python3 "$here/../../scripts/prm-set" "$prm" "Load stepping/Number of steps=2" \
  > two_steps.prm || exit 1
(run two_steps.prm) > rerun.txt 2>&1; rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: the 2-step run exited with code $rc"; tail -5 rerun.txt; exit 1; fi
expect="Removed $stale result file(s) of an earlier run from 'results'"
if [ "$(grep -cxF -- "$expect" rerun.txt)" -ne 1 ]; then
  echo "FAIL: expected the line once: $expect"; head -5 rerun.txt; exit 1
fi
echo "$expect"
/usr/bin/python3 "$here/check_files.py" results 2 || exit 1
