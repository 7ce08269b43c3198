// The finite-strain materials (models/hooke.hpp, st_venant_kirchhoff.hpp, neo_hookean.hpp): P = dPsi/dF and the
// tangent = dP/dF by complex step, the linear elastic limit at F = I, frame indifference, the analytic uniaxial
// Cauchy stress table of [Ismail2009, (5.5)] (studies/tl-neo-hookean-1d), and the loss of hyperbolicity at nu = 0.49.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <vector>

#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"

namespace sphstab {
namespace hyperelastic_models_test {

using cd = std::complex<double>;
constexpr double kStep = 1e-30;  // complex step: no cancellation, exact to round-off

Deformation<double, 1> stretch(double f) { return Deformation<double, 1>::Constant(f); }

/// mu = 1 and lambda from nu: E = 2 (1 + nu).
ElasticMaterial lame_for(double nu) { return ElasticMaterial::from_young_poisson(2 * (1 + nu), nu, 1.0); }

template <int Dim>
std::vector<std::shared_ptr<const HyperelasticModel<Dim>>> all_models(double nu) {
  const ElasticMaterial l = lame_for(nu);
  std::vector<std::shared_ptr<const HyperelasticModel<Dim>>> m;
  for (UniaxialState s : {UniaxialState::Strain, UniaxialState::Stress}) {
    if (Dim == 2 && s == UniaxialState::Stress) continue;  // Dim 2 is plane strain
    m.push_back(std::make_shared<Hooke<Dim>>(l, s));
    m.push_back(std::make_shared<StVenantKirchhoff<Dim>>(l, s));
    m.push_back(std::make_shared<NeoHookean<Dim>>(l, s));
  }
  return m;
}

/// Random F with entries I + U(-0.4, 0.4) (J > 0 checked), finite strain.
template <int Dim>
Deformation<double, Dim> random_deformation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (;;) {
    Deformation<double, Dim> F = Deformation<double, Dim>::Identity();
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) F(a, b) += u(rng);
    if (F.determinant() > 0.3) return F;
  }
}

template <int Dim>
void check_derivatives(double nu) {
  std::mt19937_64 rng(11);
  for (const auto& m : all_models<Dim>(nu)) {
    for (int trial = 0; trial < 5; ++trial) {
      const Deformation<double, Dim> F = random_deformation<Dim>(rng);
      const Deformation<double, Dim> P = m->stress(F);
      const MaterialTangent<double, Dim> A = m->tangent(F);
      for (int c = 0; c < Dim; ++c)
        for (int d = 0; d < Dim; ++d) {
          Deformation<cd, Dim> Fc = F.template cast<cd>();
          Fc(c, d) += cd(0, kStep);
          // P_cd = dPsi/dF_cd
          const double dpsi = m->energy(Fc).imag() / kStep;
          EXPECT_NEAR(dpsi, P(c, d), 1e-12 * (1 + P.cwiseAbs().maxCoeff())) << m->name() << " P" << c << d;
          // column (c, d) of the tangent = dP/dF_cd; the complex tangent agrees with the real one
          const Deformation<cd, Dim> Pc = m->stress(Fc);
          for (int a = 0; a < Dim; ++a)
            for (int b = 0; b < Dim; ++b) {
              EXPECT_NEAR(Pc(a, b).imag() / kStep, A(a * Dim + b, c * Dim + d), 1e-12 * (1 + A.cwiseAbs().maxCoeff()))
                  << m->name() << " dP" << a << b << "/dF" << c << d;
              EXPECT_NEAR(Pc(a, b).real(), P(a, b), 1e-14 * (1 + P.cwiseAbs().maxCoeff())) << m->name();
            }
        }
      const Deformation<cd, Dim> Fcast = F.template cast<cd>();
      EXPECT_LT((m->tangent(Fcast).real() - A).cwiseAbs().maxCoeff(), 1e-13 * A.cwiseAbs().maxCoeff()) << m->name();
    }
  }
}

TEST(HyperelasticModels, StressIsTheEnergyDerivativeAndTangentTheStressDerivative1D) {
  for (double nu : {0.3, 0.49, -0.2}) check_derivatives<1>(nu);
}

TEST(HyperelasticModels, StressIsTheEnergyDerivativeAndTangentTheStressDerivative2D) {
  for (double nu : {0.3, 0.49, -0.2}) check_derivatives<2>(nu);
}

