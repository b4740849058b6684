#!/usr/bin/env bash
# check.sh <signorini> <base.prm>
# Release extrapolation (doc/robustness.md) changes the path of the
# active-set search, not its end: runs <base.prm> with
# 'Contact/Release extrapolation' = true and = false, prints the Newton
# iterations of both, and requires both runs to pass their reference checks
# and to give the same contact pressures (to 1e-8 of the largest) and the
# same statuses at every point of the last load step.
set -u
exe="$(realpath "$1")"; base="$(realpath "$2")"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
status=0
for mode in true false; do
  { cat "$base"
    printf 'subsection Contact\n  set Release extrapolation = %s\nend\n' "$mode"
    printf 'subsection Output\n  set Directory = %s\n  set Write VTU = false\nend\n' "$dir/$mode"; } > "$mode.prm"
  if ! "$exe" "$mode.prm" > "$mode.log" 2>&1; then
    tail -5 "$mode.log"; echo "FAIL: extrapolation $mode did not run to the end"; exit 1
  fi
  echo "extrapolation $mode: $(grep -E "^  Newton iterations" "$mode.log" | awk '{ s += $3 } END { print s }') Newton iterations, $(grep -c "release extrapolation:" "$mode.log") solve(s) with points opened early"
  if grep -q "FAIL$" "$mode.log"; then
    grep "FAIL$" "$mode.log" | head -3; echo "FAIL: a reference check with extrapolation $mode failed"; status=1
  else
    echo "extrapolation $mode: $(grep -c 'reference check: .*PASS$' "$mode.log") reference checks pass"
  fi
done
last="$(ls true/contact_*.csv | tail -1)"; last="${last##*/}"
paste -d, "true/$last" "false/$last" | awk -F, -v tol=1e-8 '
  NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) if ($i == "p") ip = i; else if ($i == "status") is = i; next }
  { p = $ip < 0 ? -$ip : $ip; if (p > pmax) pmax = p
    d = $ip - $(ip + n); if (d < 0) d = -d; if (d > dmax) dmax = d
    if ($is != $(is + n)) bad++; rows++ }
  END { r = pmax > 0 ? dmax / pmax : 1
        printf "%d points: largest pressure difference %.1e of the largest pressure (bar %.0e), %d status differences\n", rows, r, tol, bad
        exit (rows > 0 && r <= tol && bad == 0) ? 0 : 1 }' || status=1
[ $status -eq 0 ] && echo "PASS: the same contact state with and without release extrapolation" || echo "FAIL"
exit $status
