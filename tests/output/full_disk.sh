#!/usr/bin/env bash
# full_disk.sh <signorini> <scene.prm> <mpiexec>
# A write that fails (a full disk) stops the run on every rank with exit
# code 2 and one message naming the file and the reason, and the files on
# disk stay complete. No root, no mount: a symbolic link named like the file
# (or like its temporary name) points to /dev/full, where every write fails
# with ENOSPC; the program opens the link like a file, so the real write
# path is tested. Cases: the appended tables, each kind of per-step file (a
# later step; rank 1 failing on 2 ranks: rank 0 must stop too, no hang),
# the parameter echo; and an output directory that cannot be created.
set -u
exe="$1"; prm="$2"; mpiexec="${3:-mpiexec}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
[ -w /dev/full ] || { echo "FAIL: /dev/full is not writable here"; exit 1; }
top="$(mktemp -d)"; trap 'rm -rf "$top"' EXIT
/usr/bin/python3 "$here/../../scripts/prm-set" "$prm" "Load stepping/Number of steps=3" \
  > "$top/scene.prm" || exit 1
status=0
# case <link name> <ranks> <file(s) named in the message, quoted as there>
case_() {
  local link="$1" np="$2" file="$3" reason="No space left on device"
  local dir="$top/$np-$link"
  mkdir -p "$dir/results"
  ln -s /dev/full "$dir/results/$link"
  if [ "$np" -gt 1 ]; then
    (cd "$dir" && timeout 120 "$mpiexec" -n "$np" --allow-run-as-root "$exe" "$top/scene.prm" > out.txt 2>&1)
  else
    (cd "$dir" && timeout 120 "$exe" "$top/scene.prm" > out.txt 2>&1)
  fi
  local rc=$? n
  n="$(grep -F "signorini: run stopped: cannot write $file: $reason" "$dir/out.txt" | wc -l)"
  if [ $rc -ne 2 ] || [ "$n" -ne 1 ]; then
    echo "FAIL: $link on $np rank(s): exit code $rc (expected 2), message "cannot write $file: $reason" printed $n time(s) (expected once):"
    tail -3 "$dir/out.txt"; status=1; return
  fi
  if ! out="$(/usr/bin/python3 "$here/check_files.py" "$dir/results")"; then
    echo "$out"; status=1; return
  fi
  echo "PASS: $link -> /dev/full on $np rank(s): exit code 2, "cannot write $file: $reason" once; ${out#PASS: $top/}"
}
case_ statistics.csv           1 "'results/statistics.csv'"
case_ newton_history.csv       1 "'results/newton_history.csv'"
case_ solution_0002.1.vtu.tmp  2 "'results/solution_0002.1.vtu' (as 'results/solution_0002.1.vtu.tmp')"
case_ solution_0002.pvtu.tmp   1 "'results/solution_0002.pvtu' (as 'results/solution_0002.pvtu.tmp')"
case_ solution.pvd.tmp         1 "'results/solution.pvd' (as 'results/solution.pvd.tmp')"
case_ contact_surface_0002.1.vtu.tmp 2 "'results/contact_surface_0002.1.vtu' (as 'results/contact_surface_0002.1.vtu.tmp')"
case_ contact_surface.pvd.tmp 1 "'results/contact_surface.pvd' (as 'results/contact_surface.pvd.tmp')"
case_ contact_0003.csv.tmp     1 "'results/contact_0003.csv' (as 'results/contact_0003.csv.tmp')"
case_ parameters.prm.tmp       1 "'results/parameters.prm' (as 'results/parameters.prm.tmp')"
# The rank that failed is named (rank 1's own VTU piece).
if ! grep -q "(on rank 1)" "$top/2-solution_0002.1.vtu.tmp/out.txt"; then
  echo "FAIL: the message does not name rank 1"; status=1
fi
# An output directory that is a file is refused at input (exit 1):
# tests/bad_input/output_directory_is_file.prm.
exit $status
