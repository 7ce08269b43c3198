#pragma once
// What the study measures from the probe records of the runs (impact_run.hpp): the speed of the incident Rayleigh wave
// in the slow reference, and per run the error at the probes against its reference and the speed of the surface wave
// its absorbing sides send back, against rayleigh_speed() (A.35).
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "impact_cases.hpp"
#include "impact_run.hpp"

namespace nrbc_impact {

/// Time of the largest |s| over records with t >= t_from, and that largest value.
inline std::pair<double, double> peak(const std::vector<double>& t, const std::vector<double>& s, double t_from = 0) {
  double best = 0, when = NAN;
  for (std::size_t k = 0; k < s.size(); ++k)
    if (t[k] >= t_from && std::abs(s[k]) > best) best = std::abs(s[k]), when = t[k];
  return {when, best};
}

/// Least-squares slope dx/dt of points (t_k, x_k) and its standard error.
inline std::pair<double, double> speed_fit(const std::vector<double>& t, const std::vector<double>& x) {
  const double m = static_cast<double>(t.size());
  double st = 0, sx = 0;
  for (std::size_t k = 0; k < t.size(); ++k) st += t[k], sx += x[k];
  st /= m, sx /= m;
  double stt = 0, stx = 0, sxx = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    stt += (t[k] - st) * (t[k] - st), stx += (t[k] - st) * (x[k] - sx), sxx += (x[k] - sx) * (x[k] - sx);
  const double slope = stx / stt;
  const double resid = std::max(0.0, sxx - slope * stx);
  return {slope, m > 2 ? std::sqrt(resid / (m - 2) / stt) : NAN};
}

/// v_y at probe q over a run's records.
inline std::vector<double> vy_of(const ImpactRun& r, std::size_t q) {
  std::vector<double> v;
  for (const auto& rec : r.v) v.push_back(rec[q][1]);
  return v;
}

/// The peak of a wave at a probe (a row of speeds.csv).
struct Arrival {
  std::string run, wave, probe;
  double x, t_peak, peak;
};

/// The incident Rayleigh wave of a reference run: the peak times of |v_y| at the surface probes s1..s9 (t_in), and
/// the speed fitted to them as x(t) beyond the patch (s5..s9, x >= 0.51).
struct Incident {
  double v_patch = 0;
  std::vector<double> t_in;
  double c_r = NAN, c_r_err = NAN;
  std::vector<Arrival> arrivals;
};

inline Incident incident_wave(const ImpactRun& ref) {
  const std::vector<Probe> pr = probes();
  Incident in{.v_patch = ref.c.v_patch, .t_in = std::vector<double>(pr.size(), NAN)};
  std::vector<double> ti, xi;
  for (std::size_t q = 0; q < 9; ++q) {
    const auto [when, top] = peak(ref.t, vy_of(ref, q));
    in.t_in[q] = when;
    if (q < 4) continue;
    ti.push_back(when), xi.push_back(pr[q].x);
    in.arrivals.push_back({"reference", "incident", pr[q].name, pr[q].x, when, top});
  }
  std::tie(in.c_r, in.c_r_err) = speed_fit(ti, xi);
  return in;
}

/// A run against its reference: the errors at the probes and the surface wave its absorbing sides send back.
struct Measures {
  const ImpactRun* reference = nullptr;  ///< the reference run of the same v_patch
  double error_surface = 0, error_depth = 0;
  bool sides_measured = false;                  ///< absorbing sides, the slow impact, run to the reference's end
  double reflected = NAN, reflected_err = NAN;  ///< speed of the wave sent back (NaN: too few peaks)
  std::vector<Arrival> arrivals;
};

/// The reference run of a run: the one named "reference" at the same patch speed.
inline const ImpactRun& reference_of(const std::vector<ImpactRun>& runs, const ImpactRun& r) {
  return *std::find_if(runs.begin(), runs.end(),
                       [&](const ImpactRun& q) { return q.c.name == "reference" && q.c.v_patch == r.c.v_patch; });
}

inline Measures measure(const ImpactRun& r, const ImpactRun& rf, const Incident& in) {
  const std::vector<Probe> pr = probes();
  const std::size_t np = pr.size();
  const double c_s = std::sqrt(kSteel.mu() / kSteel.density());
  Measures ms{.reference = &rf};
  // Error: per probe, the largest |v - v_ref| over time over the largest |v_ref|; the largest of these over the
  // surface probes beyond the patch (s4..s9) and over the two at depth.
  const std::size_t m = std::min(r.t.size(), rf.t.size());
  double &e_surf = ms.error_surface, &e_depth = ms.error_depth;
  for (std::size_t q = 3; q < np; ++q) {
    double e = 0, s0 = 0;
    for (std::size_t k = 0; k < m; ++k)
      e = std::max(e, (r.v[k][q] - rf.v[k][q]).norm()), s0 = std::max(s0, rf.v[k][q].norm());
    if (std::isnan(rf.v[0][q][0]) || std::isnan(r.v[0][q][0])) continue;  // a probe outside this domain
    double& into = q < 9 ? e_surf : e_depth;
    into = std::max(into, e / s0);
  }
  if (m < rf.t.size()) e_surf = e_depth = INFINITY;  // stopped early
  // The surface wave sent back by an absorbing side at x = X: at the surface probes beyond the patch (s4.., x <
  // X - 0.1), the peak of |v_y - v_y,ref| in the window of arrival times of a wave going to the side and back at a
  // speed between 0.6 c_s and c_s, t_in(x) + 2 (X - x) / [c_s, 0.6 c_s] (this excludes the reflected P; S and
  // Rayleigh are not separated, Powell's "Rayleigh/S"), fitted as x(t).
  const double side_x = 0.5 * r.c.nx * kDx;
  ms.sides_measured = r.c.side == Side::Sides && r.c.v_patch == in.v_patch && m == rf.t.size();
  if (ms.sides_measured) {
    std::vector<double> tb, xb;
    for (std::size_t q = 3; q < 9 && pr[q].x < side_x - 0.1; ++q) {
      std::vector<double> d, a = vy_of(r, q), b = vy_of(rf, q);
      for (std::size_t k = 0; k < m; ++k) d.push_back(a[k] - b[k]);
      const double from = in.t_in[q] + 2 * (side_x - pr[q].x) / c_s,
                   to = in.t_in[q] + 2 * (side_x - pr[q].x) / (0.6 * c_s);
      for (std::size_t k = 0; k < m; ++k)
        if (r.t[k] > to) d[k] = 0;
      const auto [when, top] = peak(r.t, d, from);
      if (std::isnan(when)) continue;
      tb.push_back(when), xb.push_back(pr[q].x);
      ms.arrivals.push_back({tag_of(r.c), "reflected", pr[q].name, pr[q].x, when, top});
    }
    if (tb.size() >= 3) std::tie(ms.reflected, ms.reflected_err) = speed_fit(tb, xb), ms.reflected = -ms.reflected;
  }
  return ms;
}

/// Every run measured against its reference.
inline std::vector<Measures> measure_all(const std::vector<ImpactRun>& runs, const Incident& in) {
  std::vector<Measures> ms;
  for (const ImpactRun& r : runs) ms.push_back(measure(r, reference_of(runs, r), in));
  return ms;
}

}  // namespace nrbc_impact
