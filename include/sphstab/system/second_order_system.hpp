#pragma once
/// \file second_order_system.hpp
/// The semi-discrete system ü = a(u) that the explicit integrators advance, described by callables so that any
/// force function (momentum form, linear operator, pair loop) can drive it.
///
/// Degrees of freedom: u, v and a hold the FREE particles only, interleaved dof = i * dofs_per_particle + c
/// (docs/conventions.md §1). Fixed particles are not unknowns: the acceleration callable applies their prescribed
/// displacement itself (clamped: zero; mirror ghosts: a copy of their partner's; time-dependent: through
/// set_time, called with the time of u before every acceleration evaluation).
#include <Eigen/Core>
#include <functional>

namespace sphstab {

/// accel = a(u): both of size ndof; `accel` is already sized by the caller and must be overwritten.
using AccelerationFunction = std::function<void(const Eigen::VectorXd& u, Eigen::VectorXd& accel)>;
/// Strain (potential) energy U(u) such that, for a conservative system, M a(u) = -dU/du.
using EnergyFunction = std::function<double(const Eigen::VectorXd& u)>;
/// Velocity-dependent hook (XSPH, Powell 2.71): from u and the half-step velocity v, write the velocity
/// `w` used for the displacement update (same size as v).
using VelocityHook = std::function<void(const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& w)>;

/// How the hook's velocity w is used. DriftOnly: u += dt w, v unchanged (Monaghan's XSPH: particles move
/// with the smoothed velocity). Replace: v <- w, then u += dt v (Powell 2.71 read literally as an assignment;
/// dissipative).
enum class VelocityHookMode { DriftOnly, Replace };

struct SecondOrderSystem {
  AccelerationFunction acceleration;  ///< required
  EnergyFunction strain_energy;       ///< optional: enables strain/total energy diagnostics
  VelocityHook velocity_hook;         ///< optional
  VelocityHookMode hook_mode = VelocityHookMode::DriftOnly;
  std::function<void(double t)> set_time;  ///< optional: time-dependent prescribed displacements
  int dofs_per_particle = 1;               ///< Dim of the displacement field (1..3)
  Eigen::VectorXd mass;                    ///< per free particle (ndof / dofs_per_particle); empty: unit masses
  /// Reference positions of the free particles, interleaved like u (optional; needed by the box check and by
  /// VTK snapshots, which show X + u).
  Eigen::VectorXd reference_positions;

  /// Throws std::invalid_argument("<who>: ...") if the callable is missing or sizes do not match ndof.
  void validate(long ndof, const char* who) const;
  /// Mass of DOF k (unit if mass is empty).
  double dof_mass(long k) const { return mass.size() ? mass[k / dofs_per_particle] : 1.0; }
};

}  // namespace sphstab