TEST(HyperelasticModels, LinearElasticLimitAtTheIdentity) {
  for (double nu : {0.3, 0.49}) {
    const ElasticMaterial l = lame_for(nu);
    for (const auto& m : all_models<2>(nu)) {
      const Deformation<double, 2> I = Deformation<double, 2>::Identity();
      EXPECT_EQ(m->stress(I).cwiseAbs().maxCoeff(), 0.0) << m->name();
      EXPECT_NEAR(m->energy(I), 0.0, 1e-15) << m->name();
      const MaterialTangent<double, 2> A = m->tangent(I);
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
          for (int c = 0; c < 2; ++c)
            for (int d = 0; d < 2; ++d) {
              const double C = l.lambda() * (a == b) * (c == d) + l.mu() * ((a == c) * (b == d) + (a == d) * (b == c));
              EXPECT_NEAR(A(2 * a + b, 2 * c + d), C, 1e-13 * l.lambda()) << m->name() << a << b << c << d;
            }
    }
    for (const auto& m : all_models<1>(nu)) {
      const Deformation<double, 1> I = Deformation<double, 1>::Identity();
      EXPECT_NEAR(m->stress(I)(0, 0), 0.0, 1e-15) << m->name();
      // 1D strain: lambda + 2 mu [Ismail2009, (4.16)]; 1D stress: Young's E (4.21)-(4.22)
      const double M = m->uniaxial() == UniaxialState::Strain
                           ? l.lambda() + 2 * l.mu()
                           : l.mu() * (3 * l.lambda() + 2 * l.mu()) / (l.lambda() + l.mu());
      EXPECT_NEAR(m->tangent(I)(0, 0), M, 1e-13 * M) << m->name();
    }
  }
}

TEST(HyperelasticModels, FrameIndifferenceOfTheHyperelasticModelsOnly) {
  std::mt19937_64 rng(5);
  const ElasticMaterial l = lame_for(0.3);
  const NeoHookean<2> nh(l);
  const StVenantKirchhoff<2> svk(l);
  const Hooke<2> hooke(l);
  for (double angle : {0.3, 1.1, 2.5}) {
    Deformation<double, 2> Q;
    Q << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    const Deformation<double, 2> F = random_deformation<2>(rng);
    const Deformation<double, 2> QF = Q * F;
    for (const HyperelasticModel<2>* m : std::vector<const HyperelasticModel<2>*>{&nh, &svk}) {
      EXPECT_LT((m->stress(QF) - Q * m->stress(F)).cwiseAbs().maxCoeff(), 1e-13) << m->name();
      EXPECT_NEAR(m->energy(QF), m->energy(F), 1e-13) << m->name();
    }
    // Hooke's small-strain law is not objective: a finite rotation of the identity is stressed.
    EXPECT_GT(hooke.stress(Q).cwiseAbs().maxCoeff(), 0.1 * l.mu()) << angle;
  }
}

// The table of [Ismail2009, (5.5)], T11/mu for lambda_3 = 1 (4 decimals), checked against the models' Cauchy stress
// T = J^{-1} P F^T [Ismail2009, (3.33), (5.5)].
struct TableRow {
  double nu, lambda2;
  std::array<double, 5> t11;  // at lambda_1 = 1.5, 2, 3, 4, 6
};
const std::array<double, 5> kStretches{1.5, 2, 3, 4, 6};
const std::vector<TableRow> kTable{{0.3, 1, {1.2388, 2.0199, 3.2160, 4.2699, 6.2813}},
                                   {0.3, 2, {0.9660, 1.2699, 1.7813, 2.2649, 3.2273}},
                                   {0.49, 1, {14.0785, 18.4821, 20.6107, 20.7321, 20.4660}},
                                   {0.49, 2, {18.3607, 17.7321, 15.9660, 14.6116, 13.0634}}};

TEST(HyperelasticModels, NeoHookeanUniaxialCauchyStressMatchesTheTable) {
  for (const TableRow& row : kTable) {
    const ElasticMaterial l = lame_for(row.nu);
    ASSERT_NEAR(l.mu(), 1.0, 1e-15);
    const NeoHookean<1> bar(l);  // 1D strain: lambda_2 = lambda_3 = 1
    const NeoHookean<2> plane(l);
    for (int k = 0; k < 5; ++k) {
      Deformation<double, 2> F = Deformation<double, 2>::Zero();
      F(0, 0) = kStretches[k];
      F(1, 1) = row.lambda2;
      EXPECT_NEAR(plane.cauchy_stress(F)(0, 0), row.t11[k], 5.01e-5) << row.nu << " " << row.lambda2 << " " << F(0, 0);
      if (row.lambda2 == 1) {
        const Deformation<double, 1> f = stretch(kStretches[k]);
        EXPECT_NEAR(bar.cauchy_stress(f)(0, 0), row.t11[k], 5.01e-5) << row.nu << " " << f(0, 0);
        EXPECT_NEAR(bar.stress(f)(0, 0), row.t11[k], 5.01e-5) << "1D strain: J = F, so P11 = T11";
      }
    }
  }
  // lambda_1 = 1, lambda_2 = 2: 0.5199 (nu 0.3), 16.9821 (nu 0.49)
  const Deformation<double, 2> F = Eigen::Vector2d(1, 2).asDiagonal();
  EXPECT_NEAR(NeoHookean<2>(lame_for(0.3)).cauchy_stress(F)(0, 0), 0.5199, 5.01e-5);
  EXPECT_NEAR(NeoHookean<2>(lame_for(0.49)).cauchy_stress(F)(0, 0), 16.9821, 5.01e-5);
}

