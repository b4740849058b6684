#!/usr/bin/env bash
# contact_surface.sh <signorini> <scene.prm> <ranks> <mpiexec>
# The contact surface output read back: the scene (a flat rigid master, so
# that the contact force is the integral of the pressure) runs with the
# postprocessors 'contact surface, reference checks' on 1 and on <ranks>
# ranks; contact_surface.py checks each run's last step against its
# statistics.csv and the two runs against each other (the same faces and
# nodal pressures), check_files.py that every result file is complete.
set -u
exe="$1"; prm="$2"; np="$3"; mpiexec="$4"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_rmaps_base_oversubscribe=1
export OPENBLAS_CORETYPE=Haswell
dir="$(mktemp -d)"; trap 'rm -rf "$dir"' EXIT
cd "$dir"
/usr/bin/python3 "$here/../../scripts/prm-set" "$prm" \
  "Output/Postprocessors=contact surface, reference checks" > scene.prm || exit 1
status=0
for n in 1 "$np"; do
  mkdir "np$n"
  (cd "np$n" && "$mpiexec" -n "$n" --allow-run-as-root "$exe" ../scene.prm > out.txt 2>&1) ||
    { echo "FAIL: the run on $n rank(s) failed"; tail -5 "np$n/out.txt"; exit 1; }
  /usr/bin/python3 "$here/check_files.py" "np$n/results" || status=1
done
/usr/bin/python3 "$here/contact_surface.py" "np$np/results" np1/results || status=1
exit $status
