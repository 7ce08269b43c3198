#pragma once
/// \file elastic_material.hpp
/// The isotropic linear-elastic material of every form: the reference density rho0 and the 3D constants (Lame's
/// lambda, the shear modulus mu, the bulk modulus K = lambda + 2 mu / 3). The same type drives the small-strain
/// elastic forms and their Jacobians (lambda, mu; 2D is plane strain), the rate-form scheme (EOS p = K (rho/rho0 - 1),
/// dS/dt = 2 mu dev D; mu = 0 is a fluid), the linear elastic bars and the finite-strain models (hooke.hpp,
/// st_venant_kirchhoff.hpp, neo_hookean.hpp).
///
/// Both lambda and K are STORED: the constant the material was given is kept exactly as given and the other is
/// derived once, lambda = K - 2 mu / 3 (from_bulk_shear) or K = lambda + 2 mu / 3 (from_lame); from_young_poisson
/// computes both from (E, nu). Why: the forms read lambda and the rate form reads K, and each must see exactly the
/// double it was given (long nonlinear runs amplify a last-bit change); recomputing one from the other would round.
///
/// The two one-dimensional states of [Ismail2009, §4.4] (Dim = 1 models; Dim = 2 is plane strain):
///   1D strain (lateral stretches held at 1, a bar that may not change its cross-section, (4.16)): the small-strain
///     modulus is lambda + 2 mu, wave speed c_L;
///   1D stress (lateral stresses zero, a thin bar, (4.17)-(4.22)): the small-strain modulus is Young's
///     E = mu (3 lambda + 2 mu) / (lambda + mu), wave speed c_b.
/// Poisson's ratio nu = lambda / (2 (lambda + mu)) [Ismail2009, (4.20)].
///
/// \code{.cpp}
/// const auto steel = sphstab::ElasticMaterial::from_young_poisson(200e9, 0.3, 8000);  // lambda 115.4, mu 76.9 GPa
/// double cl = std::sqrt(steel.uniaxial_modulus(sphstab::UniaxialState::Strain) / steel.density());  // 5801 m/s
/// const auto gms = sphstab::ElasticMaterial::from_bulk_shear(1, 0.22, 1);  // K = 1 exactly, lambda = 1 - 0.44/3
/// \endcode
#include <string>

namespace sphstab {

/// The one-dimensional reduction of a 3D material [Ismail2009, §4.4] (used by Dim = 1 models; Dim = 2 is plane
/// strain).
enum class UniaxialState {
  Strain,  ///< lateral stretches 1 (Ismail's algorithm 5.1: J = F)
  Stress   ///< lateral stresses 0 (lateral stretch solved from the lateral equilibrium)
};
/// "strain" / "stress".
std::string uniaxial_state_name(UniaxialState state);

/// Whether validate accepts mu = 0 (a fluid: the rate form's EOS alone) or needs a solid (mu > 0).
enum class ShearModulusRule { Positive, NonNegative };

/// Isotropic linear-elastic material: density rho0 and the 3D constants lambda, mu, K (see the file comment for which
/// are stored exactly). The named constructors do not validate (except from_young_poisson, which checks E and nu);
/// each consumer calls validate(who) with its own name.
class ElasticMaterial {
 public:
  /// Lame's lambda and mu kept as given; K = lambda + 2 mu / 3.
  static ElasticMaterial from_lame(double lambda, double mu, double density);
  /// K and mu kept as given; lambda = K - 2 mu / 3.
  static ElasticMaterial from_bulk_shear(double bulk_modulus, double mu, double density);
  /// From Young's modulus E > 0 and Poisson's ratio nu in (-1, 1/2): lambda = E nu / ((1 + nu)(1 - 2 nu)),
  /// mu = E / (2 (1 + nu)), K = E / (3 (1 - 2 nu)), each from (E, nu) directly. Throws std::invalid_argument (one
  /// line, with the value) for E, nu or the density out of range.
  static ElasticMaterial from_young_poisson(double young, double poisson, double density);

  double lambda() const { return m_lambda; }              ///< Lame's first parameter
  double mu() const { return m_mu; }                      ///< shear modulus
  double bulk_modulus() const { return m_bulk_modulus; }  ///< K (3D)
  double density() const { return m_density; }            ///< reference density rho0 (zero pressure)

  double young() const { return m_mu * (3 * m_lambda + 2 * m_mu) / (m_lambda + m_mu); }  ///< [Ismail2009, (4.22)]
  double poisson() const { return m_lambda / (2 * (m_lambda + m_mu)); }                  ///< [Ismail2009, (4.20)]
  /// Small-strain modulus of the 1D state: lambda + 2 mu (strain, (4.16)) or E (stress, (4.21)).
  double uniaxial_modulus(UniaxialState state) const {
    return state == UniaxialState::Strain ? m_lambda + 2 * m_mu : young();
  }
  /// Bulk sound speed c0 = sqrt(K / rho0), the EOS's (c0^2 = dp/drho).
  double sound_speed() const;
  /// Longitudinal (P) wave speed of small-strain waves, sqrt((K + 4 mu / 3) / rho0).
  double p_wave_speed() const;

  /// Throws std::invalid_argument("<who>: ...", one line with the values) unless lambda, mu, K and rho0 are finite,
  /// rho0 > 0, mu > 0 (or mu >= 0 with ShearModulusRule::NonNegative) and K > 0, i.e. nu in (-1, 1/2) for a solid.
  void validate(const char* who, ShearModulusRule shear = ShearModulusRule::Positive) const;

 private:
  ElasticMaterial(double lambda, double mu, double bulk_modulus, double density)
      : m_lambda(lambda), m_mu(mu), m_bulk_modulus(bulk_modulus), m_density(density) {}
  double m_lambda, m_mu, m_bulk_modulus, m_density;
};

}  // namespace sphstab
