#!/usr/bin/env bash
# The critical-strain-petsc benchmark: one process group per case (so peak RSS is per case), each run under nice and
# `timeout` (a case over the limit is a row with status timeout), rows appended to results/critical-strain-petsc/
# results.csv. Usage: bash benchmarks/distributed/critical_strain_petsc.sh [BUILD_DIR] [SIZES...]
#   default sizes 128 256; limit per case: ${CASE_TIMEOUT:-600} s.
set -uo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
shift || true
sizes=("${@:-128 256}")
[ $# -eq 0 ] && sizes=(128 256)
out=results/critical-strain-petsc/results.csv
bin=${BIN:-$build/bin/petsc_critical_strain}
limit=${CASE_TIMEOUT:-600}
mpirun=(mpirun --allow-run-as-root --oversubscribe --bind-to none)
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
[ -f "$out" ] || echo "route,method,ranks,n,dofs,e_crit,status,iterations,inner_iterations,residual,build_s,assembly_s,solve_s,total_s,cpu_s,peak_rss_mb_max_rank,peak_rss_mb_sum,reason" > "$out"
run() {  # ranks, label, args...
  local ranks=$1 label=$2
  shift 2
  echo "critical-strain-petsc: $label ranks=$ranks $*" >&2
  local line
  line=$(nice timeout "$limit" "${mpirun[@]}" -np "$ranks" "$bin" "$@" 2>/tmp/critical_strain_petsc.err)
  local rc=$?
  if [ $rc -eq 0 ] && [ -n "$line" ]; then
    echo "$line" | tee -a "$out" >&2
  else
    local n
    n=$(echo "$*" | sed -E 's/.*--n ([0-9]+).*/\1/')
    echo "$label,,$ranks,$n,,nan,$( [ $rc -eq 124 ] && echo timeout || echo error ),,,,,,,$( [ $rc -eq 124 ] && echo "$limit" ),,,,\"$(tail -1 /tmp/critical_strain_petsc.err | tr -d '",')\"" | tee -a "$out" >&2
  fi
}
# Per size: the single-process routes, then the PETSc routes on 1 and 2 ranks. Unshifted Krylov-Schur and LOBPCG (with
# a looser tolerance, see the summary) only up to UNSHIFTED_MAX (default 128): they need hundreds of K solves or steps.
for n in "${sizes[@]}"; do
  run 1 direct --route direct --n "$n"
  [ "$n" -le "${MATRIX_FREE_MAX:-256}" ] && run 1 matrix-free --route matrix-free --n "$n"
  for ranks in 1 2; do
    run "$ranks" petsc --route petsc --n "$n" --method shift-invert --solver cholesky
    if [ "$n" -le "${UNSHIFTED_MAX:-128}" ]; then
      run "$ranks" petsc --route petsc --n "$n" --method krylov-schur --solver cholesky
      run "$ranks" petsc --route petsc --n "$n" --method lobpcg --solver gamg -eps_tol 1e-8 -eps_max_it 5000
    fi
  done
done
