#pragma once
/// \file hooke.hpp
/// Hooke's law written as a finite-strain model (small-strain linear elasticity; NOT frame indifferent):
///   eps = sym(F - I),  P = T = lambda tr(eps) I + 2 mu eps  [Ismail2009, (4.13)],
///   Psi = lambda/2 (tr eps)^2 + mu eps:eps,  dP/dF = lambda delta_ab delta_cd + mu (delta_ac delta_bd + delta_ad
///   delta_bc).
/// Dim = 2: plane strain. Dim = 1: P = M (F - 1) with M = lambda + 2 mu (1D strain, (4.16)) or E (1D stress, (4.21)).
/// It is the material of the small-strain forms (total_lagrangian.hpp, linear_elastic.hpp), which the finite-strain
/// TL form reproduces with it.
/// \code{.cpp}
/// const auto lame = sphstab::ElasticMaterial::from_young_poisson(200e9, 0.3, 8000);
/// const sphstab::Hooke<1> bar(lame, sphstab::UniaxialState::Stress);  // T11 = E eps ([Ismail2009] algorithm 4.1)
/// double T11 = bar.stress(sphstab::Deformation<double, 1>::Constant(1.0 + 5e-7))(0, 0);  // 100 kPa (expression)
/// \endcode
#include <string>

#include "sphstab/models/hyperelastic_model.hpp"

namespace sphstab {

template <int Dim>
class Hooke final : public HyperelasticModelT<Dim, Hooke<Dim>> {
  using Base = HyperelasticModelT<Dim, Hooke<Dim>>;
  using Base::m_material, Base::m_uniaxial, Base::one_d_stress;

 public:
  /// Throws std::invalid_argument for invalid constants (ElasticMaterial::validate).
  explicit Hooke(const ElasticMaterial& material, UniaxialState uniaxial = UniaxialState::Strain)
      : Base(material, uniaxial, "Hooke", "hooke") {}
  /// 1D stress: J = F s^2 with the small-strain lateral stretch s = 1 - nu (F - 1); otherwise det F.
  double volume_ratio(const Deformation<double, Dim>& F) const override {
    if (Dim == 1 && m_uniaxial == UniaxialState::Stress) {
      const double s = 1 - m_material.poisson() * (F(0, 0) - 1);
      return F(0, 0) * s * s;
    }
    return F.determinant();
  }

  template <class Scalar>
  Scalar energy_impl(const Deformation<Scalar, Dim>& F) const {
    const Deformation<Scalar, Dim> e = strain(F);
    const Scalar tr = e.trace();
    return 0.5 * lam() * tr * tr + mu() * (e.array() * e.array()).sum();
  }
  template <class Scalar>
  Deformation<Scalar, Dim> stress_impl(const Deformation<Scalar, Dim>& F) const {
    const Deformation<Scalar, Dim> e = strain(F);
    return (lam() * e.trace()) * Deformation<Scalar, Dim>::Identity() + (2 * mu()) * e;
  }
  template <class Scalar>
  MaterialTangent<Scalar, Dim> tangent_impl(const Deformation<Scalar, Dim>&) const {
    MaterialTangent<Scalar, Dim> t = MaterialTangent<Scalar, Dim>::Zero();
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b)
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d)
            t(a * Dim + b, c * Dim + d) =
                lam() * (a == b) * (c == d) + mu() * ((a == c) * (b == d) + (a == d) * (b == c));
    return t;
  }

 private:
  template <class Scalar>
  static Deformation<Scalar, Dim> strain(const Deformation<Scalar, Dim>& F) {
    const Deformation<Scalar, Dim> g = F - Deformation<Scalar, Dim>::Identity();
    return 0.5 * (g + g.transpose());
  }
  /// 1D: the uniaxial modulus M as lambda + 2 mu with (lambda, mu) = (M, 0).
  double lam() const { return Dim == 1 ? m_material.uniaxial_modulus(m_uniaxial) : m_material.lambda(); }
  double mu() const { return Dim == 1 ? 0.0 : m_material.mu(); }
};

}  // namespace sphstab
