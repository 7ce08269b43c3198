// The 2D TL-versus-UL critical pre-strain (Ismail 2009 §4.7; studies/tl-ul-pairing, 2D section) on a small block:
// the UL forms' critical pre-strain from the engine (analytic Jacobian) lies in the bracket of an independent Cholesky
// sweep of the complex-step Jacobian of the force itself, and the finite-strain TL form with Hooke's law does not see
// the pre-stretch at all (A1 = 0 to round-off, critical pre-strain infinite).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/particles/block_lattice.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {
namespace tl_ul_critical_2d_test {

constexpr int kNx = 9, kNy = 3;

/// 9 x 3 free particles, cubic spline h = 1.3 dx, fixed layers two supports deep (the TL strain of the fixed
/// neighbours of free particles needs complete neighbourhoods of their own).
std::shared_ptr<const Discretisation<2>> block() {
  const Kernel<2> k(KernelType::CubicSpline);
  return make_discretisation(
      make_block_lattice_2d(kNx, kNy, {.spacing = 1.0, .support_radius = 2 * k.support_radius(1.3)}), k, 1.3);
}

const ElasticMaterial kLame = ElasticMaterial::from_young_poisson(1.0, 0.3, 1.0);
const ElasticMaterial& kMaterial = kLame;

bool positive_definite(const SparseMatrix<>& a) {
  return is_positive_definite(ColSparseMatrix(SparseMatrix<>(0.5 * (a + SparseMatrix<>(a.transpose())))));
}

class UlCritical2D : public testing::TestWithParam<std::pair<MomentumForm, PreStrainKind>> {};

// Engine (analytic A0 + e A1, bisection and generalised eigenproblem) against a Cholesky sweep of the complex-step
// A0 + e A1 on the grid e_k = 1e-5 * 1.01^k: last positive definite < e_crit <= first not.
TEST_P(UlCritical2D, EngineInsideCholeskySweepBracket) {
  const auto [form, kind] = GetParam();
  const auto disc = block();
  const CriticalLoad r = critical_load(analytic_jacobian_2d(*disc, kMaterial, form, kind), LoadDirection::Tension,
                                       CriticalLoadOptions::strain_2d());
  ASSERT_EQ(r.info(), Status::Successful);
  ASSERT_TRUE(std::isfinite(r.load) && r.load > 0);
  const Linearisation cs =
      affine_jacobian(ElasticForm2D(disc, kMaterial, form, PreStrain{kind, 0}), Eigen::VectorXd::Zero(disc->dofs()));
  double lo = 0, hi = 0;
  for (double e = 1e-5; e < 1; e *= 1.01) {
    if (!positive_definite(cs.at(e))) {
      hi = e;
      break;
    }
    lo = e;
  }
  ASSERT_GT(hi, 0) << "the sweep found no loss of definiteness";
  EXPECT_LT(lo, r.load);
  EXPECT_LE(r.load, hi);
}

INSTANTIATE_TEST_SUITE_P(Forms, UlCritical2D,
                         testing::Values(std::pair{MomentumForm::Conservative, PreStrainKind::UniaxialX},
                                         std::pair{MomentumForm::Conservative, PreStrainKind::Isotropic},
                                         std::pair{MomentumForm::Plus, PreStrainKind::Isotropic}),
                         [](const testing::TestParamInfo<UlCritical2D::ParamType>& info) {
                           std::string name =
                               momentum_form_name(info.param.first) + "_" + prestrain_kind_name(info.param.second);
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// TL, Hooke plane strain, at the affinely pre-stretched states u = e d.X (fixed layers following): the Jacobian does
// not depend on e (||A1|| / ||A0|| < 1e-12), so the engine gives an infinite critical pre-strain; the same block's UL
// conservative form has a finite one.
TEST(TlCritical2D, HookeStiffnessIndependentOfPreStretch) {
  const auto disc = block();
  const int nfree = disc->free_count();
  auto hooke = std::make_shared<Hooke<2>>(kLame);
  FiniteStrainTotalLagrangian<2> tl(disc, hooke, 1.0);
  for (const Eigen::Vector2d d : {Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)}) {
    auto affine = [&](double e, bool fixed) {
      Eigen::VectorXd u(2 * (fixed ? disc->size() - nfree : nfree));
      for (int i = 0, k = 0; i < disc->size(); ++i)
        if ((disc->free_slot[i] < 0) == fixed) {
          u.segment<2>(2 * k++) = e * d.cwiseProduct(disc->particles.x.row(i).transpose());
        }
      return u;
    };
    Linearisation lin;
    tl.set_fixed_displacement(affine(0, true));
    lin.A0 = jacobian(tl, Eigen::VectorXd::Zero(2 * nfree));
    const double e1 = 0.2;
    tl.set_fixed_displacement(affine(e1, true));
    Eigen::VectorXd a;
    tl.acceleration(affine(e1, false), a);
    EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-13);  // the pre-stretched state is an equilibrium
    lin.A1 = SparseMatrix<>((jacobian(tl, affine(e1, false)) - lin.A0) / e1);
    lin.symmetric = true;
    lin.dofs_per_particle = 2;
    EXPECT_LT(lin.A1.norm() / lin.A0.norm(), 1e-12);
    const CriticalLoad r = critical_load(lin, LoadDirection::Tension, CriticalLoadOptions::strain_2d());
    EXPECT_EQ(r.info(), Status::Successful);
    EXPECT_TRUE(std::isinf(r.load) && r.load > 0);
  }
}

}  // namespace
}  // namespace sphstab
