#pragma once
// Private helpers shared by the two finite-strain total-Lagrangian forms (not installed): the per-particle output
// tables both expose, the density check, the DOF masses and the check of prescribed fixed displacements.
#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/models/hyperelastic_model.hpp"

namespace sphstab {
namespace detail {

/// One row per particle: F_ab at column a * Dim + b.
template <int Dim>
Eigen::MatrixXd deformation_table(const std::vector<Deformation<double, Dim>>& F) {
  Eigen::MatrixXd out(static_cast<long>(F.size()), Dim * Dim);
  for (std::size_t i = 0; i < F.size(); ++i)
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) out(static_cast<long>(i), a * Dim + b) = F[i](a, b);
  return out;
}

/// One row per particle: P_ab(F) at column a * Dim + b for the active particles, NaN elsewhere (no stress computed).
template <int Dim>
Eigen::MatrixXd stress_table(const HyperelasticModel<Dim>& material, const std::vector<Deformation<double, Dim>>& F,
                             const std::vector<int>& active) {
  Eigen::MatrixXd out =
      Eigen::MatrixXd::Constant(static_cast<long>(F.size()), Dim * Dim, std::numeric_limits<double>::quiet_NaN());
  for (int i : active) {
    const Deformation<double, Dim> P = material.stress(F[i]);
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) out(i, a * Dim + b) = P(a, b);
  }
  return out;
}

/// rho0_i V_i per DOF of the free particles.
template <int Dim>
Eigen::VectorXd lumped_dof_mass(const Discretisation<Dim>& d, const Eigen::VectorXd& rho) {
  Eigen::VectorXd m(Dim * d.free_count());
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    for (int a = 0; a < Dim; ++a) m[f * Dim + a] = rho[i] * d.particles.volume[i];
  }
  return m;
}

/// Throws std::invalid_argument (one line, naming `who`) unless `d` has `expected` entries, all finite.
inline void check_fixed_displacement(const Eigen::VectorXd& d, long expected, const char* who) {
  if (d.size() != expected)
    throw std::invalid_argument(std::string(who) + "::set_fixed_displacement: expected " + std::to_string(expected) +
                                " entries (Dim per fixed particle), got " + std::to_string(d.size()));
  if (!d.allFinite())
    throw std::invalid_argument(std::string(who) + "::set_fixed_displacement: entries must be finite");
}

/// rho0 per particle from one uniform value or N values; throws std::invalid_argument (one line, naming `who`) for
/// another size or a value that is not finite and > 0.
inline Eigen::VectorXd particle_density(const Eigen::VectorXd& density, int N, const char* who) {
  if (density.size() != 1 && density.size() != N)
    throw std::invalid_argument(std::string(who) + ": density has " + std::to_string(density.size()) +
                                " entries, expected 1 or " + std::to_string(N) + " (one per particle)");
  Eigen::VectorXd rho = density.size() == 1 ? Eigen::VectorXd::Constant(N, density[0]) : density;
  for (int i = 0; i < N; ++i)
    if (!(rho[i] > 0) || !std::isfinite(rho[i]))
      throw std::invalid_argument(std::string(who) + ": density of particle " + std::to_string(i) +
                                  " must be finite and > 0 (got " + format_number(rho[i]) + ")");
  return rho;
}

}  // namespace detail
}  // namespace sphstab
