#!/usr/bin/env bash
# Installs, from Debian's archive, whatever of the project's build and run
# dependencies is missing. Idempotent: a machine that has everything runs no apt.
set -euo pipefail
packages=(
  build-essential cmake
  libeigen3-dev libgsl-dev libboost-dev libfftw3-dev
  doctest-dev libbenchmark-dev
  libcli11-dev libtoml11-dev nlohmann-json3-dev
  libhdf5-dev hdf5-tools python3-h5py libssl-dev zlib1g-dev libmatio-dev python3-scipy
  clang libclang-rt-14-dev
  gnuplot-nox
  gmsh calculix-ccx
  slurm-wlm munge parallel
  pkg-config ccache
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-venv python3-pip
  python3-setuptools python3-wheel python3-pytest
  jupyter-nbconvert python3-ipykernel python3-matplotlib python3-nbformat
)
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q "${missing[@]}"
else
  echo "setup: all packages present"
fi
