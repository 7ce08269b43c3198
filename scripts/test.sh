#!/usr/bin/env bash
# README test command: install dependencies, build, run the whole GoogleTest suite through ctest.
# Prints the wall time of each phase (dependencies, build, tests).
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$SECONDS
bash scripts/install-deps.sh
t1=$SECONDS
bash scripts/build.sh
t2=$SECONDS
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j "$(nproc)" --timeout 600
t3=$SECONDS
echo "test.sh: dependencies $((t1 - t0)) s, build $((t2 - t1)) s, tests $((t3 - t2)) s"
