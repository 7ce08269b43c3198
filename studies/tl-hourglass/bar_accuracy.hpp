#pragma once
// Part (c) of the tl-hourglass study, the accuracy cost of the [Ganzenmueller2015] hourglass control term on Ismail's
// 1D validation bar (common/ismail_bar.hpp, as in studies/tl-bar-wave-1d: Hooke 1D stress, modified mollifier
// h = 2.75 dx, the -100 kPa pulse from the left fixed layers, clamped right end) against the coefficient c_HG:
// leap-frog at half the linear limit of each c_HG to 1.9 L / c; max |sigma - sigma_exact| at x = 0.05, 0.10, 0.15 m,
// the mean error on the middle 80 % of the plateau at 0.10, the arrival (half amplitude) error at 0.10, the speed
// from the arrivals at 0.05 and 0.10 and the zigzag content of u at the end.
// Holds the run of one coefficient and the tables bar.csv, bar_probes.csv with their Markdown table.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/ismail_bar.hpp"
#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/models/hooke.hpp"

namespace hourglass {

using namespace sphstab;
namespace ib = sphstab::study::ismail_bar;

struct BarResult {
  double dt = 0;
  long steps = 0;
  std::vector<double> worst;  ///< per probe: max |sigma - sigma_exact|, kPa
  double plateau = 0;         ///< mean sigma - sigma_exact on the middle 80 % of the plateau at x = 0.10, kPa
  double arrival_error = 0;   ///< arrival at x = 0.10 minus the exact one, ns
  double speed_error = 0;     ///< speed from the arrivals at 0.05 and 0.10 over c, minus 1
  double zigzag = 0;          ///< RMS of the second difference / 4 of u at the end, relative to RMS u
};

/// The bar with c_HG = chg; every second step of the probe at x = 0.10 goes to probe_csv.
inline BarResult bar_run(const ib::Bar& bar, double chg, CsvWriter& probe_csv) {
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(ib::kE, ib::kNu, ib::kRho);
  const double c = std::sqrt(ib::kE / ib::kRho);
  const auto& disc = bar.disc;
  const std::vector<double>& x_fixed = bar.x_fixed;
  const std::vector<double>& probes = ib::kProbes;
  auto hooke = std::make_shared<Hooke<1>>(lame, UniaxialState::Stress);
  FiniteStrainTotalLagrangian<1> tl(disc, hooke, ib::kRho, {.hourglass = chg});
  const double v0 = ib::source_velocity(c);
  Eigen::VectorXd dfix(x_fixed.size());
  double t_now = 0;
  auto set_fixed = [&] {
    for (std::size_t k = 0; k < x_fixed.size(); ++k) dfix[k] = ib::source_displacement(x_fixed[k], t_now, c, v0);
    tl.set_fixed_displacement(dfix);
  };
  set_fixed();
  BarResult res;
  res.dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
  const double t_end = 1.9 * ib::kLength / c;
  SecondOrderSystem sys;
  sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
    set_fixed();
    tl.acceleration(u, a);
  };
  sys.set_time = [&](double t) { t_now = t; };
  sys.mass = tl.dof_mass();
  LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
  res.worst.assign(probes.size(), 0.0);
  std::vector<double> arrival(probes.size(), std::nan("")), prev(probes.size(), 0.0);
  double t_prev = 0, plateau_sum = 0;
  long plateau_count = 0;
  SnapshotFunction probe_run([&](const StepView& view) {
    const double t = view.time;
    t_now = t;
    const Eigen::MatrixXd P = tl.stresses(view.u);
    for (std::size_t p = 0; p < probes.size(); ++p) {
      const double xp = bar.probe_x(p);
      const double s = P(disc->free[bar.probe_slot[p]], 0);
      const double exact = ib::exact_stress(xp, t, c);
      res.worst[p] = std::max(res.worst[p], std::abs(s - exact) / 1e3);
      const double threshold = 0.5 * ib::kStress * (p == 2 ? 2 : 1);
      if (std::isnan(arrival[p]) && s <= threshold) arrival[p] = ib::crossing_time(t_prev, prev[p], t, s, threshold);
      prev[p] = s;
      if (p == 1) {
        // plateau: the incident wave's flat top at x = 0.10 (reflection not yet there), middle 80 %
        const double tau = t - xp / c;
        if (tau > ib::kRise + 0.1 * (ib::kDuration - 2 * ib::kRise) &&
            tau < ib::kDuration - ib::kRise - 0.1 * (ib::kDuration - 2 * ib::kRise)) {
          plateau_sum += s - exact;
          ++plateau_count;
        }
        if (view.step % 2 == 0) probe_csv.row({chg, t * 1e6, s / 1e3, exact / 1e3});
      }
    }
    t_prev = t;
  });
  study::run_probed(stepper, res.dt, t_end, probe_run);
  res.steps = stepper.steps();
  // zigzag content at the end: RMS of the second difference / 4 of u over the free particles, relative to RMS u
  const Eigen::VectorXd& u = stepper.u();
  double z = 0;
  for (int f = 1; f + 1 < u.size(); ++f) z += std::pow((u[f + 1] - 2 * u[f] + u[f - 1]) / 4, 2);
  res.zigzag = std::sqrt(z / (u.size() - 2)) / std::sqrt(u.squaredNorm() / u.size());
  const double xa = bar.probe_x(0), xb = bar.probe_x(1);
  res.speed_error = (xb - xa) / (arrival[1] - arrival[0]) / c - 1;
  const double t_half = ib::kRise / 2;
  res.arrival_error = (arrival[1] - (t_half + xb / c)) * 1e9;
  res.plateau = plateau_sum / std::max(1L, plateau_count) / 1e3;
  return res;
}

/// bar.csv, bar_probes.csv and the Markdown table of the bar.
struct BarTables {
  CsvWriter bar, probes;
  std::string md_bar;
  explicit BarTables(const std::string& out)
      : bar(out + "/bar.csv",
            {"hourglass", "dt_ns", "steps", "max_error_kpa_x0.05", "max_error_kpa_x0.1", "max_error_kpa_x0.15",
             "plateau_error_kpa_x0.1", "arrival_error_ns_x0.1", "speed_rel_error", "zigzag_rms_end"}),
        probes(out + "/bar_probes.csv", {"hourglass", "t_us", "sigma_sph_kpa_x0.1", "sigma_exact_kpa_x0.1"}) {}
  void add(double chg, const BarResult& r) {
    const std::vector<double>& worst = r.worst;
    bar.row(
        {chg, r.dt * 1e9, r.steps, worst[0], worst[1], worst[2], r.plateau, r.arrival_error, r.speed_error, r.zigzag});
    study::md_row(md_bar,
                  {study::sig(chg, 2), study::sig(r.dt * 1e9, 4), study::sig(worst[0], 3), study::sig(worst[1], 3),
                   study::sig(worst[2], 3), study::fixed(r.plateau, 3, true), study::fixed(r.arrival_error, 2, true),
                   study::fixed(100 * r.speed_error, 3, true) + " %", study::sig(r.zigzag, 3)});
  }
};

}  // namespace hourglass
