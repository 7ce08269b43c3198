#!/usr/bin/env bash
# Stepping speed (issue 4): TL SpMV vs UL re-assembly vs pair loops, 2D, 1e4-1e6 particles (about 2 min).
set -euo pipefail
"$1/stepping_benchmark" --out "$2"
