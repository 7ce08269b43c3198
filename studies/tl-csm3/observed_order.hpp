#pragma once
// The observed order of convergence of the Turek & Hron (2006) CSM3 study over the last three resolutions of the
// chosen form (order.csv and its Markdown table): per measure (u_x, u_y mean, amplitude, frequency) the order p from
// three values by bisection, the log-log slope of the error against the reference and the Richardson extrapolation.
#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "common/study.hpp"
#include "csm3_cases.hpp"
#include "run_tables.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace csm3_study {

using namespace sphstab;

/// Observed order p of three values at spacings h1 > h2 > h3: (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p),
/// by bisection on p in [0.05, 8]; NaN when the differences change sign (no monotone convergence) or no root lies
/// there.
inline double observed_order(double h1, double h2, double h3, double f1, double f2, double f3) {
  const double r = (f1 - f2) / (f2 - f3);
  if (!(r > 0) || !std::isfinite(r)) return NAN;
  auto g = [&](double p) { return (std::pow(h1, p) - std::pow(h2, p)) / (std::pow(h2, p) - std::pow(h3, p)) - r; };
  double a = 0.05, b = 8;
  if (g(a) * g(b) > 0) return NAN;
  for (int it = 0; it < 100; ++it) {
    const double c = 0.5 * (a + b);
    (g(a) * g(c) <= 0 ? b : a) = c;
  }
  return 0.5 * (a + b);
}

/// Writes <out>/order.csv (header only with fewer than three resolutions) from the runs of the chosen form, the
/// first `resolutions` entries of `results`, and returns its Markdown table.
inline std::string order_table(const std::string& out, const std::vector<CaseResult>& results,
                               std::size_t resolutions) {
  std::string md_order;
  CsvWriter ocsv(out + "/order.csv", {"quantity", "value_1", "value_2", "value_3", "reference", "observed_order",
                                      "loglog_slope_of_error", "richardson_extrapolated"});
  if (resolutions >= 3) {
    const CaseResult &a = results[resolutions - 3], &b = results[resolutions - 2], &c = results[resolutions - 1];
    const std::vector<std::tuple<std::string, std::array<double, 3>, double>> qs{
        {"ux mean", {a.ux.mean, b.ux.mean, c.ux.mean}, C::ux_mean},
        {"ux amplitude", {a.ux.amplitude, b.ux.amplitude, c.ux.amplitude}, C::ux_amplitude},
        {"uy mean", {a.uy.mean, b.uy.mean, c.uy.mean}, C::uy_mean},
        {"uy amplitude", {a.uy.amplitude, b.uy.amplitude, c.uy.amplitude}, C::uy_amplitude},
        {"uy frequency", {a.uy.frequency, b.uy.frequency, c.uy.frequency}, C::frequency},
        {"ux frequency", {a.ux.frequency, b.ux.frequency, c.ux.frequency}, C::frequency}};
    for (const auto& [name, v, ref] : qs) {
      const double p = observed_order(a.dx, b.dx, c.dx, v[0], v[1], v[2]);
      const double slope = study::loglog_slope({a.dx, b.dx, c.dx}, {v[0] - ref, v[1] - ref, v[2] - ref});
      // Richardson: f_h = f + C h^p, so f = f3 + (f3 - f2) / ((h2 / h3)^p - 1); NaN without an order
      const double ext = v[2] + (v[2] - v[1]) / (std::pow(b.dx / c.dx, p) - 1);
      ocsv.row({name, v[0], v[1], v[2], ref, p, slope, ext});
      study::md_row(md_order, {name, study::sig(v[0], 5), study::sig(v[1], 5), study::sig(v[2], 5), study::sig(ref, 5),
                               study::sig(p, 3), study::sig(slope, 3), study::sig(ext, 5),
                               std::isnan(ext) ? std::string("-") : rel(ext, ref)});
    }
  }
  return md_order;
}

}  // namespace csm3_study
