#!/usr/bin/env bash
# partial_step.sh <signorini> <mpiexec> <ranks>
# A run that stops in a load step keeps what converged: partial_step.prm's
# step 2 converges to its sub-step t = 0.75 and then fails after its cuts.
# Expected: exit code 2; the message says the last converged sub-step is
# written; statistics.csv ends with step 2 at t = 0.75 and the files are
# complete (check_files.py); the run summary is printed ("stopped in load
# step 2 of 2: 2 load step(s) written").
set -u
exe="$1"; mpiexec="$2"; np="$3"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
"$mpiexec" -n "$np" --allow-run-as-root "$exe" "$here/partial_step.prm" > out.txt 2>&1; rc=$?
status=0
if [ $rc -ne 2 ]; then echo "FAIL: exit code $rc, expected 2"; tail -5 out.txt; exit 1; fi
grep -q "The results of the completed steps and of the last converged sub-step are in 'results'" out.txt ||
  { echo "FAIL: the message does not mention the written sub-step"; tail -3 out.txt; status=1; }
grep -q "^Run summary (stopped in load step 2 of 2): 2 load step(s) written" out.txt ||
  { echo "FAIL: no run summary of the stopped run"; status=1; }
/usr/bin/python3 "$here/check_files.py" results || status=1
last="$(tail -1 results/statistics.csv | cut -d, -f1,2)"
if [ "$last" != "2,7.500000e-01" ]; then
  echo "FAIL: statistics.csv ends with '$last', expected step 2 at t = 0.75"; status=1
fi
reaction="$(tail -1 results/statistics.csv | cut -d, -f9)"
if [ "$reaction" != "7.500000e+04" ]; then
  echo "FAIL: reaction_1_y of the written sub-step is '$reaction', expected the load 7.500000e+04 (forces of the failed attempt?)"; status=1
fi
[ $status -eq 0 ] && echo "PASS: exit code 2, step 2 written at t = 0.75 (its last converged sub-step), run summary printed, files complete"
exit $status
