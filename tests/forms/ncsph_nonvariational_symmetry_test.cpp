// The NCSPH strain with the plain plus divergence (FiniteStrainTotalLagrangian, not a variational pair): its
// linearisation at rest is symmetric on a periodic lattice (one constant NCSPH correction: K = s G) and has no
// growing mode there; on a free block the surface particles' corrections make it non-symmetric and unstable, while
// the variational NCSPH form on the same block stays symmetric (studies/tl-instability).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/variational_total_lagrangian.hpp"
#include "sphstab/growth/growth_rate.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace ncsph_nonvariational_symmetry_test {

struct Result {
  double asymmetry;
  GrowthAnalysis growth;
};

Result linearise(bool periodic, bool variational) {
  const double dx = 0.005, h = 1.5 * dx;
  const Kernel<2> kernel(KernelType::WendlandC2);
  const ParticleSet<2> set = periodic ? make_lattice<2>(LatticeType::Square, 8, {.spacing = dx, .periodic = true})
                                      : make_lattice<2>(LatticeType::Square, 8, {.spacing = dx, .fixed_layers = 0});
  const auto disc = make_discretisation(set, kernel, h);
  const auto svk = std::make_shared<StVenantKirchhoff<2>>(ElasticMaterial::from_lame(2e6, 0.5e6, 1.0));
  std::unique_ptr<ForceFunction> tl;
  if (variational) {
    tl = std::make_unique<VariationalTotalLagrangian<2>>(disc, svk, 1000.0,
                                                         make_gradient_provider<2>(Correction::Ncsph));
  } else {
    FiniteStrainOptions<2> opt;
    opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
    tl = std::make_unique<FiniteStrainTotalLagrangian<2>>(disc, svk, 1000.0, opt);
  }
  const Eigen::MatrixXd A(jacobian(*tl, Eigen::VectorXd::Zero(tl->dofs())));
  Eigen::VectorXd x(tl->dofs());
  for (int f = 0; f < disc->free_count(); ++f) x[2 * f] = x[2 * f + 1] = set.x(disc->free[f], 0);
  return {(A - A.transpose()).norm() / A.norm(), growth_rate(A, x)};
}

TEST(NcsphNonVariational, SymmetricAndStableOnAPeriodicLattice) {
  const Result r = linearise(true, false);
  EXPECT_LT(r.asymmetry, 1e-12);
  EXPECT_TRUE(r.growth.unstable.empty());
}

TEST(NcsphNonVariational, NonSymmetricAndUnstableOnAFreeBlockUnlikeTheVariationalForm) {
  const Result r = linearise(false, false);
  EXPECT_GT(r.asymmetry, 0.05);  // the study finds 0.15 on a 12 x 12 block
  ASSERT_FALSE(r.growth.unstable.empty());
  EXPECT_GT(r.growth.growth_rate, 1e3 * r.growth.tolerance);
  const Result v = linearise(false, true);
  EXPECT_LT(v.asymmetry, 1e-12);
  EXPECT_TRUE(v.growth.unstable.empty());
}

}  // namespace
}  // namespace sphstab
