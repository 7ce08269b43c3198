#!/usr/bin/env bash
# README main job: install dependencies, build, run every default study into results/.
# A study is studies/<name>/ with main.cpp (built to build/bin/study_<name>) and optionally plot.py,
# or with a run.sh (called as run.sh BIN_DIR OUT_DIR) for studies that drive other programs (benchmarks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
bin=${BUILD_DIR:-build}/bin
only=${1:-}
for dir in studies/*/; do
  name=$(basename "$dir")
  [ -n "$only" ] && [ "$only" != "$name" ] && continue
  exe="$bin/study_${name//-/_}"
  [ -x "$exe" ] || [ -f "$dir/run.sh" ] || continue
  echo "== study $name"
  mkdir -p "results/$name"
  start=$SECONDS
  if [ -f "$dir/run.sh" ]; then
    bash "$dir/run.sh" "$bin" "results/$name"
  else
    "$exe" --out "results/$name"
  fi
  if [ -f "$dir/plot.py" ]; then "${PYTHON:-/usr/bin/python3}" "$dir/plot.py" "results/$name"; fi
  if [ -f "$dir/summary.md.in" ]; then
    "${PYTHON:-/usr/bin/python3}" scripts/render_summary.py "$dir/summary.md.in" "results/$name/summary.json" \
      > "results/$name/summary.md"
  fi
  echo "== study $name done in $((SECONDS - start)) s"
done
