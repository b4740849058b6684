#!/usr/bin/env bash
# failed_step_history.sh <signorini> <file.prm> <ranks> <mpiexec>
# The iterates of failed attempts are in newton_history.csv, also those of
# the attempt after which the run stops: the scene's last step fails after
# its step cuts (the run stops with exit code 2 and "load step N did not
# converge between t = A and t = B after K step cuts"); the history must
# end with the rows of step N, K + 1 attempts (distinct target times), the
# last at t = B, none of them converged, and be complete (check_files.py).
set -u
exe="$1"; prm="$2"; np="$3"; mpiexec="${4:-mpiexec}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
if [ "$np" -gt 1 ]; then
  "$mpiexec" -n "$np" --allow-run-as-root "$exe" "$prm" > out.txt 2>&1; rc=$?
else
  "$exe" "$prm" > out.txt 2>&1; rc=$?
fi
if [ $rc -ne 2 ]; then echo "FAIL: exit code $rc, expected 2"; tail -5 out.txt; exit 1; fi
/usr/bin/python3 "$here/check_files.py" results || exit 1
/usr/bin/python3 - out.txt results/newton_history.csv <<'PY'
import csv, re, sys
text = open(sys.argv[1]).read()
m = re.search(r"load step (\d+) did not converge between t = (\S+) and t = (\S+) after (\d+) step cuts", text)
if not m:
    print("FAIL: no 'did not converge' message"); sys.exit(1)
step, t_end, cuts = int(m.group(1)), float(m.group(3)), int(m.group(4))
rows = list(csv.DictReader(open(sys.argv[2])))
last = [r for r in rows if int(r["step"]) == step]
times = []
for r in last:
    if not times or float(r["time"]) != times[-1]:
        times.append(float(r["time"]))
fails = []
if not last or rows[-1] is not last[-1]:
    fails.append("newton_history.csv does not end with step %d" % step)
if len(times) != cuts + 1:
    fails.append("step %d: %d attempts in newton_history.csv, expected %d (%d cuts)" % (step, len(times), cuts + 1, cuts))
if times and abs(times[-1] - t_end) > 1e-4 * abs(t_end):
    fails.append("last attempt at t = %g, the message says %g" % (times[-1], t_end))
if any(r["converged"] != "0" for r in last):
    fails.append("a row of the failed step says converged")
for f in fails:
    print("FAIL: " + f)
if fails:
    sys.exit(1)
print("PASS: step %d failed: its %d attempts (%d rows, last at t = %g) are in newton_history.csv"
      % (step, len(times), len(last), times[-1]))
PY
