#pragma once
// The rate-form section of the TL-vs-UL pairing study (1D): the finite-strain updated-Lagrangian scheme that
// practitioners run (Gray-Monaghan-Swift / Powell: continuity, equation of state, Jaumann rate, predictor-corrector;
// forms/rate_form.hpp) on the bar, kernel and h of main.cpp. Basic SPH: summation continuity, the symmetric momentum
// equation (1.36) with the plain gradient, no XSPH, no artificial viscosity, no artificial stress; and the same with
// the GMS artificial stress (eps = 0.3, n = 4).
// 1. critical stress sigma0_crit / M by the rate-form engine (stability/rate_form_critical_stress.hpp), against
//    T_plus / (1 - T_plus) from the UL plus form's T_crit (the engine header's relation).
// 2. runs from the perturbed pre-stretched state (rate_form_bar.hpp), the measures of main.cpp's TL/UL loop.
// Writes critical_rate_form.csv, pairing_rate_form.csv, middle7_rate_form.csv and appends rows to the runs table.
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "rate_form_bar.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/stability/load_bracket.hpp"
#include "sphstab/stability/rate_form_critical_stress.hpp"

namespace pairing_rf {

struct SectionInputs {
  std::shared_ptr<const sphstab::Discretisation<1>> disc;  ///< the bar of main.cpp (lattice = stretched state)
  double t_plus = 0;                                       ///< T_crit of the UL plus form (engine, eigen route)
  double tension = 0.05;                                   ///< run tension T = sigma0 / E_bar
  double delta = 0;                                        ///< centre displacement (absolute, as the UL run)
  int centre = 0;                                          ///< free index of the centre particle
  double t_end = 100, t_arrival = 0;
  double nu = 0.3;  ///< splits M into K and mu
};

/// Unstable intervals [from, to] of tau along a grid (ascending tau, unstable flag), their edges refined between the
/// neighbouring grid points by the library's geometric bisection (stability/load_bracket.hpp) of `unstable(tau)` to
/// rtol; an interval that starts at the first grid point (or ends at the last) keeps that point as its edge.
struct UnstableInterval {
  double from, to;
  bool open_below, open_above;  ///< unstable at the first / last grid point
};

inline std::vector<UnstableInterval> unstable_intervals(const std::vector<std::pair<double, bool>>& grid,
                                                        const std::function<bool(double)>& unstable, double rtol) {
  using sphstab::LoadBracket;
  // The edge between a and b (unstable(a) != unstable(b)), a < b: bisect the predicate that holds at a.
  auto edge = [&](double a, double b) {
    const bool at_a = unstable(a);
    LoadBracket br;
    br.lo = a, br.hi = b;
    sphstab::bisect_critical_load(
        br, [&](double t) { return unstable(t) == at_a; }, rtol);
    return br.critical();
  };
  std::vector<UnstableInterval> out;
  for (std::size_t k = 0; k < grid.size();) {
    if (!grid[k].second) {
      ++k;
      continue;
    }
    std::size_t e = k;
    while (e + 1 < grid.size() && grid[e + 1].second) ++e;
    const bool below = k == 0, above = e + 1 == grid.size();
    out.push_back({below ? grid[k].first : edge(grid[k - 1].first, grid[k].first),
                   above ? grid[e].first : edge(grid[e].first, grid[e + 1].first), below, above});
    k = e + 1;
  }
  return out;
}

/// "below b (down to the smallest tried, a)", "a–b" or "above a (up to the largest tried, b)" per interval, joined by
/// "; " ("none" if empty).
inline std::string describe(const std::vector<UnstableInterval>& v) {
  using sphstab::study::sig;
  std::string s;
  for (const UnstableInterval& i : v) {
    if (!s.empty()) s += "; ";
    if (i.open_below && i.open_above)
      s += "every tension tried";
    else if (i.open_below)
      s += "below " + sig(i.to, 4) + " (down to the smallest tried, " + sig(i.from, 2) + ")";
    else if (i.open_above)
      s += "above " + sig(i.from, 4) + " (up to the largest tried, " + sig(i.to, 2) + ")";
    else
      s += sig(i.from, 4) + "–" + sig(i.to, 4);
  }
  return s.empty() ? "none" : s;
}

inline void run_section(const SectionInputs& in, const std::string& out, sphstab::study::Summary& summary,
                        std::string& md_runs) {
  using namespace sphstab;
  const double e_bar = 1.0;  // the bar's 1D modulus (E of the TL and UL forms)
  const ElasticMaterial material = material_with_modulus(e_bar, in.nu, 1.0);
  const double M = p_wave_modulus(material);
  summary.set("rf_bulk", material.bulk_modulus(), 4);
  summary.set("rf_shear", material.mu(), 4);
  summary.set("rf_m", M, 6);
  summary.set("rf_nu", in.nu, 3);

  struct Variant {
    std::string run, label;
    RateFormOptions options;
  };
  const std::vector<Variant> variants = {{"RF", "basic SPH", {}},
                                         {"RF-AS", "basic SPH + artificial stress 0.3", {.artificial_stress = 0.3}}};

  // 1. critical stress
  CsvWriter ccsv(out + "/critical_rate_form.csv",
                 {"run", "options", "sigma0_crit_over_m", "t_crit_equivalent", "xi_crit", "growth_above", "evaluations",
                  "t_plus", "predicted_t_plus_over_1_minus_t_plus", "relative_deviation", "status", "reason"});
  const double predicted = in.t_plus / (1 - in.t_plus);  // rate_form_critical_stress.hpp header note
  for (const Variant& v : variants) {
    const RateFormCriticalStress r =
        rate_form_critical_stress<1>(in.disc, material, v.options, {.direction = LoadDirection::Tension});
    const double t_equiv = r.stress / e_bar;  // T = sigma0 / E_bar, = sigma0 / M since M = E_bar
    const double dev = std::abs(r.stress_over_modulus - predicted) / predicted;
    ccsv.row({v.run, v.label, r.stress_over_modulus, t_equiv, r.xi, r.growth_above, r.evaluations, in.t_plus, predicted,
              dev, status_name(r.status), r.reason});
    const std::string key = v.run == "RF" ? "rf" : "rf_as";
    summary.set(key + "_sigma_crit", r.stress_over_modulus, 6);
    summary.set(key + "_t_crit", t_equiv, 6);
    summary.set(key + "_crit_reason", r.reason + " (" + status_name(r.status) + ")");
    if (v.run == "RF") {
      summary.set("rf_xi_crit", r.xi, 8);
      summary.set("rf_predicted", predicted, 6);
      summary.set("rf_prediction_deviation", dev, 2);
      summary.set("rf_evaluations", r.evaluations);
    }
    std::cout << "rate form " << v.label << ": sigma0_crit / M = " << r.stress_over_modulus << " (" << r.reason
              << "); T_plus / (1 - T_plus) = " << predicted << "\n";
  }

  // Growth rate of the at-rest spectrum over a grid of tensions, in the engine's family of states (deviator 0,
  // rho = rho0 / xi with sigma0 = K (1 - 1/xi)) and in the runs' family (the uniaxial stretch from rest,
  // S = (4 mu / 3) ln xi): where each scheme is unstable, beyond its first threshold. "Unstable" as in the engine:
  // growth rate > 1e-7 max |lambda|. Grid 20 points per decade from 1e-7 to 10^-0.15 = 0.71 (engine family: below
  // 0.999 K / M).
  CsvWriter gcsv(out + "/growth_rate_form.csv",
                 {"run", "family", "sigma0_over_m", "xi", "growth_rate", "growth_over_max_abs_lambda", "unstable"});
  CsvWriter bcsv(out + "/unstable_bands_rate_form.csv", {"run", "family", "from_sigma0_over_m", "to_sigma0_over_m",
                                                         "from_is_smallest_tried", "to_is_largest_tried"});
  for (const Variant& v : variants)
    for (const std::string family : {"engine", "stretched"}) {
      auto scheme_at = [&](double tau) {
        double rho = 0, dev = 0;
        if (family == "engine") {
          rho = material.density() * (1 - tau * M / material.bulk_modulus());  // rho0 / xi
        } else {
          const StretchedState st = stretched_state(material, tau * M);
          rho = st.density, dev = st.deviator;
        }
        return RateFormScheme<1>(in.disc, material, v.options, rho, Eigen::VectorXd::Constant(1, dev));
      };
      auto growth = [&](double tau) {
        const RateFormScheme<1> scheme = scheme_at(tau);
        const RateFormSpectrum spec = rate_form_spectrum(scheme, scheme.uniform_state());
        const double scale = spec.eigenvalues.size() ? spec.eigenvalues.cwiseAbs().maxCoeff() : 1.0;
        return std::pair{spec.growth_rate, scale};
      };
      auto unstable = [&](double tau) {
        const auto [g, scale] = growth(tau);
        return g > 1e-7 * scale;
      };
      std::vector<std::pair<double, bool>> grid;
      for (int k = 0; k <= 137; ++k) {
        const double tau = std::pow(10.0, -7 + k / 20.0);
        if (family == "engine" && tau * M >= 0.999 * material.bulk_modulus()) continue;
        const auto [g, scale] = growth(tau);
        const bool u = g > 1e-7 * scale;
        gcsv.row({v.run, family, tau, material.density() / scheme_at(tau).initial_density(), g, g / scale, u ? 1 : 0});
        grid.emplace_back(tau, u);
      }
      const std::vector<UnstableInterval> bands = unstable_intervals(grid, unstable, 1e-8);
      for (const UnstableInterval& b : bands)
        bcsv.row({v.run, family, b.from, b.to, b.open_below ? 1 : 0, b.open_above ? 1 : 0});
      const std::string key = (v.run == "RF" ? std::string("rf") : std::string("rf_as")) + "_" + family;
      summary.set("unstable_" + key, describe(bands));
      if (v.run == "RF")  // the first threshold (the artificial stress has none: unstable from the smallest tried)
        summary.set("first_edge_" + key,
                    bands.empty() || bands.front().open_below ? std::string("-") : study::sig(bands.front().from, 6));
      if (key == "rf_as_stretched") summary.set("gamma_smallest_" + key, growth(grid.front().first).first, 3);
    }

  // 2. runs at sigma0 = T E_bar from the stretched state
  const StretchedState st = stretched_state(material, in.tension * e_bar);
  summary.set("rf_xi", st.xi, 6);
  summary.set("rf_density", st.density, 6);
  summary.set("rf_pressure", st.pressure, 4);
  summary.set("rf_deviator", st.deviator, 4);
  const double spacing = in.disc->particles.spacing;
  CsvWriter pcsv(out + "/pairing_rate_form.csv",
                 {"run", "t", "min_gap_over_spacing", "max_gap_over_spacing", "gap_deviation_over_initial"}, false);
  std::vector<std::string> tcols{"run", "t"};
  for (int k = -3; k <= 3; ++k) tcols.push_back("d" + std::to_string(k) + "_over_dx");
  CsvWriter tcsv(out + "/middle7_rate_form.csv", tcols, false);
  for (const Variant& v : variants) {
    const RateFormScheme<1> scheme(in.disc, material, v.options, st.density, Eigen::VectorXd::Constant(1, st.deviator));
    const Eigen::VectorXd y_eq = scheme.uniform_state();
    const double residual = equilibrium_residual(scheme, y_eq);
    const RateFormSpectrum spec = rate_form_spectrum(scheme, y_eq);
    const Eigen::VectorXd x_eq = free_positions(scheme, y_eq);
    const Eigen::VectorXd y0 = perturbed_state(scheme, y_eq, in.disc->free[in.centre], in.delta);
    const PairingOptions po{
        .delta = in.delta, .spacing = spacing, .dt = 0.05, .t_end = in.t_end, .t_arrival = in.t_arrival};
    const PairingResult r = run_pairing(
        scheme, y0, po, [&](long step, double t, double gmin, double gmax, double amp, const Eigen::VectorXd& y) {
          if (step % 4 != 0) return;
          pcsv.row({v.run, t, gmin, gmax, amp});
          const Eigen::VectorXd x = free_positions(scheme, y);
          std::vector<CsvCell> row{v.run, t};
          for (int k = -3; k <= 3; ++k) row.push_back((x[in.centre + k] - x_eq[in.centre + k]) / spacing);
          tcsv.row(row);
        });
    const std::string key = v.run == "RF" ? "rf" : "rf_as";
    summary.set("t_pair_" + key, std::isnan(r.t_pair) ? std::string("never") : study::sig(r.t_pair, 4));
    summary.set("amp_arrival_" + key, r.amp_arrival, 3);
    summary.set("amp_max_" + key, r.amp_max, 3);
    summary.set("gap_min_" + key, r.gap_min, 4);
    summary.set("t_stop_" + key, r.time, 4);
    summary.set("gamma_" + key, spec.growth_rate, 3);
    study::md_row(md_runs, {v.run, scheme.name(), study::sig(residual, 2), study::sig(r.amp_arrival, 3),
                            study::sig(r.amp_max, 3), study::sig(r.gap_min, 4),
                            std::isnan(r.t_pair) ? "never" : study::sig(r.t_pair, 4), study::sig(r.time, 4), r.status});
    std::cout << v.run << ": growth rate " << spec.growth_rate << " (" << status_name(spec.status) << "), min gap "
              << r.gap_min << ", t_pair " << r.t_pair << ", " << r.status << "\n";
  }
}

}  // namespace pairing_rf
