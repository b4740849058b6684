#!/usr/bin/env bash
# stale_files.sh <signorini> <scene.prm>
# Results of an earlier run are not mixed with the new ones: a 4-step run,
# then a 2-step run in the same directory. The second removes exactly the
# first's result files (and says how many), keeps every other file (a
# user's notes, files named almost like results, a symbolic link), and
# leaves a complete 2-step result set.
set -u
exe="$1"; prm="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
steps() { /usr/bin/python3 "$here/../../scripts/prm-set" "$prm" "Load stepping/Number of steps=$1" > "run$1.prm"; }
steps 4 && steps 2 || exit 1
"$exe" run4.prm > out4.txt 2>&1 || { echo "FAIL: the 4-step run failed"; tail -3 out4.txt; exit 1; }
# 4 x (contact CSV, VTU, PVTU, surface VTU, surface PVTU) + solution.pvd,
# contact_surface.pvd, statistics.csv, newton_history.csv
removed=24
keep="notes.txt solution_final.vtu contact_summary.csv statistics.csv.bak my_solution_0001.pvtu contact_0009.csv"
for f in $keep; do [ "$f" = contact_0009.csv ] || echo "user file" > "results/$f"; done
ln -s notes.txt results/contact_0009.csv
"$exe" run2.prm > out2.txt 2>&1 || { echo "FAIL: the 2-step run failed"; tail -3 out2.txt; exit 1; }
expect="Removed $removed result file(s) of an earlier run from 'results'"
if [ "$(grep -cxF -- "$expect" out2.txt)" -ne 1 ]; then
  echo "FAIL: expected once: $expect"; head -3 out2.txt; exit 1
fi
for f in $keep; do
  [ -e "results/$f" ] || { echo "FAIL: results/$f was removed"; exit 1; }
done
echo "PASS: $expect; kept: $keep"
rm -f results/contact_0009.csv # the link is not a result of the 2-step run
/usr/bin/python3 "$here/check_files.py" results 2
