#include "sphstab/models/von_mises.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

VonMises::VonMises(double yield_stress) : m_yield(yield_stress) {
  if (!(yield_stress > 0))  // rejects NaN too; +inf means "never yields"
    throw std::invalid_argument("VonMises: yield stress must be > 0 (got " + format_number(yield_stress) + ")");
}

template <int Dim>
double von_mises_stress(const StoredDeviator<Dim>& s) {
  if constexpr (Dim == 1) {
    return 1.5 * std::abs(s[0]);  // s = diag(S, -S/2, -S/2): s:s = 3/2 S^2, sqrt(3/2 s:s) = 3/2 |S|
  } else {
    const double zz = -(s[0] + s[1]);  // plane strain: the implied S_zz
    return std::sqrt(1.5 * (s[0] * s[0] + s[1] * s[1] + zz * zz + 2 * s[2] * s[2]));
  }
}

template <int Dim>
RadialReturn<Dim> radial_return(const VonMises& model, const StoredDeviator<Dim>& trial) {
  RadialReturn<Dim> r{.deviator = trial, .yielded = false, .trial_stress = von_mises_stress<Dim>(trial)};
  if (std::isfinite(r.trial_stress) && r.trial_stress > model.yield_stress()) {  // never for Y = +inf
    r.deviator = (model.yield_stress() / r.trial_stress) * trial;
    r.yielded = true;
  }
  return r;
}

template double von_mises_stress<1>(const StoredDeviator<1>&);
template double von_mises_stress<2>(const StoredDeviator<2>&);
template RadialReturn<1> radial_return<1>(const VonMises&, const StoredDeviator<1>&);
template RadialReturn<2> radial_return<2>(const VonMises&, const StoredDeviator<2>&);

}  // namespace sphstab
