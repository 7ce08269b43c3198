#pragma once
/// \file particle_state_file.hpp
/// A particle state (growth/state_stability.hpp) read from a file another SPH code wrote, and the modes of its
/// verdict written for ParaView.
///
/// **CSV** (io/csv.hpp; first line the header, one row per particle, columns in any order):
///   x [y]                 positions (a column y makes the state 2D)                                  required
///   vx [vy]               velocities                                                                 optional (0)
///   density               rho_i > 0                                                                  required
///   mass                  m_i > 0                                                                    required, or
///                         ParticleStateFileOptions::mass
///   s_xx [s_yy s_xy]      deviatoric stress (1D: s_xx; 2D: all three)                                optional (0)
///   fixed                 1 for a fixed particle, 0 for a free one                                   optional (0)
/// **VTK PolyData (.vtp)** (io/vtk.hpp, ASCII, as write_vtp writes it): the points (z = 0; 1D: y = z = 0 too) and the
/// point-data arrays "velocity" (optional), "density", "mass" (or the option), "deviator" (1 or 3 components:
/// xx[, yy, xy]; optional) or, as io/rate_form_vtk.hpp writes a snapshot, "pressure" with "sigma_xx" [, "sigma_yy",
/// "sigma_xy"] (S = sigma + p I), and "fixed" (optional). A snapshot of this project's runs has no mass array: give
/// the mass as an option.
///
/// \code{.cpp}
/// sphstab::ParticleState<2> s = sphstab::read_particle_state<2>("state.csv", {.h = 0.013, .spacing = 0.01});
/// \endcode
#include <limits>
#include <string>

#include "sphstab/growth/state_stability.hpp"

namespace sphstab {

struct ParticleStateFileOptions {
  double h = 0;        ///< the smoothing length (files carry none), finite and > 0
  double spacing = 0;  ///< ParticleState::spacing (0: unknown)
  /// The mass of every particle when the file has no mass column or array (NaN: the file must have one). Refused
  /// when the file has one too.
  double mass = std::numeric_limits<double>::quiet_NaN();
};

/// The dimension of the state in `path`: 2 when a CSV has a column "y" or a .vtp has a point with y != 0, else 1.
/// Throws as read_csv / read_vtp.
int particle_state_dimension(const std::string& path);

/// Reads a state from a .csv or .vtp file (by extension). Throws std::invalid_argument("<path>: ...") naming a
/// missing or non-numeric column, a file of the other dimension or an unknown extension, std::runtime_error if the
/// file cannot be read; the values themselves are checked by rate_form_at_state.
template <int Dim>
ParticleState<Dim> read_particle_state(const std::string& path, const ParticleStateFileOptions& options);

/// Writes the state with its verdict's modes: points x, point data "velocity", "density", "mass", "fixed" and the
/// velocity shapes "semi_discrete_mode" and "map_mode" (Dim components; 0 on fixed particles and where a mode was
/// not computed). Throws as write_vtp, and std::invalid_argument when the result does not belong to the state.
template <int Dim>
void write_state_modes_vtp(const std::string& path, const ParticleState<Dim>& state, const StateStability& result);

}  // namespace sphstab
