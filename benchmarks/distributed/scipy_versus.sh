#!/usr/bin/env bash
# Issue 13's SciPy comparison: per size, the direct route, petsc_critical_load (shift-invert, 1 rank) and SciPy's eigsh
# shift-invert (benchmarks/distributed/scipy_critical_strain.py) on the matrices `sphstab jacobian elastic` exports,
# one after the other in the same run, each in its own process under nice and `timeout`. Rows (the columns of
# critical_strain_petsc.sh) go to results/critical-strain-petsc/scipy.csv, which this script rewrites.
# Usage: bash benchmarks/distributed/scipy_versus.sh [BUILD_DIR] [SIZES...]   (default sizes 32 64 128)
set -uo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
shift || true
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(32 64 128)
out=results/critical-strain-petsc/scipy.csv
limit=${CASE_TIMEOUT:-900}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
echo "route,method,ranks,n,dofs,e_crit,status,iterations,inner_iterations,residual,build_s,assembly_s,solve_s,total_s,cpu_s,peak_rss_mb_max_rank,peak_rss_mb_sum,reason" > "$out"
run() {  # label, command...
  local label=$1
  shift
  echo "scipy-versus: $label" >&2
  local line
  line=$(nice timeout "$limit" "$@" 2>"$work/err")
  local rc=$?
  if [ $rc -eq 0 ] && [ -n "$line" ]; then
    echo "$line" | tee -a "$out" >&2
  else
    echo "$label,,1,$n,,nan,$( [ $rc -eq 124 ] && echo timeout || echo error ),,,,,,,,,,,\"$(tail -1 "$work/err" | tr -d '",')\"" | tee -a "$out" >&2
  fi
}
for n in "${sizes[@]}"; do
  run direct "$build/bin/petsc_critical_strain" --route direct --n "$n"
  run petsc mpirun --allow-run-as-root --oversubscribe --bind-to none -np 1 "$build/bin/petsc_critical_strain" \
    --route petsc --n "$n" --method shift-invert --solver cholesky
  run scipy "${PYTHON:-/usr/bin/python3}" benchmarks/distributed/scipy_critical_strain.py "$build/bin/sphstab" "$n" \
    "$work/n$n"
  rm -rf "$work/n$n"
done
