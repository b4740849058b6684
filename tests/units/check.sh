#!/usr/bin/env bash
# check.sh <signorini> <si.prm> <mm.prm>
# Unit invariance: the same problem in [m, N, Pa] and [mm, N, MPa] must give
# the same contact state. Compares the last contact CSVs row by row after
# scaling (x: 1e3, p and traction: 1e-6, gap and slip: 1e3): the largest
# difference relative to the largest value of each column must be <= 1e-8,
# and the statuses equal.
set -u
exe="$(realpath "$1")"; si="$(realpath "$2")"; mm="$(realpath "$3")"
prm_set="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)/prm-set"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
for u in si mm; do
  prm="$si"; [ "$u" = mm ] && prm="$mm"
  /usr/bin/python3 "$prm_set" "$prm" "Output/Directory=$dir/$u" > "$u.prm" || exit 1
  "$exe" "$u.prm" > "$u.log" 2>&1 || { cat "$u.log"; echo "FAIL: $u run"; exit 1; }
  grep -E "Newton iterations|contact pair" "$u.log" | sed "s/^/$u: /"
done
csv_si="$(ls si/contact_*.csv | tail -1)"; csv_mm="$(ls mm/contact_*.csv | tail -1)"
paste -d, "$csv_si" "$csv_mm" | awk -F, '
  NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) name[i] = $i; next }
  {
    rows++
    for (i = 2; i <= n; ++i) {
      if (name[i] == "status") { if ($i != $(i + n)) bad_status++; continue }
      s = (name[i] ~ /^(p|traction)/) ? 1e-6 : 1e3
      a = $i * s; b = $(i + n)
      d = a - b; if (d < 0) d = -d
      if (d > diff[i]) diff[i] = d
      m = (a < 0 ? -a : a); if (m > max[i]) max[i] = m
    }
  }
  END {
    worst = 0
    for (i = 2; i <= n; ++i) if (name[i] != "status" && max[i] > 0) {
      r = diff[i] / max[i]; if (r > worst) worst = r
      printf "%s: largest relative difference %.1e\n", name[i], r
    }
    printf "%d points, %d status differences, worst %.1e (bar 1e-8)\n", rows, bad_status, worst
    exit (worst <= 1e-8 && bad_status == 0 && rows > 0) ? 0 : 1
  }' && echo "PASS: unit invariant" || { echo "FAIL: not unit invariant"; exit 1; }
