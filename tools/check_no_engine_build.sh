#!/usr/bin/env bash
# The MPM without any DEM engine: configures a scratch build with MPM_LIG_WITH_LIGGGHTS=OFF and
# MPM_LIG_WITH_LAMMPS=OFF (LAMMPS's package is disabled outright, so a stray lookup fails the
# configure), builds everything that configuration has (the MPM, the continuum materials, their
# tests, bench_mpm, a continuum-only mpm_lig), checks that nothing links an engine, runs its tests.
#
#   bash tools/check_no_engine_build.sh [BUILD_DIR]     (default: build-no-engine)
#   CMAKE_ARGS="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache" JOBS=2 bash tools/check_no_engine_build.sh
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build-no-engine}
# shellcheck disable=SC2086  # CMAKE_ARGS is a list of arguments
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DMPM_LIG_WITH_LIGGGHTS=OFF \
  -DMPM_LIG_WITH_LAMMPS=OFF -DCMAKE_DISABLE_FIND_PACKAGE_LAMMPS=ON ${CMAKE_ARGS:-} >/dev/null
cmake --build "$dir" -j"${JOBS:-$(nproc)}"

fail() { echo "check_no_engine_build: $*" >&2; exit 1; }
for needed in mpm_lig bench_mpm test_mpm_basics test_mpm_elastic test_mpm_footings; do
  [ -x "$dir/$needed" ] || fail "$needed was not built"
done
for dem_part in mpm_lig_engine_liggghts.so mpm_lig_engine_lammps.so src/dem src/rve src/coupling \
                src/element; do
  [ ! -e "$dir/$dem_part" ] || fail "$dem_part exists in an engine-free build"
done
for binary in "$dir"/mpm_lig "$dir"/bench_mpm "$dir"/test_*; do
  if ldd "$binary" | grep -Eiq 'liggghts|lammps'; then
    fail "$binary links a DEM engine"
  fi
done
ctest --test-dir "$dir" -j"${JOBS:-$(nproc)}" --output-on-failure
echo "check_no_engine_build: the MPM builds and passes its tests without a DEM engine"
