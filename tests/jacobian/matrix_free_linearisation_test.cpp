// The matrix-free A0, A1 (strain -> stress -> divergence) against the assembled analytic_jacobian_2d on random
// vectors: two codings of the same closed form, one as a fused triple product, one as three sweeps.
#include "sphstab/jacobian/matrix_free_linearisation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>
#include <iostream>
#include <random>

#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/artificial_stress_term.hpp"
#include "sphstab/forms/gradient_provider.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_operator.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace matrix_free_linearisation_test {

const ElasticMaterial kMaterial = ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

struct SetCase {
  std::string name;
  std::shared_ptr<const Discretisation<2>> disc;
};

std::shared_ptr<const Discretisation<2>> lattice(LatticeType type, int n, KernelType kernel, double h,
                                                 LatticeOptions opt = {}) {
  Kernel<2> k(kernel);
  opt.support_radius = k.support_radius(h);
  return make_discretisation(make_lattice<2>(type, n, opt), k, h);
}

std::vector<SetCase> particle_sets() {
  std::vector<SetCase> sets;
  sets.push_back({"square fixed layers", lattice(LatticeType::Square, 9, KernelType::CubicSpline, 1.3)});
  sets.push_back({"hex fixed layers", lattice(LatticeType::Hexagonal, 8, KernelType::WendlandC2, 1.5)});
  sets.push_back(
      {"square periodic", lattice(LatticeType::Square, 8, KernelType::QuinticSpline, 1.2, {.periodic = true})});
  // No fixed layers: incomplete neighbourhoods (g != 0), so alpha enters A0 and the four forms differ.
  sets.push_back(
      {"square free surface", lattice(LatticeType::Square, 7, KernelType::CubicSpline, 1.3, {.fixed_layers = 0})});
  // Jittered positions and unequal volumes: no lattice identity helps.
  Kernel<2> k(KernelType::WendlandC2);
  auto jittered = make_lattice<2>(LatticeType::Square, 8, {.support_radius = 2.8, .perturbation = 0.2, .seed = 7});
  for (int i = 0; i < jittered.size(); i += 3) jittered.volume[i] *= 1.3;
  sets.push_back({"jittered unequal volumes", make_discretisation(jittered, k, 1.4)});
  return sets;
}

/// max |a - b| / max |b|.
double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

TEST(MatrixFreeLinearisation, MatchesAssembledOnRandomVectors) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> uniform(-1, 1);
  double worst = 0;
  int cases = 0, products = 0;
  for (const SetCase& s : particle_sets())
    for (MomentumForm form : all_momentum_forms())
      for (PreStrainKind kind : {PreStrainKind::Isotropic, PreStrainKind::UniaxialX}) {
        const Linearisation as = analytic_jacobian_2d(*s.disc, kMaterial, form, kind);
        const MatrixFreeLinearisation mf(*s.disc, kMaterial, form, kind);
        const std::string what = s.name + " " + momentum_form_name(form) + " " + prestrain_kind_name(kind);
        ASSERT_EQ(mf.dofs(), as.dofs()) << what;
        EXPECT_EQ(mf.symmetric(), as.symmetric) << what;
        EXPECT_EQ(mf.complete(), as.complete) << what;
        ++cases;
        for (int trial = 0; trial < 3; ++trial) {
          Eigen::VectorXd x(mf.dofs()), y0(mf.dofs()), y1(mf.dofs()), y(mf.dofs());
          for (auto& v : x) v = uniform(rng);
          mf.apply_A0(x, y0);
          mf.apply_A1(x, y1);
          const double load = 0.37;
          mf.apply(load, x, y);
          const Eigen::VectorXd r0 = as.A0 * x, r1 = as.A1 * x, r = as.at(load) * x;
          // Both sides sum O(100) products of size max |A0| |x| in different orders: round-off only.
          EXPECT_LE(relative_difference(y0, r0), 1e-12) << what;
          EXPECT_LE(relative_difference(y, r), 1e-12) << what;
          worst = std::max({worst, relative_difference(y0, r0), relative_difference(y, r)});
          if (form == MomentumForm::Minus) {
            EXPECT_EQ(y1.cwiseAbs().maxCoeff(), 0.0) << what;
            EXPECT_EQ(r1.cwiseAbs().maxCoeff(), 0.0) << what;
          } else {
            EXPECT_LE(relative_difference(y1, r1), 1e-12) << what;
            worst = std::max(worst, relative_difference(y1, r1));
          }
          products += 3;
        }
      }
  std::cout << "matrix-free vs assembled: largest relative difference " << worst << " over " << cases << " cases, "
            << products << " products\n";
}

TEST(MatrixFreeLinearisation, FormsDifferWhereTheyShould) {
  // Guards the comparison above against a shared blind spot: on the free-surface block the A0 of plus and minus
  // differ (alpha g_i sigma_i), and uniaxial A1 of plus and conservative differ.
  auto d = lattice(LatticeType::Square, 6, KernelType::CubicSpline, 1.3, {.fixed_layers = 0});
  const MatrixFreeLinearisation plus(*d, kMaterial, MomentumForm::Plus, PreStrainKind::UniaxialX);
  const MatrixFreeLinearisation minus(*d, kMaterial, MomentumForm::Minus, PreStrainKind::UniaxialX);
  const MatrixFreeLinearisation cons(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::UniaxialX);
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(plus.dofs(), -1, 1).array().sin();
  Eigen::VectorXd a(plus.dofs()), b(plus.dofs());
  plus.apply_A0(x, a);
  minus.apply_A0(x, b);
  EXPECT_GT(relative_difference(a, b), 1e-3);
  plus.apply_A1(x, a);
  cons.apply_A1(x, b);
  EXPECT_GT(relative_difference(a, b), 1e-3);
}

