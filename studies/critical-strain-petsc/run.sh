#!/usr/bin/env bash
# Critical strain on PETSc/SLEPc (results/critical-strain-petsc): the distributed cases (n = 128, 256) and the SciPy
# comparison (n = 32, 64, 128) rewritten from scratch, then the Results table of summary.md replaced by the table of
# the new rows (benchmarks/distributed/critical_strain_petsc_table.py). The Reading section of summary.md is prose
# written against the committed rows: reread it after a rerun. Needs the build's PETSc backend (SPHSTAB_WITH_PETSC).
# Called by scripts/main.sh as run.sh BIN_DIR OUT_DIR.
set -euo pipefail
py=${PYTHON:-/usr/bin/python3}
build=$(dirname "$1")
[ -x "$1/petsc_critical_strain" ] || { echo "critical-strain-petsc: $1/petsc_critical_strain not built (PETSc off)" >&2; exit 1; }
rm -f "$2/results.csv"
bash benchmarks/distributed/critical_strain_petsc.sh "$build" 128 256
bash benchmarks/distributed/scipy_versus.sh "$build"
"$py" - "$2/summary.md" "$2/results.csv" <<'PY'
import subprocess, sys
md, csv = sys.argv[1], sys.argv[2]
table = subprocess.run([sys.executable, "benchmarks/distributed/critical_strain_petsc_table.py", csv],
                       check=True, capture_output=True, text=True).stdout
text = open(md, encoding="utf-8").read()
head, rest = text.split("## Results\n", 1)
_, tail = rest.split("## Reading", 1)
open(md, "w", encoding="utf-8").write(head + "## Results\n\n" + table + "\n## Reading" + tail)
PY
