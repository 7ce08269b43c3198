#!/usr/bin/env bash
# Configures and builds sphstab (Release) into ${BUILD_DIR:-build}; extra arguments go to the CMake configure step.
# SPHSTAB_TARGETS="a b": build only those targets (scripts/main.sh builds only what its studies need).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
# Ninja for a new build directory when it is installed (install-deps.sh installs it): it compiles a target's sources
# while the library they link is still being built, where Make waits for the whole library (docs/ci.md). An existing
# directory keeps the generator it was configured with.
gen=()
if [ ! -f "$build/CMakeCache.txt" ] && command -v ninja >/dev/null; then gen=(-G Ninja); fi
cmake -S . -B "$build" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# shellcheck disable=SC2086
cmake --build "$build" -j "$(nproc)" ${SPHSTAB_TARGETS:+--target $SPHSTAB_TARGETS}
