#include "sphstab/problems/scene.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

template <int Dim>
double Scene<Dim>::time_step(double cfl) const {
  if (!(cfl > 0) || !std::isfinite(cfl))
    throw std::invalid_argument("scene " + name + ": cfl must be finite and > 0 (got " + format_number(cfl) + ")");
  return cfl * scheme->discretisation().h / scheme->material().p_wave_speed();
}

template <int Dim>
const SceneMeasure<Dim>& Scene<Dim>::measure(const std::string& which) const {
  std::string valid;
  for (const SceneMeasure<Dim>& m : measures) {
    if (m.name == which) return m;
    valid += (valid.empty() ? "" : ", ") + m.name;
  }
  throw std::invalid_argument("scene " + name + ": no measure '" + which + "' (valid: " + valid + ")");
}

template struct Scene<1>;
template struct Scene<2>;

}  // namespace sphstab
