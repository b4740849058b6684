#!/usr/bin/env bash
# echo_input_file.sh <signorini> <scene.prm>
# The parameter echo never overwrites the input file: run as
# 'signorini parameters.prm' with Output/Directory = '.', and through a
# symbolic link and a hard link to that file, the echo goes to
# parameters.echo.prm (a note says so) and parameters.prm is unchanged;
# an input file of another name gives the echo parameters.prm.
set -u
exe="$1"; prm="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
/usr/bin/python3 "$here/../../scripts/prm-set" "$prm" "Load stepping/Number of steps=2" \
  "Output/Directory=." "Output/Postprocessors=reference checks" > parameters.prm || exit 1
cp parameters.prm original.prm
mkdir other; ln -s ../parameters.prm other/link.prm; ln parameters.prm hard.prm
status=0
note="Note: './parameters.prm' is the input file: the parameters are echoed to './parameters.echo.prm'"
for input in parameters.prm ./parameters.prm "$dir/parameters.prm" other/link.prm hard.prm; do
  rm -f parameters.echo.prm
  "$exe" "$input" > out.txt 2>&1; rc=$?
  if [ $rc -ne 0 ] || ! cmp -s parameters.prm original.prm || [ "$(grep -cxF -- "$note" out.txt)" -ne 1 ] ||
     ! grep -q "set Number of steps *= 2" parameters.echo.prm; then
    echo "FAIL: signorini $input: exit code $rc, input $(cmp -s parameters.prm original.prm && echo unchanged || echo CHANGED), note printed $(grep -cxF -- "$note" out.txt) time(s), echo: $(ls parameters.echo.prm 2>&1)"
    head -3 out.txt; status=1; cp original.prm parameters.prm
  else
    echo "PASS: signorini $input: input unchanged, echo in parameters.echo.prm"
  fi
done
# Another input name: the echo is parameters.prm as usual (no note).
mkdir plain; cp original.prm plain/input.prm; cd plain
"$exe" input.prm > out.txt 2>&1; rc=$?
if [ $rc -ne 0 ] || grep -q "^Note: " out.txt || ! grep -q "set Number of steps *= 2" parameters.prm || [ -e parameters.echo.prm ]; then
  echo "FAIL: signorini input.prm: exit code $rc, echo not in parameters.prm"; status=1
else
  echo "PASS: signorini input.prm: echo in parameters.prm"
fi
exit $status
