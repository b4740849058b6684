#!/usr/bin/env bash
# check.sh <signorini> <base.prm> [steps [tolerance [geometric tolerance]]]
# Newton on the geometry (of a rigid obstacle, or the pairing of a meshed
# master) against the fixed-point geometric loop: runs <base.prm> with
# 'Contact/Geometric linearisation' = newton and = fixed point (with
# 'Geometric tolerance' = <geometric tolerance> if given), prints the run
# summaries, and requires both runs to pass their reference checks and to
# give the same contact pressures (to <tolerance> of the largest, default
# 5e-3: the fixed point stops at 'Geometric tolerance') and the same
# statuses at the load steps <steps> (default "0010 0030 0050").
set -u
exe="$(realpath "$1")"; base="$(realpath "$2")"
steps="${3:-0010 0030 0050}"; tolerance="${4:-5e-3}"; geometric="${5:-}"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
status=0
for mode in newton "fixed point"; do
  tag=${mode// /_}
  { cat "$base"
    printf 'subsection Contact\n  set Geometric linearisation = %s\nend\n' "$mode"
    [ "$mode" = "fixed point" ] && [ -n "$geometric" ] &&
      printf 'subsection Contact\n  set Geometric tolerance = %s\nend\n' "$geometric"
    printf 'subsection Output\n  set Directory = %s\nend\n' "$dir/$tag"; } > "$tag.prm"
  if ! "$exe" "$tag.prm" > "$tag.log" 2>&1; then
    tail -5 "$tag.log"; echo "FAIL: '$mode' did not run to the end"; exit 1
  fi
  echo "$mode: $(grep -E "^Run summary|^  Newton iterations" "$tag.log" | tail -1)"
  if grep -q "FAIL$" "$tag.log"; then
    grep "FAIL$" "$tag.log" | head -3; echo "FAIL: a reference check of '$mode' failed"; status=1
  else
    echo "$mode: $(grep -c 'reference check: .*PASS$' "$tag.log") reference checks pass"
  fi
done
for step in $steps; do
  paste -d, "newton/contact_$step.csv" "fixed_point/contact_$step.csv" | awk -F, -v step="$step" -v tol="$tolerance" '
    NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) if ($i == "p") ip = i; else if ($i == "status") is = i; next }
    { p = $ip < 0 ? -$ip : $ip; if (p > pmax) pmax = p
      d = $ip - $(ip + n); if (d < 0) d = -d; if (d > dmax) dmax = d
      if ($is != $(is + n)) bad++; rows++ }
    END { r = pmax > 0 ? dmax / pmax : 1
          printf "step %s: largest pressure difference %.1e of the largest pressure, %d status differences\n", step, r, bad
          exit (rows > 0 && r <= tol && bad == 0) ? 0 : 1 }' || status=1
done
[ $status -eq 0 ] && echo "PASS: the same solution with the geometry in Newton and in the fixed-point loop" || echo "FAIL"
exit $status
