#!/usr/bin/env bash
# Cost of the coloured complex-step Jacobian against one force evaluation, 1D and 2D, as N grows (about 40 s).
set -euo pipefail
"$1/jacobian_benchmark" --benchmark_format=json >"$2/benchmark.json"
"${PYTHON:-/usr/bin/python3}" benchmarks/relative_executable.py "$2/benchmark.json"
"${PYTHON:-/usr/bin/python3}" "$(dirname "$0")/report.py" "$2"
