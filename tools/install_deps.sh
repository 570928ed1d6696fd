#!/usr/bin/env bash
# Install the Debian 12 packages mpm_lig needs, only those that are missing.
#   bash tools/install_deps.sh          what the build, the tests and the tools need
#   bash tools/install_deps.sh slurm    Slurm and munge, for the test that runs the batch script
#                                       under a one-node Slurm cluster (label slurm)
set -euo pipefail

case ${1:-build} in
  build)
    packages=(
      g++ cmake make ninja-build clang-format
      openmpi-bin libopenmpi-dev
      liggghts libliggghts-dev
      lammps liblammps-dev
      libeigen3-dev nlohmann-json3-dev libhdf5-dev libssl-dev libgtest-dev
      python3 python3-numpy python3-matplotlib python3-h5py
    )
    ;;
  slurm) packages=(slurm-wlm munge) ;;
  *) echo "usage: $0 [build|slurm]" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ $status == installed ]] || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install_deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=()
[[ $(id -u) -eq 0 ]] || sudo=(sudo)
echo "install_deps: installing ${missing[*]}"
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
  "${missing[@]}" >/dev/null
echo "install_deps: done"
