// The PETSc/SLEPc critical strain (distributed/petsc_critical_load.hpp) against the single-process direct route
// (critical_load, Criterion::Definiteness: CHOLMOD bisection + shifted Spectra over CHOLMOD) on square lattices with
// fixed layers. Run by ctest under `mpirun -np 1` and `mpirun -np 2` (tests/CMakeLists.txt); every rank runs every
// test, and the result must be the same on all ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "mpi_test_main.hpp"
#include "sphstab/distributed/petsc_critical_load.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"

namespace sphstab {
namespace {

PetscSession* g_session = nullptr;

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

std::shared_ptr<const Discretisation<2>> square(int n, double h = 1.3) {
  const Kernel<2> k(KernelType::CubicSpline);
  return make_discretisation(strain_lattice_2d(LatticeType::Square, k, h, n), k, h);
}

CriticalLoad direct(const Linearisation& lin, LoadDirection direction) {
  CriticalLoadOptions opt = CriticalLoadOptions::strain_2d();
  opt.criterion = Criterion::Definiteness;
  opt.want_mode = false;
  return critical_load(lin, direction, opt);
}

/// The same value on every rank (bitwise): max over ranks of v and of -v.
bool same_on_all_ranks(double v) { return max_over_ranks(v) == v && -max_over_ranks(-v) == v; }

struct Case {
  int n;
  MomentumForm form;
  PreStrainKind kind;
  PetscEigenMethod method;
  PetscSolver solver;
};

TEST(PetscCriticalLoad, AgreesWithTheDirectRoute) {
  const std::vector<Case> cases = {
      {16, MomentumForm::Conservative, PreStrainKind::Isotropic, PetscEigenMethod::ShiftInvert, PetscSolver::Cholesky},
      {16, MomentumForm::Plus, PreStrainKind::Isotropic, PetscEigenMethod::ShiftInvert, PetscSolver::Cholesky},
      {16, MomentumForm::Conservative, PreStrainKind::UniaxialX, PetscEigenMethod::ShiftInvert, PetscSolver::Cholesky},
      {16, MomentumForm::Conservative, PreStrainKind::Isotropic, PetscEigenMethod::KrylovSchur, PetscSolver::Cholesky},
      {16, MomentumForm::Conservative, PreStrainKind::Isotropic, PetscEigenMethod::KrylovSchur, PetscSolver::CgGamg},
      {16, MomentumForm::Conservative, PreStrainKind::Isotropic, PetscEigenMethod::Lobpcg, PetscSolver::Cholesky},
      {32, MomentumForm::Conservative, PreStrainKind::Isotropic, PetscEigenMethod::ShiftInvert, PetscSolver::Cholesky},
      {32, MomentumForm::Uncorrected, PreStrainKind::Isotropic, PetscEigenMethod::ShiftInvert, PetscSolver::Cholesky},
  };
  double worst = 0;
  for (const Case& c : cases) {
    auto d = square(c.n);
    const Linearisation lin = analytic_jacobian_2d(*d, kMaterial, c.form, c.kind);
    const CriticalLoad ref = direct(lin, LoadDirection::Tension);
    PetscCriticalLoadOptions o{.method = c.method, .solver = c.solver};
    if (c.method == PetscEigenMethod::Lobpcg) {  // LOBPCG's residual converges slowly (clustered top of K^-1 L)
      o.tol = 1e-8;                              // eigenvalue error ~ tol^2: still far below the asserted 1e-8
      o.max_iterations = 5000;
    }
    const PetscCriticalLoad r = petsc_critical_load(lin, LoadDirection::Tension, o);
    const std::string what = "n=" + std::to_string(c.n) + " " + momentum_form_name(c.form) + " " +
                             prestrain_kind_name(c.kind) + " " + r.solver + " on " + std::to_string(r.ranks) + " ranks";
    ASSERT_EQ(ref.info(), Status::Successful) << what << ": " << ref.reason;
    ASSERT_EQ(r.info(), Status::Successful) << what << ": " << r.reason;
    ASSERT_TRUE(std::isfinite(ref.load) && ref.load > 0) << what;
    EXPECT_EQ(r.global_dofs, lin.dofs());
    EXPECT_EQ(r.lattice_rows, c.n) << what;
    EXPECT_LE(r.residual, 1e-6) << what;
    EXPECT_TRUE(same_on_all_ranks(r.load)) << what << ": load differs between ranks";
    const double rel = std::abs(r.load - ref.load) / ref.load;
    EXPECT_LE(rel, 1e-8) << what << ": " << r.load << " vs direct " << ref.load;
    worst = std::max(worst, rel);
    if (g_session->rank() == 0)
      std::cout << what << ": e_crit " << r.load << " (direct " << ref.load << ", relative " << rel << "), "
                << r.iterations << " SLEPc iterations, " << r.ksp_iterations << " KSP iterations, residual "
                << r.residual << "\n";
  }
  if (g_session->rank() == 0) std::cout << "largest relative difference PETSc vs direct: " << worst << "\n";
}

TEST(PetscCriticalLoad, CubicLatticeAgreesWithTheDirectRouteAndTheMatrixFreeIteration) {
  // 3D: 7^3 free particles of a cubic lattice (1029 DOFs), assembled by products of the matrix-free linearisation;
  // the lattice "rows" of the partition are the z planes.
  const Kernel<3> k(KernelType::CubicSpline);
  const auto d =
      make_discretisation(make_lattice<3>(LatticeType::Cubic, 7, {.support_radius = k.support_radius(1.3)}), k, 1.3);
  const MatrixFreeLinearisation<3> mf(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const Linearisation lin = assemble_by_products(mf);
  const CriticalLoad ref = direct(lin, LoadDirection::Tension);
  const PetscCriticalLoad r = petsc_critical_load(lin, LoadDirection::Tension);
  const MatrixFreeCriticalLoad it = matrix_free_critical_load(mf, LoadDirection::Tension,
                                                              {.method = MatrixFreeEigenMethod::BlockLobpcg,
                                                               .residual_tol = 1e-9,
                                                               .max_iterations = 20000,
                                                               .preconditioner = MatrixFreePreconditioner::None});
  ASSERT_EQ(ref.info(), Status::Successful) << ref.reason;
  ASSERT_EQ(r.info(), Status::Successful) << r.reason;
  ASSERT_EQ(it.info(), Status::Successful) << it.reason;
  EXPECT_EQ(r.global_dofs, 3 * 343);
  EXPECT_EQ(r.lattice_rows, 7);
  EXPECT_TRUE(same_on_all_ranks(r.load));
  EXPECT_LE(std::abs(r.load - ref.load) / ref.load, 1e-8) << r.load << " vs direct " << ref.load;
  EXPECT_LE(std::abs(it.load - ref.load) / ref.load, 1e-8) << it.load << " vs direct " << ref.load;
  if (g_session->rank() == 0)
    std::cout << "3D n=7 on " << r.ranks << " ranks: e_crit " << r.load << " (direct " << ref.load << ", matrix-free "
              << it.load << ")\n";
}

TEST(PetscCriticalLoad, CompressionHasTheSignOfTheDirectRoute) {
  auto d = square(16);
  const Linearisation lin = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::UniaxialX);
  const CriticalLoad ref = direct(lin, LoadDirection::Compression);
  const PetscCriticalLoad r = petsc_critical_load(lin, LoadDirection::Compression);
  ASSERT_EQ(ref.info(), Status::Successful) << ref.reason;
  ASSERT_EQ(r.info(), Status::Successful) << r.reason;
  if (std::isinf(ref.load)) {
    EXPECT_EQ(r.load, ref.load);
  } else {
    EXPECT_LT(r.load, 0);
    EXPECT_LE(std::abs(r.load - ref.load) / std::abs(ref.load), 1e-8) << r.load << " vs " << ref.load;
  }
}

TEST(PetscCriticalLoad, NonConvergenceIsAStatusWithResidualAndIterations) {
  auto d = square(12);
  const Linearisation lin = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  // One Krylov-Schur restart with a 3-vector basis cannot reach 1e-10.
  const PetscCriticalLoad r =
      petsc_critical_load(lin, LoadDirection::Tension, {.max_iterations = 1, .ncv = 3, .from_options = false});
  EXPECT_EQ(r.info(), Status::NotConverging);
  EXPECT_TRUE(std::isnan(r.load));
  EXPECT_EQ(r.converged, 0);
  EXPECT_NE(r.reason.find("iterations"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("residual"), std::string::npos) << r.reason;
  EXPECT_EQ(r.reason.find('\n'), std::string::npos) << r.reason;
  // An inner CG capped at 2 steps cannot reach 1e-12: the solve fails and says where.
  const PetscCriticalLoad k = petsc_critical_load(lin, LoadDirection::Tension,
                                                  {.method = PetscEigenMethod::KrylovSchur,
                                                   .solver = PetscSolver::CgIcc,
                                                   .ksp_max_iterations = 2,
                                                   .from_options = false});
  EXPECT_EQ(k.info(), Status::NotConverging) << k.reason;
  EXPECT_TRUE(std::isnan(k.load));
  EXPECT_NE(k.reason.find("KSP"), std::string::npos) << k.reason;
  EXPECT_NE(k.reason.find("residual"), std::string::npos) << k.reason;
  EXPECT_EQ(k.reason.find('\n'), std::string::npos) << k.reason;
  // Shift-invert needs the direct solver: bad input, one line.
  EXPECT_THROW(petsc_critical_load(lin, LoadDirection::Tension, {.solver = PetscSolver::CgGamg}),
               std::invalid_argument);
}

TEST(PetscCriticalLoad, RowPartitionOwnsWholeRows) {
  auto d = square(10);
  const Eigen::MatrixXd x = d->free_positions();
  for (int ranks : {1, 2, 3, 7, 10}) {
    const LatticeRowPartition p = lattice_row_partition(x, ranks);
    EXPECT_EQ(p.rows, 10);
    ASSERT_EQ(static_cast<int>(p.particle_offset.size()), ranks + 1);
    EXPECT_EQ(p.particle_offset.front(), 0);
    EXPECT_EQ(p.particle_offset.back(), x.rows());
    std::vector<int> seen(x.rows(), 0);
    for (int k : p.order) ++seen[k];
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    for (int r = 0; r < ranks; ++r) {
      const int count = p.particle_offset[r + 1] - p.particle_offset[r];
      EXPECT_EQ(count % 10, 0) << "rank " << r << " of " << ranks << " owns part of a row";
      EXPECT_GE(count / 10, 10 / ranks);
      EXPECT_LE(count / 10, (10 + ranks - 1) / ranks);
      // Row order: y never decreases.
      for (int k = p.particle_offset[r] + 1; k < p.particle_offset[r + 1]; ++k)
        EXPECT_LE(x(p.order[k - 1], 1), x(p.order[k], 1) + 1e-12);
    }
  }
}

TEST(PetscCriticalLoad, MoreRanksThanRowsIsAOneLineError) {
  auto d = square(3);
  try {
    lattice_row_partition(d->free_positions(), 4);
    FAIL() << "4 ranks for 3 rows accepted";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("4 MPI ranks for a lattice of 3 rows"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  if (g_session->size() > 1) {  // the solver itself refuses a lattice with fewer rows than ranks, on every rank
    auto one = square(1);
    const Linearisation lin =
        analytic_jacobian_2d(*one, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
    try {
      petsc_critical_load(lin, LoadDirection::Tension);
      FAIL() << g_session->size() << " ranks for 1 row accepted";
    } catch (const std::invalid_argument& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("MPI ranks for a lattice of 1 rows"), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace sphstab

int main(int argc, char** argv) { return sphstab::test::run_tests_on_all_ranks(argc, argv, sphstab::g_session); }
