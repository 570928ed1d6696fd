#!/usr/bin/env bash
# One command from a fresh Debian 12 machine:
#   bash tools/quickstart.sh demo [quickstart|footing|cyclic]
#                                   install what is missing, build, run a demo case (a few minutes
#                                   at most) and draw a picture of what it computed
#   bash tools/quickstart.sh test   install what is missing, build, run the whole test suite but
#                                   the Slurm test (label slurm, about 1.5-2 min: it installs
#                                   and starts a one-node Slurm cluster); CTEST_ARGS replaces
#                                   ctest's selection: CTEST_ARGS="-L slurm" runs that test alone,
#                                   CTEST_ARGS= everything
set -euo pipefail
cd "$(dirname "$0")/.."

what=${1:-demo}
demo=${2:-quickstart}
jobs=$(nproc)
mpirun_2="mpirun --allow-run-as-root --oversubscribe -np 2"

# Pictures are drawn off-screen (matplotlib Agg): no display needed.
picture() {
  /usr/bin/python3 "$@"
}

usage="usage: $0 demo [quickstart|footing|cyclic] | test"
case $what:$demo in
  demo:quickstart | demo:footing | demo:cyclic | test:*) ;;
  *) echo "$usage" >&2; exit 2 ;;
esac

bash tools/install_deps.sh
# Ninja schedules every unit of every library at once (Make waits for a library before the next
# one starts); an existing build/ keeps the generator it was made with.
generator=()
[[ -f build/CMakeCache.txt ]] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
# The demo builds only the program it runs and the engine modules it loads (docs/build.md); the
# tests need the whole tree.
if [[ $what == demo ]]; then
  cmake --build build -j"$jobs" --target mpm_lig
else
  cmake --build build -j"$jobs"
fi

case $what in
  demo)
    case $demo in
      quickstart)
        out=out/quickstart
        $mpirun_2 build/mpm_lig cases/quickstart.json --output $out
        picture tools/plot_fields.py $out -o $out/fields.png
        ;;
      footing)
        out=out/footing_dem_quick
        $mpirun_2 build/mpm_lig cases/footing_dem_quick.json --output $out
        picture tools/plot_footing.py $out --case cases/footing_dem_quick.json --phi 29.3 \
          --label "MPM x DEM, quick" -o $out/footing.png
        picture tools/plot_fields.py $out -o $out/fields.png
        ;;
      cyclic)
        out=out/cyclic_quick
        $mpirun_2 build/mpm_lig cases/cyclic_simple_shear_quick.json --output $out
        picture tools/plot_shear.py $out -o $out/shear.png
        ;;
    esac
    echo "results in $out: history.csv, results.xdmf (ParaView), summary.json"
    echo "pictures: $(ls $out/*.png | tr '\n' ' ')"
    ;;
  test)
    ctest --test-dir build --output-on-failure -j"$jobs" ${CTEST_ARGS--LE slurm}
    ;;
esac
