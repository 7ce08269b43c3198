#pragma once
/// \file neo_hookean.hpp
/// The compressible Neo-Hookean material of [Ismail2009, §3.3.3]:
///   Psi = mu/2 (I_C - 3) - mu ln J + lambda/2 (ln J)^2                         (3.62)
///   S = mu (I - C^{-1}) + lambda ln J C^{-1}                                   (3.63)
///   P = mu (F - F C^{-1}) + lambda ln J F C^{-1} = mu (F - F^{-T}) + lambda ln J F^{-T}   (3.64)
///   dP_ab/dF_cd = mu delta_ac delta_bd + (mu - lambda ln J) Finv_bc Finv_da + lambda Finv_ba Finv_dc
///   (derived here with d(Finv_ij)/dF_kl = -Finv_ik Finv_lj and d ln J/dF = F^{-T}; not in the thesis).
/// Dim = 2: plane strain (lambda_3 = 1, I_C = tr C + 1). Dim = 1:
///   1D strain (lateral stretches 1, J = F; Ismail's algorithm 5.1, line 15):
///     P = mu (F - 1/F) + lambda ln F / F,  dP/dF = mu (1 + F^-2) + lambda (1 - ln F) / F^2;
///   1D stress (lateral stretch s with P_22 = 0, i.e. g(s) = mu (s^2 - 1) + lambda ln(F s^2) = 0, solved by Newton in
///   the scalar type so that the complex step differentiates through it):
///     P = mu (F - 1/F) + lambda ln(F s^2) / F,
///     dP/dF = mu (1 + F^-2) + lambda [(1/F + 2 s'/s)/F - ln(F s^2)/F^2],  s' = -(lambda/F) / (2 mu s + 2 lambda/s).
///   At F = 1 the 1D-stress tangent is Young's E (s' = -nu).
/// \note The 1D-strain tangent vanishes where mu (F^2 + 1) + lambda (1 - ln F) = 0: for lambda/mu = 49 (nu = 0.49)
///       at F = 3.6307 and 6.3997 (loss of hyperbolicity; cf. [Ismail2009, §5.3]); for nu = 0.3 it stays positive.
/// \note J <= 0 (an inverted particle) has no energy: every evaluation throws std::invalid_argument.
/// \code{.cpp}
/// const auto lame = sphstab::ElasticMaterial::from_young_poisson(200e9, 0.49, 8000);
/// const sphstab::NeoHookean<1> bar(lame);                      // 1D strain (algorithm 5.1)
/// const sphstab::Deformation<double, 1> F = sphstab::Deformation<double, 1>::Constant(2.0);
/// double P11 = bar.stress(F)(0, 0);                            // = T11 (J = F): 18.4821 mu
/// double dP = bar.tangent(F)(0, 0);                            // < 0 for F in (3.6307, 6.3997)
/// \endcode
#include <cmath>
#include <complex>
#include <string>

#include "sphstab/models/hyperelastic_model.hpp"
#include "sphstab/numerics/real_part.hpp"

namespace sphstab {

template <int Dim>
class NeoHookean final : public HyperelasticModelT<Dim, NeoHookean<Dim>> {
  using Base = HyperelasticModelT<Dim, NeoHookean<Dim>>;
  using Base::m_material, Base::m_uniaxial, Base::one_d_stress;

 public:
  /// Throws std::invalid_argument for invalid constants (ElasticMaterial::validate).
  explicit NeoHookean(const ElasticMaterial& material, UniaxialState uniaxial = UniaxialState::Strain)
      : Base(material, uniaxial, "NeoHookean", "neo-hookean") {}
  double volume_ratio(const Deformation<double, Dim>& F) const override {
    if (one_d_stress()) {
      const double s = lateral_stretch<double>(F(0, 0));
      return F(0, 0) * s * s;
    }
    return F.determinant();
  }

