#pragma once
/// \file st_venant_kirchhoff.hpp
/// The St Venant-Kirchhoff material [Ismail2009, §3.3.2]:
///   E = 1/2 (F^T F - I),  Psi = lambda/2 (tr E)^2 + mu E:E,  S = lambda tr(E) I + 2 mu E,  P = F S
/// (the thesis prints "S = FP" and omits the 1/2 in E; P = F S is the correct relation, [Ismail2009, §3.3]), and
///   dP_ab/dF_cd = delta_ac S_db + lambda F_ab F_cd + mu (F_ad F_cb + (F F^T)_ac delta_bd)   (derived here; checked
///   against the complex-step derivative of P in tests/models/hyperelastic_models_test.cpp).
/// Dim = 2: plane strain (E_33 = 0). Dim = 1: S = M E_11 with M = lambda + 2 mu (1D strain) or Young's E (1D stress:
/// S is linear in E, so S_22 = S_33 = 0 gives E_22 = E_33 = -nu E_11 and S_11 = E E_11 exactly, at any stretch).
/// \code{.cpp}
/// const sphstab::StVenantKirchhoff<2> svk(sphstab::ElasticMaterial::from_lame(1.2, 0.8, 1.0));  // plane strain
/// sphstab::Deformation<double, 2> F;
/// F << 1.2, 0.1, 0.0, 0.9;
/// const sphstab::Deformation<double, 2> P = svk.stress(F);    // F S
/// const sphstab::MaterialTangent<double, 2> A = svk.tangent(F);  // 4 x 4, row-major vec(F)
/// \endcode
#include <string>

#include "sphstab/models/hyperelastic_model.hpp"

namespace sphstab {

template <int Dim>
class StVenantKirchhoff final : public HyperelasticModelT<Dim, StVenantKirchhoff<Dim>> {
  using Base = HyperelasticModelT<Dim, StVenantKirchhoff<Dim>>;
  using Base::m_material, Base::m_uniaxial, Base::one_d_stress;

 public:
  /// Throws std::invalid_argument for invalid constants (ElasticMaterial::validate).
  explicit StVenantKirchhoff(const ElasticMaterial& material, UniaxialState uniaxial = UniaxialState::Strain)
      : Base(material, uniaxial, "StVenantKirchhoff", "st-venant-kirchhoff") {}
  /// 1D stress: J = F s^2 with s^2 = 1 + 2 E_22 = 1 - nu (F^2 - 1); otherwise det F.
  double volume_ratio(const Deformation<double, Dim>& F) const override {
    if (Dim == 1 && m_uniaxial == UniaxialState::Stress)
      return F(0, 0) * (1 - m_material.poisson() * (F(0, 0) * F(0, 0) - 1));
    return F.determinant();
  }

  template <class Scalar>
  Scalar energy_impl(const Deformation<Scalar, Dim>& F) const {
    const Deformation<Scalar, Dim> E = green_lagrange(F);
    const Scalar tr = E.trace();
    return 0.5 * lam() * tr * tr + mu() * (E.array() * E.array()).sum();
  }
  template <class Scalar>
  Deformation<Scalar, Dim> stress_impl(const Deformation<Scalar, Dim>& F) const {
    return F * second_piola(F);
  }
  template <class Scalar>
  MaterialTangent<Scalar, Dim> tangent_impl(const Deformation<Scalar, Dim>& F) const {
    const Deformation<Scalar, Dim> S = second_piola(F);
    const Deformation<Scalar, Dim> B = F * F.transpose();
    MaterialTangent<Scalar, Dim> t;
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b)
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d)
            t(a * Dim + b, c * Dim + d) = (a == c ? S(d, b) : Scalar(0)) + lam() * F(a, b) * F(c, d) +
                                          mu() * (F(a, d) * F(c, b) + (b == d ? B(a, c) : Scalar(0)));
    return t;
  }

 private:
  template <class Scalar>
  static Deformation<Scalar, Dim> green_lagrange(const Deformation<Scalar, Dim>& F) {
    return 0.5 * (F.transpose() * F - Deformation<Scalar, Dim>::Identity());
  }
  template <class Scalar>
  Deformation<Scalar, Dim> second_piola(const Deformation<Scalar, Dim>& F) const {
    const Deformation<Scalar, Dim> E = green_lagrange(F);
    return (lam() * E.trace()) * Deformation<Scalar, Dim>::Identity() + (2 * mu()) * E;
  }
  /// 1D: the uniaxial modulus M as lambda + 2 mu with (lambda, mu) = (M, 0).
  double lam() const { return Dim == 1 ? m_material.uniaxial_modulus(m_uniaxial) : m_material.lambda(); }
  double mu() const { return Dim == 1 ? 0.0 : m_material.mu(); }
};

}  // namespace sphstab
