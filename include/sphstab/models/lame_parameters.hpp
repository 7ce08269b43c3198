#pragma once
/// \file lame_parameters.hpp
/// Isotropic elastic constants of the finite-strain materials (hooke.hpp, st_venant_kirchhoff.hpp, neo_hookean.hpp)
/// and the two one-dimensional states of [Ismail2009, §4.4]:
///   1D strain (lateral stretches held at 1, a bar that may not change its cross-section, (4.16)): the small-strain
///     modulus is lambda + 2 mu, wave speed c_L;
///   1D stress (lateral stresses zero, a thin bar, (4.17)-(4.22)): the small-strain modulus is Young's
///     E = mu (3 lambda + 2 mu) / (lambda + mu), wave speed c_b.
/// Poisson's ratio nu = lambda / (2 (lambda + mu)) [Ismail2009, (4.20)].
///
/// \code{.cpp}
/// const auto steel = sphstab::LameParameters::from_young_poisson(200e9, 0.3);  // lambda 115.4 GPa, mu 76.9 GPa
/// double cl = std::sqrt(steel.uniaxial_modulus(sphstab::UniaxialState::Strain) / 8000.0);  // 5801 m/s
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

/// Lame's lambda and the shear modulus mu (3D isotropic material).
struct LameParameters {
  double lambda = 1.0;  ///< Lame's first parameter
  double mu = 1.0;      ///< shear modulus, > 0

  /// From Young's modulus E > 0 and Poisson's ratio nu in (-1, 0.5): mu = E / (2 (1 + nu)),
  /// lambda = E nu / ((1 + nu)(1 - 2 nu)). Throws std::invalid_argument otherwise (one line, with the value).
  static LameParameters from_young_poisson(double young, double poisson);

  double young() const { return mu * (3 * lambda + 2 * mu) / (lambda + mu); }  ///< [Ismail2009, (4.22)]
  double poisson() const { return lambda / (2 * (lambda + mu)); }              ///< [Ismail2009, (4.20)]
  /// Small-strain modulus of the 1D state: lambda + 2 mu (strain, (4.16)) or E (stress, (4.21)).
  double uniaxial_modulus(UniaxialState state) const {
    return state == UniaxialState::Strain ? lambda + 2 * mu : young();
  }

  /// Throws std::invalid_argument("<who>: ...") unless both are finite, mu > 0 and 3 lambda + 2 mu > 0 (bulk
  /// modulus > 0), i.e. nu in (-1, 0.5).
  void validate(const char* who) const;
};

}  // namespace sphstab
