#pragma once
/// \file dispatch.hpp
/// Internal to src/forms: which loop of the rate form sums the pairs (rate_form.hpp), and the active terms as
/// compile-time tags, so that a loop is compiled for the terms a scheme carries.
#include <type_traits>

#include "sphstab/forms/rate_form.hpp"

namespace sphstab::rate_form_detail {

/// C_ij and S-SPH: the local means of algorithm 4.1 (corrected_rows.hpp).
inline bool uses_local_means(RateFormMomentum m) {
  return m == RateFormMomentum::Cij || m == RateFormMomentum::StabilisedSph;
}

/// Calls body(viscosity_tag, stress_tag) with the viscosity switch and whether the artificial stress acts as
/// compile-time tags (std::integral_constant), so that the loops are compiled for the active terms only.
template <class Body>
void with_term_tags(ViscositySwitch viscosity, bool stress, Body&& body) {
  const auto with_stress = [&](auto viscosity_tag) {
    if (stress)
      body(viscosity_tag, std::true_type{});
    else
      body(viscosity_tag, std::false_type{});
  };
  switch (viscosity) {
    case ViscositySwitch::Off:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Off>{});
      break;
    case ViscositySwitch::Compression:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Compression>{});
      break;
    case ViscositySwitch::Always:
      with_stress(std::integral_constant<ViscositySwitch, ViscositySwitch::Always>{});
      break;
  }
}

}  // namespace sphstab::rate_form_detail
