#!/usr/bin/env bash
# check.sh <signorini> <file.prm> <ranks> <mpiexec>
# A bad-input case passes when signorini
#  - exits with the code of the file's "# exit: N" line (default 1: an input
#    error; 2: a run stopped, 4: a reference check failed),
#  - prints the text of its "# expect:" line exactly once (on any rank count),
#  - shows no sign of a crash (segfault, uncaught exception, abort,
#    deal.II stack trace, MPI_ABORT),
#  - and prints none of the texts of its "# absent:" lines.
# A "# options:" line gives command-line options put before the file
# (e.g. --check).
# A case that is a directory (a directory given as the parameter file) keeps
# these lines in the file 'expect' inside it.
set -u
exe="$1"; prm="$2"; np="$3"; mpiexec="${4:-mpiexec}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
meta="$prm"
if [ -d "$prm" ]; then meta="$prm/expect"; fi
expect="$(sed -n 's/^# expect: //p' "$meta")"
want_rc="$(sed -n 's/^# exit: //p' "$meta")"
want_rc="${want_rc:-1}"
read -r -a options <<< "$(sed -n 's/^# options: //p' "$meta")"
if [ -z "$expect" ]; then echo "FAIL: no '# expect:' line in $meta"; exit 1; fi
dir="$(mktemp -d)"; cd "$dir"
if [ "$np" -gt 1 ]; then
  "$mpiexec" -n "$np" --allow-run-as-root "$exe" "${options[@]}" "$prm" > out.txt 2>&1; rc=$?
else
  "$exe" "${options[@]}" "$prm" > out.txt 2>&1; rc=$?
fi
cat out.txt
count="$(grep -cF -- "$expect" out.txt)"
crashes=""
for marker in "Stacktrace" "terminate called" "MPI_ABORT" "Segmentation fault" \
              "signal 11" "An error occurred in line" "Aborted" "core dumped" \
              "Uncaught" "Exception on processing"; do
  if grep -qF -- "$marker" out.txt; then crashes="$crashes '$marker'"; fi
done
absent_found=""
while IFS= read -r text; do
  [ -n "$text" ] && grep -qF -- "$text" out.txt && absent_found="$absent_found '$text'"
done < <(sed -n 's/^# absent: //p' "$meta")
rm -rf "$dir"
if [ -n "$absent_found" ]; then echo "FAIL: the output shows:$absent_found"; exit 1; fi
if [ -n "$crashes" ]; then echo "FAIL: the output shows a crash:$crashes"; exit 1; fi
if [ "$rc" -ge 128 ]; then echo "FAIL: killed by signal $((rc - 128))"; exit 1; fi
if [ "$rc" -ne "$want_rc" ]; then echo "FAIL: exit code $rc, expected $want_rc"; exit 1; fi
if [ "$count" -ne 1 ]; then echo "FAIL: expected the message once, found it $count times: $expect"; exit 1; fi
echo "PASS: exit code $rc, message printed once, no crash"