TEST(MatrixFreeLinearisation, ForceConstructorAndSpectraOperator) {
  auto d = lattice(LatticeType::Hexagonal, 6, KernelType::CubicSpline, 1.3);
  ElasticForm2D force(d, kMaterial, MomentumForm::Uncorrected, PreStrain::uniaxial_x(0.01));
  const MatrixFreeLinearisation from_force(force);
  const MatrixFreeLinearisation direct(*d, kMaterial, MomentumForm::Uncorrected, PreStrainKind::UniaxialX);
  const Linearisation as = analytic_jacobian_2d(force);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(direct.dofs());
  Eigen::VectorXd y(direct.dofs()), z(direct.dofs());
  from_force.apply(-0.2, x, y);
  direct.apply(-0.2, x, z);
  EXPECT_EQ((y - z).cwiseAbs().maxCoeff(), 0.0);

  MatrixFreeOperator op(direct, 0.5, -3.0);
  EXPECT_EQ(op.rows(), direct.dofs());
  EXPECT_EQ(op.cols(), direct.dofs());
  op.perform_op(x.data(), y.data());
  const Eigen::VectorXd r = (0.5 * as.A0 - 3.0 * as.A1) * x;
  EXPECT_LE(relative_difference(y, r), 1e-12);
}

TEST(MatrixFreeLinearisation, HoldsLessThanTheAssembledJacobian) {
  auto d = lattice(LatticeType::Square, 24, KernelType::CubicSpline, 1.3);
  const MatrixFreeLinearisation mf(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const Linearisation as = analytic_jacobian_2d(*d, kMaterial, MomentumForm::Conservative, PreStrainKind::Isotropic);
  const double assembled = 12.0 * (as.A0.nonZeros() + as.A1.nonZeros());
  EXPECT_GT(mf.memory_bytes(), 0.0);
  EXPECT_LE(mf.memory_bytes(), 1.05 * MatrixFreeLinearisation<2>::estimated_bytes(*d));
  EXPECT_GE(mf.memory_bytes(), MatrixFreeLinearisation<2>::estimated_bytes(*d));
  // Per free particle ~4 x (61 + 21) nonzeros of 12 bytes assembled against ~21 pairs of G (all rows) and H (free
  // rows) stored: 3.2x here, where the fixed layers are a quarter of the particles (4x for large n).
  EXPECT_LT(3 * mf.memory_bytes(), assembled) << mf.memory_bytes() << " vs " << assembled;
}

std::string one_line_invalid_argument(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "<no std::invalid_argument>";
}

void expect_error(const std::function<void()>& f, const std::string& fragment) {
  const std::string message = one_line_invalid_argument(f);
  EXPECT_NE(message.find(fragment), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind("MatrixFreeLinearisation", 0), 0u) << message;
}

TEST(MatrixFreeLinearisation, RejectsBadInput) {
  auto d = lattice(LatticeType::Square, 4, KernelType::CubicSpline, 1.2);
  const MatrixFreeLinearisation mf(*d, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic);
  Eigen::VectorXd x = Eigen::VectorXd::Ones(mf.dofs()), y(mf.dofs()), short_x(mf.dofs() - 1);
  expect_error([&] { mf.apply_A0(short_x, y); }, "x has 31 and y 32 entries, need 32");
  expect_error([&] { mf.apply_A1(x, short_x); }, "need 32");
  expect_error([&] { mf.apply(1.0, x, x); }, "share storage");
  Eigen::VectorXd big = Eigen::VectorXd::Ones(40);
  expect_error([&] { mf.apply(1.0, big.head(32), big.segment(4, 32)); }, "share storage");

  expect_error(
      [&] {
        MatrixFreeLinearisation(*d, ElasticMaterial::from_lame(1, -1, 1), MomentumForm::Plus, PreStrainKind::Isotropic);
      },
      "MatrixFreeLinearisation");
  Operators<2> no_hessian = assemble_operators<2>(d->particles, d->neighbours, d->kernel, d->h, {});
  expect_error(
      [&] { MatrixFreeLinearisation(*d, no_hessian, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic); },
      "operator H[x][x] must be");

  ElasticForm2D corrected(d, kMaterial, MomentumForm::Uncorrected, {}, std::make_shared<MinusGradient<2>>());
  expect_error([&] { MatrixFreeLinearisation{corrected}; }, "is not covered");
  ElasticForm2D clamped(d, kMaterial, MomentumForm::Plus);
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(2 * (d->size() - d->free_count()));
  fixed[0] = 0.01;
  clamped.set_fixed_displacement(fixed);
  expect_error([&] { MatrixFreeLinearisation{clamped}; }, "zero fixed displacements");
  ElasticForm2D with_term(d, kMaterial, MomentumForm::Plus);
  with_term.add_term(std::make_shared<ArtificialStressTerm>(d));
  expect_error([&] { MatrixFreeLinearisation{with_term}; }, "additional momentum terms");
}

TEST(MatrixFreeLinearisation, ChecksMemoryBeforeBuilding) {
  struct LimitGuard {
    ~LimitGuard() { set_memory_limit_bytes(0); }
  } guard;
  auto d = lattice(LatticeType::Square, 8, KernelType::CubicSpline, 1.3);
  set_memory_limit_bytes(0.5 * MatrixFreeLinearisation<2>::estimated_bytes(*d));
  EXPECT_THROW(MatrixFreeLinearisation(*d, kMaterial, MomentumForm::Plus, PreStrainKind::Isotropic), MemoryLimitError);
}

}  // namespace
}  // namespace sphstab
