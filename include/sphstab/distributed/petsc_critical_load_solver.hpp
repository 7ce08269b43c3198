#pragma once
/// \file petsc_critical_load_solver.hpp
/// The PETSc route of the critical-load front door (stability/critical_load_problem.hpp, CriticalLoadRoute::
/// Distributed): the core library does not depend on PETSc or MPI, so this library (sphstab_petsc, built with
/// SPHSTAB_WITH_PETSC) supplies the solver that CriticalLoadRouteOptions::distributed holds.
///
/// \code{.cpp}
/// sphstab::ensure_petsc_session();   // or a PetscSession in main (with the command line's PETSc options)
/// sphstab::CriticalLoadRouteOptions o{.route = sphstab::CriticalLoadRoute::Distributed,
///                                     .distributed = sphstab::petsc_critical_load_solver()};
/// sphstab::CriticalLoadResult r = sphstab::critical_load(problem, sphstab::LoadDirection::Tension, o);
/// \endcode
#include "sphstab/distributed/petsc_critical_load.hpp"
#include "sphstab/stability/critical_load_problem.hpp"

namespace sphstab {

/// petsc_critical_load(lin, direction, options) with its PetscCriticalLoad copied field by field into the front
/// door's DistributedCriticalLoad (solver, iterations, KSP iterations, residual, ranks, times, status, reason).
/// Collective on PETSC_COMM_WORLD when called; needs a PetscSession (ensure_petsc_session()).
DistributedCriticalLoadSolver petsc_critical_load_solver(const PetscCriticalLoadOptions& options = {});

/// A PetscSession for the rest of the process (no command-line options; finalised at exit), unless one exists. For
/// programs such as the sphstab command line that reach the PETSc route only on request.
void ensure_petsc_session();

}  // namespace sphstab
