#!/usr/bin/env bash
# Sanitizer build: AddressSanitizer + UndefinedBehaviorSanitizer (with float-cast-overflow), no recovery, library and
# unit tests only (studies, benchmarks, PETSc and Python off), into ${SANITIZE_BUILD_DIR:-build-sanitize}; then the whole
# ctest suite, one ctest test per test program (SPHSTAB_TEST_REGISTRATION=program: one ASan start-up per program, not per
# GoogleTest case; a failure names the program and, in its output, the case).
# Run by .ci/run after the normal suite. Locally: bash scripts/sanitize.sh [extra CMake configure arguments].
# -O1 -g1 (line tables only): the sanitizers' usual optimisation level, and half the compile time of -O2 -g (measured
# on src/stability/critical_load.cpp: 41 s against 78 s of CPU, docs/ci.md); reports still name file and line.
# Compiler: clang++ (Debian's clang 14, with its ASan/UBSan runtime libclang-rt-14-dev and its OpenMP libomp-dev, which
# `install-deps.sh --sanitizer` installs below): it compiles this code base's instrumented build with much less CPU than
# g++ (src/forms/rate_form_rate_2d.cpp: 54 s against 143 s; the whole stage's build 925 s against 1344 s, docs/ci.md).
# The Release build (the results) stays with g++; SANITIZE_CXX=g++ runs this stage with g++ (in a new build directory).
# The PETSc/SLEPc backend is OFF here: OpenMPI's and PETSc's own allocations make ASan/LeakSanitizer noisy, and the
# MPI tests run under mpirun, outside ASan's reach; the Release suite (scripts/test.sh) builds and tests it.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${SANITIZE_BUILD_DIR:-build-sanitize}
bash scripts/install-deps.sh --sanitizer
flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
gen=()  # Ninja and the compiler for a new build directory (an existing one keeps both)
if [ ! -f "$build/CMakeCache.txt" ]; then
  if command -v ninja >/dev/null; then gen=(-G Ninja); fi
  cxx=${SANITIZE_CXX:-clang++}
  if ! command -v "$cxx" >/dev/null; then
    echo "sanitize.sh: compiler '$cxx' not found (bash scripts/install-deps.sh --sanitizer installs clang)" >&2
    exit 2
  fi
  gen+=(-DCMAKE_CXX_COMPILER="$cxx")
fi
t_build=$SECONDS
cmake -S . -B "$build" "${gen[@]}" -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" -DSPHSTAB_BUILD_STUDIES=OFF \
  -DSPHSTAB_BUILD_BENCHMARKS=OFF -DSPHSTAB_WITH_PETSC=OFF -DSPHSTAB_WITH_PYTHON=OFF \
  -DSPHSTAB_TEST_REGISTRATION=program "$@" >/dev/null
cmake --build "$build" -j "$(nproc)"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=0:halt_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
t0=$SECONDS
echo "sanitize.sh: build $((t0 - t_build)) s"
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" --timeout 1200
echo "sanitize.sh: tests $((SECONDS - t0)) s"
