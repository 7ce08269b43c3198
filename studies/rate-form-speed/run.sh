#!/usr/bin/env bash
# Speed of the rate-form step routes (results/rate-form-speed): rate_form_step_benchmark under /usr/bin/time -v (its
# peak RSS goes into the report), then benchmark.md against the committed earlier run benchmark_before.json.
# Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR.
set -euo pipefail
py=${PYTHON:-/usr/bin/python3}
/usr/bin/time -v "$1/rate_form_step_benchmark" --benchmark_out="$2/benchmark.json" --benchmark_out_format=json \
  2> "$2/time.txt"
peak_kb=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$2/time.txt")
rm -f "$2/time.txt"
"$py" benchmarks/rate_form_step_report.py "$2/benchmark.json" "$2/benchmark.md" "$((peak_kb / 1024))" \
  --before "$2/benchmark_before.json"
