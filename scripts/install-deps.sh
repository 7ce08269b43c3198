#!/usr/bin/env bash
# Installs the Debian 12 packages sphstab needs (run as root); does nothing for packages already present.
set -euo pipefail
packages=(cmake g++ make libeigen3-dev libspectra-dev libsuitesparse-dev liblapack-dev liblapacke-dev
          libfftw3-dev libgtest-dev libbenchmark-dev libcli11-dev python3-matplotlib python3-numpy python3-scipy
          pkg-config time python3-dev pybind11-dev python3-pytest petsc-dev libslepc-real-dev openmpi-bin libopenmpi-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
