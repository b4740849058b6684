#!/usr/bin/env bash
# check.sh <signorini> <base.prm>
# Normal coefficient sweep: runs <base.prm> with 'Contact/Pair 1/Normal
# coefficient' c_n = 1e-3 ... 1e6, prints the Newton iterations and p0 of
# each run, and requires every run's contact pressures (last contact CSV) to
# equal those of c_n = 1 to 1e-6 relative to p0, with the same statuses.
set -u
exe="$(realpath "$1")"; base="$(realpath "$2")"
prm_set="$(cd "$(dirname "${BASH_SOURCE[0]}")/../../scripts" && pwd)/prm-set"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
status=0
for cn in 1 1e-3 1e-2 1e-1 10 1e2 1e3 1e4 1e5 1e6; do
  /usr/bin/python3 "$prm_set" "$base" "Contact/Pair 1/Normal coefficient=$cn" \
    "Output/Directory=$dir/c$cn" > "c$cn.prm" || exit 1
  if ! "$exe" "c$cn.prm" > "c$cn.log" 2>&1; then
    tail -5 "c$cn.log"; echo "FAIL: c_n = $cn did not run to the end"; status=1; continue
  fi
  its=$(grep -E "^  Newton iterations:" "c$cn.log" | awk '{s += $3} END {print s}')
  csv="$(ls "c$cn"/contact_*.csv | tail -1)"
  ref="$(ls c1/contact_*.csv | tail -1)"
  paste -d, "$ref" "$csv" | awk -F, -v cn="$cn" -v its="$its" '
    NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) if ($i == "p") ip = i; else if ($i == "status") is = i; next }
    { if ($ip > pmax) pmax = $ip; if ($(ip + n) > qmax) qmax = $(ip + n)
      d = $ip - $(ip + n); if (d < 0) d = -d; if (d > dmax) dmax = d
      if ($is != $(is + n)) bad++; rows++ }
    END { r = dmax / pmax
          printf "c_n = %-5s Newton %3d  p0 = %.9e Pa  largest pressure difference to c_n = 1: %.1e of p0, %d status differences\n", cn, its, qmax, r, bad
          exit (rows > 0 && r <= 1e-6 && bad == 0) ? 0 : 1 }' || status=1
done
[ $status -eq 0 ] && echo "PASS: same contact pressures for c_n from 1e-3 to 1e6" || echo "FAIL: the pressures depend on c_n"
exit $status