  /// The lateral stretch s of 1D stress at the axial stretch F > 0 (g(s) = 0; see the file comment).
  template <class Scalar>
  Scalar lateral_stretch(const Scalar& F) const {
    using std::log;
    const double lam = m_material.lambda(), mu = m_material.mu();
    Scalar s(1.0);
    int converged = -1;
    for (int it = 0; it < 100; ++it) {
      const Scalar g = mu * (s * s - 1.0) + lam * (log(F) + 2.0 * log(s));
      const Scalar dg = 2.0 * mu * s + 2.0 * lam / s;
      const Scalar step = g / dg;
      // Newton can overshoot below 0 from s = 1 for large F: halve towards 0 instead.
      s = detail::re(s - step) > 0 ? Scalar(s - step) : Scalar(0.5 * s);
      if (converged < 0 && std::abs(detail::re(step)) <= 1e-15 * detail::re(s)) converged = it;
      if (converged >= 0 && it >= converged + 2) break;  // two more steps converge the complex part
    }
    return s;
  }

  template <class Scalar>
  Scalar energy_impl(const Deformation<Scalar, Dim>& F) const {
    using std::log;
    const double lam = m_material.lambda(), mu = m_material.mu();
    if (one_d_stress()) {
      const Scalar f = F(0, 0);
      check(f);
      const Scalar s = lateral_stretch(f);
      const Scalar lnJ = log(f * s * s);
      return 0.5 * mu * (f * f + 2.0 * s * s - 3.0) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
    }
    const Scalar J = F.determinant();
    check(J);
    const Scalar lnJ = log(J);
    const Scalar ic = (F.transpose() * F).trace() + double(3 - Dim);  // lateral stretches 1
    return 0.5 * mu * (ic - 3.0) - mu * lnJ + 0.5 * lam * lnJ * lnJ;
  }

  template <class Scalar>
  Deformation<Scalar, Dim> stress_impl(const Deformation<Scalar, Dim>& F) const {
    using std::log;
    const double lam = m_material.lambda(), mu = m_material.mu();
    if (one_d_stress()) {
      const Scalar f = F(0, 0);
      check(f);
      const Scalar s = lateral_stretch(f);
      Deformation<Scalar, Dim> P;
      P(0, 0) = mu * (f - 1.0 / f) + lam * log(f * s * s) / f;
      return P;
    }
    const Scalar J = F.determinant();
    check(J);
    const Deformation<Scalar, Dim> FinvT = F.inverse().transpose();
    return mu * (F - FinvT) + (lam * log(J)) * FinvT;  // (3.64) with F C^{-1} = F^{-T}
  }

  template <class Scalar>
  MaterialTangent<Scalar, Dim> tangent_impl(const Deformation<Scalar, Dim>& F) const {
    using std::log;
    const double lam = m_material.lambda(), mu = m_material.mu();
    MaterialTangent<Scalar, Dim> t;
    if (one_d_stress()) {
      const Scalar f = F(0, 0);
      check(f);
      const Scalar s = lateral_stretch(f);
      const Scalar ds = -(lam / f) / (2.0 * mu * s + 2.0 * lam / s);
      t(0, 0) = mu * (1.0 + 1.0 / (f * f)) + lam * ((1.0 / f + 2.0 * ds / s) / f - log(f * s * s) / (f * f));
      return t;
    }
    const Scalar J = F.determinant();
    check(J);
    const Deformation<Scalar, Dim> Fi = F.inverse();
    const Scalar c = mu - lam * log(J);
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b)
        for (int cc = 0; cc < Dim; ++cc)
          for (int d = 0; d < Dim; ++d)
            t(a * Dim + b, cc * Dim + d) =
                (a == cc && b == d ? Scalar(mu) : Scalar(0)) + c * Fi(b, cc) * Fi(d, a) + lam * Fi(b, a) * Fi(d, cc);
    return t;
  }

 private:
  template <class Scalar>
  static void check(const Scalar& J) {
    const double j = detail::re(J);
    if (!(j > 0)) detail::require_positive_jacobian(j, "NeoHookean");
  }
};

}  // namespace sphstab
