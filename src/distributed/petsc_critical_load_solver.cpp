#include "sphstab/distributed/petsc_critical_load_solver.hpp"

#include <slepcsys.h>

#include <memory>

namespace sphstab {

DistributedCriticalLoadSolver petsc_critical_load_solver(const PetscCriticalLoadOptions& options) {
  return [options](const Linearisation& lin, LoadDirection direction) {
    const PetscCriticalLoad p = petsc_critical_load(lin, direction, options);
    DistributedCriticalLoad d;
    d.load = p.load;
    d.lambda_max = p.lambda_max;
    d.residual = p.residual;
    d.iterations = p.iterations;
    d.inner_iterations = p.ksp_iterations;
    d.ranks = p.ranks;
    d.assembly_seconds = p.assembly_seconds;
    d.solve_seconds = p.solve_seconds;
    d.solver = p.solver;
    d.status = p.status;
    d.reason = p.reason;
    return d;
  };
}

void ensure_petsc_session() {
  static std::unique_ptr<PetscSession> session;
  PetscBool initialised = PETSC_FALSE;
  SlepcInitialized(&initialised);
  if (!session && !initialised) session = std::make_unique<PetscSession>(nullptr, nullptr);
}

}  // namespace sphstab
