#!/usr/bin/env bash
# parameter_reference.sh <signorini> <doc/parameters.prm>
# The parameter reference in doc/ is what the program declares: every
# entry, default and documentation string of `signorini --print-parameters`
# (answered without starting MPI) equals doc/parameters.prm, so a parameter
# added or changed without regenerating the reference fails here.
set -u
exe="$1"; reference="$2"
out="$(mktemp)"; trap 'rm -f "$out"' EXIT
"$exe" --print-parameters > "$out" || { echo "FAIL: --print-parameters exited with $?"; exit 1; }
if ! diff -u "$reference" "$out" > /dev/null; then
  diff -u "$reference" "$out" | head -20
  echo "FAIL: doc/parameters.prm differs from --print-parameters; run scripts/make-parameter-reference"
  exit 1
fi
echo "PASS: $(grep -c '^ *set ' "$out") entries, doc/parameters.prm up to date"
