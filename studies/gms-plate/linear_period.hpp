#pragma once
/// \file linear_period.hpp
/// The small-amplitude SPH bending period of a plate case from the spectrum of its initial state
/// (growth/rate_form_spectrum.hpp): at rest and stress free, so the artificial stress and the viscosity's compression
/// switch are off in the linearisation. Of the vibration modes below three times the thin-plate frequency, the bending
/// mode is the one whose velocity shape overlaps most with the initial velocity (7.3)-(7.4) (|cos| of the angle
/// between them, `overlap`). Softer modes exist: the plain SPH gradient's near-zero-energy patterns, which `softer`
/// counts.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <vector>

#include "plate_case.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"

namespace sphstab::gms_plate {

struct LinearPeriod {
  double period = kNaN, overlap = kNaN, growth_rate = kNaN;
  int softer = -1;             ///< vibration modes of lower frequency than the bending mode
  std::vector<double> lowest;  ///< the candidates' periods, lowest frequency first
};

inline LinearPeriod linear_period(const PlateCase& c) {
  const Scene<2> s = plate_scene(c);
  const RateFormScheme<2>& scheme = *s.scheme;
  const Eigen::VectorXd y = scheme.uniform_state();
  const RateFormSpectrum all = rate_form_spectrum(scheme, y);
  if (all.info() != Status::Successful) throw std::runtime_error("plate spectrum: " + all.reason);
  std::vector<std::complex<double>> w;
  for (const auto& l : all.eigenvalues)
    if (l.imag() > 1e-12) w.push_back(l);
  std::sort(w.begin(), w.end(), [](auto a, auto b) { return a.imag() < b.imag(); });
  const double w_max = 3 * 2 * M_PI / thin_period(c);
  w.erase(std::find_if(w.begin(), w.end(), [&](auto l) { return l.imag() > w_max; }), w.end());
  Eigen::VectorXcd targets(static_cast<Eigen::Index>(w.size()));
  for (std::size_t k = 0; k < w.size(); ++k) targets[static_cast<Eigen::Index>(k)] = w[k];
  const RateFormSpectrum sp = rate_form_spectrum(scheme, y, {.mode_targets = targets});
  const Discretisation<2>& d = scheme.discretisation();
  Eigen::VectorXd v0(2 * d.free_count());
  for (int f = 0; f < d.free_count(); ++f) v0.segment<2>(2 * f) = s.y0.segment<2>(scheme.velocity_offset(d.free[f]));
  LinearPeriod out;
  out.growth_rate = all.growth_rate;
  for (int k = 0; k < sp.modes.cols(); ++k) {
    const double o = std::abs(sp.modes.col(k).dot(v0)) / (sp.modes.col(k).norm() * v0.norm());
    out.lowest.push_back(2 * M_PI / w[k].imag());
    if (!(o <= out.overlap)) out.overlap = o, out.softer = k, out.period = out.lowest.back();
  }
  return out;
}

}  // namespace sphstab::gms_plate
