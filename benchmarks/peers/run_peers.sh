#!/usr/bin/env bash
# benchmarks/peers/run_peers.sh SIGNORINI [quick]
# The peers benchmark of issue 32 (scripts/benchmark peers calls it with
# the built binary): installs Debian's GetFEM Python interface and
# matplotlib when missing, then runs benchmarks/peers/run_peers.py.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
binary="$1"; shift
if ! /usr/bin/python3 -c "import getfem, matplotlib" 2>/dev/null; then
  if [ "$(id -u)" = 0 ]; then
    echo "== installing: python3-getfem python3-matplotlib"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq
    apt-get install -y -qq --no-install-recommends python3-getfem python3-matplotlib
  else
    echo "Install them with:  sudo apt-get install python3-getfem python3-matplotlib" >&2
    exit 1
  fi
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# one thread each: Signorini runs on 1 rank, GetFEM's MUMPS is sequential
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
exec /usr/bin/python3 "$here/run_peers.py" "$binary" "$@"
