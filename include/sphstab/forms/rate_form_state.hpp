#pragma once
/// \file rate_form_state.hpp
/// Per-particle fields of a RateFormScheme state y, in particle order: what studies measure and snapshots show.
/// Fixed particles read as the scheme treats them: their reference positions, zero velocity, and their own density
/// and deviator when they evolve (RateFormOptions::evolve_fixed), otherwise the initial ones.
///
/// \code{.cpp}
/// const Eigen::Matrix2Xd x = sphstab::rate_form_positions(scheme, y);  // 2 x N
/// const std::vector<Eigen::Matrix2d> sigma = sphstab::rate_form_stresses(scheme, y);
/// \endcode
#include <Eigen/Core>
#include <vector>

#include "sphstab/forms/rate_form.hpp"

namespace sphstab {

/// Positions, Dim x N. Throws std::invalid_argument for a state of the wrong size (all functions here).
template <int Dim>
Eigen::Matrix<double, Dim, Eigen::Dynamic> rate_form_positions(const RateFormScheme<Dim>& scheme,
                                                               const Eigen::VectorXd& y);

/// Velocities, Dim x N (0 for fixed particles).
template <int Dim>
Eigen::Matrix<double, Dim, Eigen::Dynamic> rate_form_velocities(const RateFormScheme<Dim>& scheme,
                                                                const Eigen::VectorXd& y);

/// Densities, N.
template <int Dim>
Eigen::VectorXd rate_form_densities(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y);

/// Stored deviators, kStress x N (1D: S_xx; 2D: S_xx, S_yy, S_xy).
template <int Dim>
Eigen::MatrixXd rate_form_deviators(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y);

/// Cauchy stresses sigma = -p I + S (tension positive), p = K (rho / rho0 - 1) [GMS2001, (2.4), (3.3)].
template <int Dim>
std::vector<Eigen::Matrix<double, Dim, Dim>> rate_form_stresses(const RateFormScheme<Dim>& scheme,
                                                                const Eigen::VectorXd& y);

}  // namespace sphstab
