#!/usr/bin/env bash
# README main job: install dependencies, build what the chosen studies need (Release), run them.
#   bash scripts/main.sh                 the default main job: the headline studies in full into results/, and one
#                                        short (--quick) run of the other families into build/quick/ (about 14 min on a fresh clone, build included)
#   bash scripts/main.sh --all           every study in full: regenerates the results/ tree as committed (hours)
#   bash scripts/main.sh NAME...         the named studies in full
#   options: --jobs N (studies side by side, default the core count), --list (print the plan and estimate only)
# The studies, their families and which belong to the default job: studies/index.toml. The engine, with the estimate
# and progress lines: scripts/run_studies.py. Wall times of the last full runs: results/timings.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
py=${PYTHON:-/usr/bin/python3}
if [ ! -x "$py" ]; then bash scripts/install-deps.sh; fi
targets=$("$py" scripts/run_studies.py --targets "$@")
for a in "$@"; do [ "$a" = "--list" ] && exec "$py" scripts/run_studies.py "$@"; done
needs=$("$py" scripts/run_studies.py --needs "$@")
bash scripts/install-deps.sh ${needs:+$(printf -- '--%s ' $needs)}
SPHSTAB_TARGETS="$targets" bash scripts/build.sh
exec "$py" scripts/run_studies.py "$@"
