#!/usr/bin/env bash
# Installs the Debian 12 packages sphstab needs (run as root); does nothing for packages already present.
#   --fe   also the finite-element reference of the impact studies (python3-dolfinx 0.5 and its 85 packages; about
#          30 s on this 2-core machine): only the studies that name `needs = ["fe"]` in studies/index.toml use it
#   --sanitizer  also the sanitizer stage's compiler (scripts/sanitize.sh): clang, its ASan/UBSan runtime
#          (libclang-rt-14-dev) and its OpenMP (libomp-dev)
set -euo pipefail
packages=(cmake g++ make ninja-build libeigen3-dev libspectra-dev libsuitesparse-dev liblapack-dev liblapacke-dev
          libfftw3-dev libgtest-dev libbenchmark-dev libcli11-dev python3-matplotlib python3-numpy python3-scipy
          pkg-config time python3-dev pybind11-dev python3-pytest petsc-dev libslepc-real-dev openmpi-bin libopenmpi-dev)
for a in "$@"; do
  case "$a" in
    --fe) packages+=(python3-dolfinx) ;;
    --sanitizer) packages+=(clang libclang-rt-14-dev libomp-dev) ;;
    *) echo "install-deps: unknown option '$a' (valid: --fe, --sanitizer)" >&2; exit 2 ;;
  esac
done
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
