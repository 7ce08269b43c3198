#pragma once
/// \file hyperelastic_model.hpp
/// The interface of a finite-strain (hyperelastic) material, Dim = 1 (a 1D state, elastic_material.hpp) or Dim = 2
/// (plane strain): the strain energy density Psi(F) per unit reference volume, the first Piola-Kirchhoff stress
/// P = dPsi/dF [Ismail2009, §3.3: P = dPsi/dF] and its tangent dP/dF, for the deformation gradient F = I + Grad u.
///
/// Every quantity is templated on the scalar so that complex-step (and the force functions' complex overloads)
/// differentiate exactly: an implementation derives from HyperelasticModelT and writes three templates
///   energy_impl<Scalar>(F), stress_impl<Scalar>(F), tangent_impl<Scalar>(F).
///
/// \note Tangent layout: a Dim^2 x Dim^2 matrix over vec(F) in ROW-major order, entry (a Dim + b, c Dim + d) =
///       dP_ab / dF_cd. At F = I every model gives the linear elastic tensor
///       lambda delta_ab delta_cd + mu (delta_ac delta_bd + delta_ad delta_bc) (Dim = 1: the uniaxial modulus).
/// \note Sign: tension positive. Cauchy stress T = J^{-1} P F^T [Ismail2009, (3.33)].
#include <Eigen/Core>
#include <Eigen/LU>
#include <complex>
#include <string>

#include "sphstab/models/elastic_material.hpp"

namespace sphstab {

/// Deformation gradient or first Piola-Kirchhoff stress, Dim x Dim.
template <class Scalar, int Dim>
using Deformation = Eigen::Matrix<Scalar, Dim, Dim>;
/// dP/dF over row-major vec(F), Dim^2 x Dim^2.
template <class Scalar, int Dim>
using MaterialTangent = Eigen::Matrix<Scalar, Dim * Dim, Dim * Dim>;

template <int Dim>
class HyperelasticModel {
 public:
  using Real = Deformation<double, Dim>;
  using Complex = Deformation<std::complex<double>, Dim>;
  virtual ~HyperelasticModel() = default;

  /// e.g. "neo-hookean/1d-strain", "st-venant-kirchhoff/plane-strain".
  virtual std::string name() const = 0;
  virtual const ElasticMaterial& material() const = 0;
  /// The 1D state (meaningful for Dim = 1 only; Dim = 2 is plane strain).
  virtual UniaxialState uniaxial() const = 0;

  /// Psi(F), per unit reference volume.
  virtual double energy(const Real& F) const = 0;
  virtual std::complex<double> energy(const Complex& F) const = 0;
  /// P(F) = dPsi/dF.
  virtual Real stress(const Real& F) const = 0;
  virtual Complex stress(const Complex& F) const = 0;
  /// dP/dF (layout in the file comment).
  virtual MaterialTangent<double, Dim> tangent(const Real& F) const = 0;
  virtual MaterialTangent<std::complex<double>, Dim> tangent(const Complex& F) const = 0;
  /// Any Eigen expression (Deformation::Constant(f), Q * F, ...): evaluated to a Deformation of its scalar first (the
  /// expression would otherwise convert to both the real and the complex overload).
  template <class Derived>
  auto energy(const Eigen::MatrixBase<Derived>& F) const {
    return energy(Deformation<typename Derived::Scalar, Dim>(F));
  }
  template <class Derived>
  auto stress(const Eigen::MatrixBase<Derived>& F) const {
    return stress(Deformation<typename Derived::Scalar, Dim>(F));
  }
  template <class Derived>
  auto tangent(const Eigen::MatrixBase<Derived>& F) const {
    return tangent(Deformation<typename Derived::Scalar, Dim>(F));
  }
  /// J = V/V0 of the 3D deformation: det F for plane strain and 1D strain, F s^2 for 1D stress (s the lateral
  /// stretch).
  virtual double volume_ratio(const Real& F) const { return F.determinant(); }
  /// The Cauchy stress T = J^{-1} P F^T [Ismail2009, (3.33)], with J = volume_ratio(F).
  Real cauchy_stress(const Real& F) const { return stress(F) * F.transpose() / volume_ratio(F); }
};

/// CRTP helper: Derived implements energy_impl, stress_impl, tangent_impl templated on the scalar (and volume_ratio);
/// the constants, the 1D lateral state and the name are kept here.
template <int Dim, class Derived>
class HyperelasticModelT : public HyperelasticModel<Dim> {
 public:
  /// "<label>/1d-<uniaxial state>" in 1D, "<label>/plane-strain" in 2D.
  std::string name() const override {
    return std::string(m_label) + (Dim == 1 ? "/1d-" + uniaxial_state_name(m_uniaxial) : std::string("/plane-strain"));
  }
  const ElasticMaterial& material() const override { return m_material; }
  UniaxialState uniaxial() const override { return m_uniaxial; }
  using typename HyperelasticModel<Dim>::Real;
  using typename HyperelasticModel<Dim>::Complex;
  using HyperelasticModel<Dim>::energy;  // the expression overloads
  using HyperelasticModel<Dim>::stress;
  using HyperelasticModel<Dim>::tangent;
  double energy(const Real& F) const override { return self().energy_impl(F); }
  std::complex<double> energy(const Complex& F) const override { return self().energy_impl(F); }
  Real stress(const Real& F) const override { return self().stress_impl(F); }
  Complex stress(const Complex& F) const override { return self().stress_impl(F); }
  MaterialTangent<double, Dim> tangent(const Real& F) const override { return self().tangent_impl(F); }
  MaterialTangent<std::complex<double>, Dim> tangent(const Complex& F) const override { return self().tangent_impl(F); }

 protected:
  /// Throws std::invalid_argument for invalid constants (ElasticMaterial::validate, the message naming `who`).
  HyperelasticModelT(const ElasticMaterial& material, UniaxialState uniaxial, const char* who, const char* label)
      : m_material(material), m_uniaxial(uniaxial), m_label(label) {
    m_material.validate(who);
  }
  /// Uniaxial stress in 1D: the lateral stretches follow from the zero lateral stress.
  bool one_d_stress() const { return Dim == 1 && m_uniaxial == UniaxialState::Stress; }

  ElasticMaterial m_material;
  UniaxialState m_uniaxial;

 private:
  const Derived& self() const { return static_cast<const Derived&>(*this); }
  const char* m_label;
};

namespace detail {
/// Throws std::invalid_argument("<who>: J = ... <= 0 ...") when Re det F <= 0 (or is not finite).
void require_positive_jacobian(double J, const std::string& who);
}  // namespace detail

}  // namespace sphstab
