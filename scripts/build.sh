#!/usr/bin/env bash
# Configures and builds sphstab (Release) into ${BUILD_DIR:-build}; extra arguments go to the CMake configure step.
# SPHSTAB_TARGETS="a b": build only those targets (scripts/main.sh builds only what its studies need).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
# shellcheck disable=SC2086
cmake --build "$build" -j "$(nproc)" ${SPHSTAB_TARGETS:+--target $SPHSTAB_TARGETS}
