#pragma once
/// \file distributed_rate_form.hpp
/// The rate-form scheme (forms/rate_form.hpp) stepped under MPI, on PETSC_COMM_WORLD (a PetscSession must exist).
///
/// Replicated state, divided rates: every rank holds the whole state and runs the same integrator
/// (integrate/rate_form_run.hpp, unchanged); each rate evaluation computes only the rank's block of particles
/// (RateFormScheme::set_row_partition) and an MPI_Allgatherv of the rate vector completes it. Each particle's rate is
/// computed by the same operations as in one process, so the states after any number of steps are the same bits as a
/// single-process run, on every rank (tests/distributed/rate_form_mpi_test.cpp, 100 steps, 1 and 2 ranks).
///
/// What this divides: the rate evaluation, which is nearly all of a step's work (neighbour rebuilds and the vector
/// updates stay replicated). What it does not: memory (the state, neighbour list and workspace are whole on every
/// rank) and communication grows with the state size (one allgather of the rate vector per evaluation, 2 per
/// predictor-corrector step). A halo-exchange version with per-rank lists is the step to 10^7+ particles
/// (docs/scaling.md).
///
/// \code{.cpp}
/// sphstab::PetscSession session(&argc, &argv);
/// sphstab::RateFormScheme<2> scheme(disc, material, options);
/// const auto block = sphstab::distribute_rate_form(scheme);   // this rank's particles [block.first, block.last)
/// const auto run = sphstab::run_rate_form(scheme, y0, {.dt = dt, .t_end = t});   // the same on every rank
/// \endcode
#include <Eigen/Core>

#include "sphstab/forms/rate_form.hpp"

namespace sphstab {

struct RateFormBlock {
  int first = 0, last = 0;  ///< this rank's particles [first, last)
  int rank = 0, ranks = 1;
  long pairs = 0;  ///< neighbour-list entries of the block's rows (the cost the split balances)
};

/// Collective on PETSC_COMM_WORLD. Splits the particles into one contiguous block per rank with about equal numbers
/// of neighbour-list entries (the evaluation's cost) and sets the scheme's row partition with an allgather of the
/// rate vector. Throws std::invalid_argument (one line) for more ranks than particles, or what set_row_partition
/// rejects (absorbing particles).
template <int Dim>
RateFormBlock distribute_rate_form(RateFormScheme<Dim>& scheme);

/// Collective: true when v has the same size and the same bits on every rank.
bool identical_on_all_ranks(const Eigen::VectorXd& v);

extern template RateFormBlock distribute_rate_form<1>(RateFormScheme<1>&);
extern template RateFormBlock distribute_rate_form<2>(RateFormScheme<2>&);

}  // namespace sphstab
