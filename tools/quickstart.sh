#!/usr/bin/env bash
# One command from a fresh Debian 12 machine:
#   bash tools/quickstart.sh demo   install what is missing, build, run the quickstart case
#   bash tools/quickstart.sh test   install what is missing, build, run the whole test suite
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-demo}
jobs=$(nproc)

bash tools/install_deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"

case $what in
  demo)
    mpirun --allow-run-as-root --oversubscribe -np 2 build/mpm_lig cases/quickstart.json \
      --output out/quickstart
    echo "quickstart results: out/quickstart (history.csv, results.xdmf for ParaView, summary.json)"
    ;;
  test)
    ctest --test-dir build --output-on-failure -j"$jobs" ${CTEST_ARGS:-}
    ;;
  *)
    echo "usage: $0 demo|test" >&2
    exit 2
    ;;
esac
