#pragma once
/// \file rate_form_vtk.hpp
/// A VTK snapshot (vtk.hpp) of a RateFormScheme state: the particles at their positions with velocity, density,
/// pressure, the Cauchy stress components (rate_form_state.hpp), the von Mises stress and fixed / driven flags, plus
/// any fields a study adds.
///
/// \code{.cpp}
/// sphstab::write_rate_form_vtp("run_000100.vtp", scheme, y, {{"ring", 1, ring}});
/// \endcode
#include <Eigen/Core>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/io/vtk.hpp"

namespace sphstab {

/// Writes points (current positions) and the fields "velocity", "density", "pressure", "sigma_xx" (2D also "sigma_yy",
/// "sigma_xy"), "von_mises" (sqrt(3 J2) of the deviator, models/von_mises.hpp), "fixed" and "driven" (1 for fixed /
/// driven particles), then `extra`. Throws as write_vtp does, and std::invalid_argument
/// for a state of the wrong size.
template <int Dim>
void write_rate_form_vtp(const std::string& path, const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                         const std::vector<VtkField>& extra = {});

}  // namespace sphstab
