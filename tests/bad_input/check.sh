#!/usr/bin/env bash
# check.sh <signorini> <file.prm> <ranks> <mpiexec>
# A bad-input case passes when signorini exits non-zero and prints the text of
# the file's "# expect:" line exactly once (on any rank count).
set -u
exe="$1"; prm="$2"; np="$3"; mpiexec="${4:-mpiexec}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
expect="$(sed -n 's/^# expect: //p' "$prm")"
dir="$(mktemp -d)"; cd "$dir"
if [ "$np" -gt 1 ]; then
  "$mpiexec" -n "$np" --allow-run-as-root "$exe" "$prm" > out.txt 2>&1; rc=$?
else
  "$exe" "$prm" > out.txt 2>&1; rc=$?
fi
cat out.txt
count="$(grep -cF -- "$expect" out.txt)"
rm -rf "$dir"
if [ "$rc" -eq 0 ]; then echo "FAIL: exit code 0, expected non-zero"; exit 1; fi
if [ "$count" -ne 1 ]; then echo "FAIL: expected the message once, found it $count times: $expect"; exit 1; fi
echo "PASS: exit code $rc, message printed once"
