#pragma once
/// \file diagnostics.hpp
/// Energy and momentum of a SecondOrderSystem state.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "sphstab/system/second_order_system.hpp"

namespace sphstab {

/// One diagnostics record. kinetic = ½ Σ m_i |v_i|²; strain = U(u) (NaN when the system has no strain-energy
/// callable); total = kinetic + strain (kinetic alone when strain is NaN); momentum[c] = Σ_i m_i v_i^c for
/// c < dofs_per_particle (0 beyond).
struct Diagnostics {
  long step = 0;
  double time = 0;
  double kinetic = 0, strain = 0, total = 0;
  std::array<double, 3> momentum{};
  double max_abs_displacement = 0, max_abs_velocity = 0;
};

Diagnostics compute_diagnostics(const SecondOrderSystem& system, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                long step, double time);

/// Column names of the diagnostics CSV (step, t, kinetic, strain, total, momentum_x.., max_abs_u, max_abs_v).
std::vector<std::string> diagnostics_columns(int dofs_per_particle);

}  // namespace sphstab
