// The rate-form scheme stepped under MPI (distributed/distributed_rate_form.hpp) against the same run in one process:
// 100 predictor-corrector steps of the GMS scheme (XSPH, viscosity, artificial stress) and of the NCSPH scheme end in
// the same bits, on every rank. Run by ctest under `mpirun -np 1` and `mpirun -np 2` (tests/CMakeLists.txt).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "../forms/forms_fixture.hpp"
#include "mpi_test_main.hpp"
#include "sphstab/distributed/distributed_rate_form.hpp"
#include "sphstab/distributed/petsc_critical_load.hpp"
#include "sphstab/integrate/rate_form_run.hpp"

namespace sphstab {
namespace {

PetscSession* g_session = nullptr;

using test::kGms;

/// 100 steps in this process (the reference: every rank runs it whole) and distributed over the ranks.
void expect_distributed_run_is_the_same_bits(const RateFormOptions& options, const std::string& name) {
  const auto disc = test::lattice_discretisation<2>({.n = 20, .h = 1.5});
  const RateFormScheme<2> whole(disc, kGms, options);
  Eigen::VectorXd y0 = whole.uniform_state();
  for (int i = 0; i < disc->size(); i += 5)
    if (whole.velocity_offset(i) >= 0) y0[whole.velocity_offset(i)] = 0.01;
  const RateFormRunOptions run{.dt = 0.05, .t_end = 5.0};
  const RateFormRunResult reference = run_rate_form(whole, y0, run);
  ASSERT_TRUE(reference.completed()) << name << ": " << reference.message;
  ASSERT_EQ(reference.steps, 100) << name;

  RateFormScheme<2> split = whole;
  const RateFormBlock block = distribute_rate_form(split);
  EXPECT_EQ(block.ranks, g_session->size());
  EXPECT_LT(block.first, block.last);
  EXPECT_TRUE(split.partitioned());
  const RateFormRunResult distributed = run_rate_form(split, y0, run);
  ASSERT_TRUE(distributed.completed()) << name << ": " << distributed.message;
  EXPECT_GT((reference.y - y0).cwiseAbs().maxCoeff(), 1e-4) << name;  // the state moved
  EXPECT_EQ(test::differing_bits(reference.y, distributed.y), 0) << name << " on rank " << block.rank;
  EXPECT_TRUE(identical_on_all_ranks(distributed.y)) << name;
}

TEST(DistributedRateForm, GmsSchemeAfter100StepsIsTheSameBits) {
  expect_distributed_run_is_the_same_bits(
      {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3}, "gms");
}

TEST(DistributedRateForm, NcsphSchemeAfter100StepsIsTheSameBits) {
  expect_distributed_run_is_the_same_bits({.gradient = RateFormGradient::Ncsph}, "ncsph");
}

TEST(DistributedRateForm, BlocksCoverTheParticlesInOrder) {
  const auto disc = test::lattice_discretisation<2>({.n = 12, .h = 1.3});
  RateFormScheme<2> scheme(disc, kGms);
  const RateFormBlock block = distribute_rate_form(scheme);
  // Rank r's block starts where rank r - 1's ends, the first at 0 and the last at the particle count.
  double previous_end = 0;
  for (int r = 0; r < block.ranks; ++r) {
    const double first = max_over_ranks(block.rank == r ? block.first : -1.0);
    const double last = max_over_ranks(block.rank == r ? block.last : -1.0);
    EXPECT_EQ(first, previous_end) << "rank " << r;
    EXPECT_LT(first, last) << "rank " << r;
    previous_end = last;
  }
  EXPECT_EQ(previous_end, disc->size());
}

TEST(DistributedRateForm, BadInputIsOneLine) {
  const auto disc = test::lattice_discretisation<2>({.n = 4, .h = 1.3});
  RateFormScheme<2> scheme(disc, kGms);
  EXPECT_THROW(scheme.set_row_partition(0, 0, [](Eigen::VectorXd&) {}), std::invalid_argument);
  EXPECT_THROW(scheme.set_row_partition(0, disc->size() + 1, [](Eigen::VectorXd&) {}), std::invalid_argument);
  EXPECT_THROW(scheme.set_row_partition(0, 1, {}), std::invalid_argument);
  AbsorbingParticles<2> boundary;
  boundary.particles = {0};
  boundary.normals = {Eigen::Vector2d(-1, 0)};
  RateFormScheme<2> absorbing(disc, kGms);
  absorbing.set_absorbing(boundary);
  try {
    distribute_rate_form(absorbing);
    ADD_FAILURE() << "absorbing particles accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace sphstab

int main(int argc, char** argv) { return sphstab::test::run_tests_on_all_ranks(argc, argv, sphstab::g_session); }
