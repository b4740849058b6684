#!/usr/bin/env bash
# check.sh <signorini> <base.prm> [<Contact parameter> <tolerance> [<prm text>]]
# Release extrapolation and the pairing at status changes
# (doc/robustness.md) change the path of the active-set search, not its
# end: runs <base.prm> with the Contact parameter (default 'Release
# extrapolation') = true and = false, prints the Newton iterations of both,
# and requires both runs to pass their reference checks and to give the
# same contact pressures (to <tolerance> of the largest, default 1e-8) and
# the same statuses at every point of the last load step. The optional
# prm text (printf %b escapes) is appended to both runs.
set -u
exe="$(realpath "$1")"; base="$(realpath "$2")"
param="${3:-Release extrapolation}"; tol="${4:-1e-8}"; extra="${5:-}"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
status=0
for mode in true false; do
  { cat "$base"
    printf 'subsection Contact\n  set %s = %s\nend\n' "$param" "$mode"
    printf '%b\n' "$extra"
    printf 'subsection Output\n  set Directory = %s\n  set Write VTU = false\nend\n' "$dir/$mode"; } > "$mode.prm"
  if ! "$exe" "$mode.prm" > "$mode.log" 2>&1; then
    tail -5 "$mode.log"; echo "FAIL: $param $mode did not run to the end"; exit 1
  fi
  echo "$param $mode: $(grep -E "^  Newton iterations" "$mode.log" | awk '{ s += $3 } END { print s }') Newton iterations, $(grep -c "release extrapolation:" "$mode.log") solve(s) with points opened early, $(grep -c "(paired again)" "$mode.log") pairing(s) at status changes"
  if grep -q "FAIL$" "$mode.log"; then
    grep "FAIL$" "$mode.log" | head -3; echo "FAIL: a reference check with $param $mode failed"; status=1
  else
    echo "$param $mode: $(grep -c 'reference check: .*PASS$' "$mode.log") reference checks pass"
  fi
done
last="$(ls true/contact_*.csv | tail -1)"; last="${last##*/}"
paste -d, "true/$last" "false/$last" | awk -F, -v tol="$tol" '
  NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) if ($i == "p") ip = i; else if ($i == "status") is = i; next }
  { p = $ip < 0 ? -$ip : $ip; if (p > pmax) pmax = p
    d = $ip - $(ip + n); if (d < 0) d = -d; if (d > dmax) dmax = d
    if ($is != $(is + n)) bad++; rows++ }
  END { r = pmax > 0 ? dmax / pmax : 1
        printf "%d points: largest pressure difference %.1e of the largest pressure (bar %.0e), %d status differences\n", rows, r, tol, bad
        exit (rows > 0 && r <= tol && bad == 0) ? 0 : 1 }' || status=1
[ $status -eq 0 ] && echo "PASS: the same contact state with $param true and false" || echo "FAIL"
exit $status