TEST(HyperelasticModels, NeoHookeanOneDimensionalStressHasNoLateralStress) {
  const ElasticMaterial l = lame_for(0.3);
  const NeoHookean<1> bar(l, UniaxialState::Stress);
  for (double f : {0.5, 0.9, 1.0, 1.3, 3.0, 6.0}) {
    const double s = bar.lateral_stretch(f);
    // principal P_22 of [Ismail2009, (5.4)] with lambda_2 = lambda_3 = s
    EXPECT_NEAR(l.mu() * (s - 1 / s) + l.lambda() * std::log(f * s * s) / s, 0.0, 1e-13) << f;
    EXPECT_EQ(f > 1, s < 1) << f;  // lateral contraction in tension
  }
  // small strain: P = E (F - 1) + O((F - 1)^2)
  const double e = 1e-5;
  EXPECT_NEAR(bar.stress(stretch(1 + e))(0, 0) / e, l.young(), 1e-4 * l.young());
}

/// The 1D-strain tangent dP/dF of [Ismail2009]'s 1D Neo-Hookean law (algorithm 5.1) changes sign where
/// mu (F^2 + 1) + lambda (1 - ln F) = 0.
TEST(HyperelasticModels, NeoHookeanLosesHyperbolicityOnlyForNearlyIncompressible) {
  const NeoHookean<1> nh49(lame_for(0.49)), nh30(lame_for(0.3));
  auto tangent = [](const NeoHookean<1>& m, double f) { return m.tangent(stretch(f))(0, 0); };
  EXPECT_GT(tangent(nh49, 3.6306), 0);
  EXPECT_LT(tangent(nh49, 3.6308), 0);
  EXPECT_LT(tangent(nh49, 6.3996), 0);
  EXPECT_GT(tangent(nh49, 6.3998), 0);
  for (double f = 0.2; f <= 20; f += 0.01) EXPECT_GT(tangent(nh30, f), 0) << f;
}

TEST(HyperelasticModels, EigenExpressionsSelectTheOverloadOfTheirScalar) {
  const NeoHookean<2> nh(lame_for(0.3));
  Deformation<double, 2> F;
  F << 1.3, 0.2, -0.1, 0.8;
  const Deformation<double, 2> Q = Eigen::Rotation2Dd(0.4).toRotationMatrix();
  EXPECT_EQ((nh.stress(Q * F) - nh.stress(Deformation<double, 2>(Q * F))).cwiseAbs().maxCoeff(), 0.0);
  const std::complex<double> psi = nh.energy(F.cast<cd>() * cd(1, 0));
  EXPECT_EQ(psi.real(), nh.energy(F));
  EXPECT_EQ(NeoHookean<1>(lame_for(0.3)).tangent(Deformation<double, 1>::Constant(2.0))(0, 0),
            NeoHookean<1>(lame_for(0.3)).tangent(stretch(2.0))(0, 0));
}

TEST(HyperelasticModels, BadInput) {
  EXPECT_THROW(ElasticMaterial::from_young_poisson(1, 0.5, 1.0), std::invalid_argument);
  EXPECT_THROW(ElasticMaterial::from_young_poisson(1, -1, 1.0), std::invalid_argument);
  EXPECT_THROW(ElasticMaterial::from_young_poisson(0, 0.3, 1.0), std::invalid_argument);
  EXPECT_THROW(NeoHookean<2>(ElasticMaterial::from_lame(1, 0, 1.0)), std::invalid_argument);
  EXPECT_THROW(StVenantKirchhoff<2>(ElasticMaterial::from_lame(-1, 1, 1.0)), std::invalid_argument);  // nu < -1
  EXPECT_THROW(Hooke<1>(ElasticMaterial::from_lame(NAN, 1, 1.0)), std::invalid_argument);
  const NeoHookean<2> nh(lame_for(0.3));
  Deformation<double, 2> inverted;
  inverted << -1, 0, 0, 1;
  try {
    nh.stress(inverted);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("J = det F"), std::string::npos) << e.what();
  }
  EXPECT_THROW(NeoHookean<1>(lame_for(0.3)).energy(stretch(0.0)), std::invalid_argument);
}

}  // namespace
}  // namespace sphstab
