#!/usr/bin/env bash
# check.sh <signorini> <base.prm> <tolerance> <label A> <settings A> <label B> <settings B>
# Two settings that change the path of the Newton / active-set search, not
# its end (doc/robustness.md: release extrapolation, pairing at status
# changes, line search, the initial status): runs <base.prm> with settings
# A and with settings B ('Subsection/Entry=value' entries for
# scripts/prm-set, separated by newlines: printf %b escapes, so '\n'),
# prints the Newton iterations and step cuts of both, and requires of both
# runs
#   - every reference check passes and no load step is cut;
# and between them, at every point of the last load step,
#   - the same contact pressure and tangential traction, to <tolerance> of
#     the largest pressure;
#   - the same status (free / stick / slip).
set -u
exe="$(realpath "$1")"; base="$(realpath "$2")"; tol="$3"
labels=("$4" "$6"); texts=("$5" "$7")
prm_set="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)/prm-set"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
status=0
for k in 0 1; do
  mapfile -t sets < <(printf '%b\n' "${texts[$k]}" | grep -v '^[[:space:]]*$')
  /usr/bin/python3 "$prm_set" "$base" "${sets[@]}" "Output/Directory=$dir/run$k" \
    "Output/Postprocessors=reference checks" > "run$k.prm" || exit 1
  if ! "$exe" "run$k.prm" > "run$k.log" 2>&1; then
    tail -5 "run$k.log"; echo "FAIL: ${labels[$k]}: did not run to the end"; exit 1
  fi
  newton=$(grep -E "^  Newton iterations" "run$k.log" | awk '{ s += $3 } END { print s }')
  cuts=$(grep -c "step not converged: cut" "run$k.log")
  echo "${labels[$k]}: $newton Newton iterations, $cuts step cut(s), $(grep -c "release extrapolation:" "run$k.log") solve(s) with points opened early, $(grep -c "(paired again)" "run$k.log") pairing(s) at status changes, $(grep -c "line search:" "run$k.log") line search(es)"
  if grep -q "FAIL$" "run$k.log"; then
    grep "FAIL$" "run$k.log" | head -3; echo "FAIL: a reference check of ${labels[$k]} failed"; status=1
  else
    echo "${labels[$k]}: $(grep -c 'reference check: .*PASS$' "run$k.log") reference checks pass"
  fi
  if [ "$cuts" -gt 0 ]; then
    echo "FAIL: ${labels[$k]}: $cuts step cut(s)"; status=1
  fi
done
last="$(ls run0/contact_*.csv | tail -1)"; last="${last##*/}"
paste -d, "run0/$last" "run1/$last" | awk -F, -v tol="$tol" '
  NR == 1 { n = NF / 2; nt = 0
            for (i = 1; i <= n; ++i) {
              if ($i == "p") ip = i; else if ($i == "status") is = i
              else if ($i ~ /^traction_t/) it[++nt] = i }
            next }
  { p = $ip < 0 ? -$ip : $ip; if (p > pmax) pmax = p
    d = $ip - $(ip + n); if (d < 0) d = -d; if (d > dmax) dmax = d
    for (k = 1; k <= nt; ++k) {
      d = $(it[k]) - $(it[k] + n); if (d < 0) d = -d; if (d > tmax) tmax = d }
    if ($is != $(is + n)) bad++; rows++ }
  END { r = pmax > 0 ? dmax / pmax : 1; rt = pmax > 0 ? tmax / pmax : 1
        printf "%d points: largest pressure difference %.1e, tangential traction difference %.1e of the largest pressure (bar %.0e), %d status differences\n", rows, r, rt, tol, bad
        exit (rows > 0 && r <= tol && rt <= tol && bad == 0) ? 0 : 1 }' || status=1
[ $status -eq 0 ] && echo "PASS: the same contact state with ${labels[0]} and ${labels[1]}" || echo "FAIL"
exit $status
