// Ismail (2009) §4.6.3, the density step: a -100 kPa pulse in a 1D bar (E = 200 GPa, Hooke 1D stress, rho1 = 8000)
// meets a step to rho2 = ratio x rho1 at mid-span; the reflected and transmitted stress and particle-velocity plateaus
// against the impedance formulas (problems/impedance_step.hpp). Finite-strain TL form with a per-particle rho0
// (forms/finite_strain_total_lagrangian.hpp), modified mollifier h = 2.75 dx, plus divergence. The stiffness is one
// material for the whole bar (the form takes one HyperelasticModel): a stiffness step is not possible without
// changing the form.
// Source as in tl-bar-wave-1d: the left fixed layers carry the exact incoming wave; the right fixed layers are clamped
// (their reflection reaches no probe before t_end). Plateaus: the mean over [t_front + rise, t_front + duration - rise]
// of each wave at its probe, t_front from the exact speeds. Writes to --out DIR: probes_<case>_n<n>.csv,
// coefficients.csv, summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/impedance_step.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kE = 200e9, kRho1 = 8000, kNu = 0.3, kLength = 0.3, kStep = 0.15, kStress = -100e3;
constexpr double kHOverDx = 2.75, kRise = 2e-6, kDuration = 10e-6;
constexpr double kProbeR = 0.05, kProbeT = 0.225;

double shape(double t) {
  if (t <= 0 || t >= kDuration) return 0;
  auto s2 = [](double x) { return std::pow(std::sin(0.5 * std::numbers::pi * x), 2); };
  if (t < kRise) return s2(t / kRise);
  if (t > kDuration - kRise) return s2((kDuration - t) / kRise);
  return 1;
}
double shape_integral(double t) {
  if (t <= 0) return 0;
  const double r = kRise;
  auto ramp_int = [r](double x) { return 0.5 * x - r / (2 * std::numbers::pi) * std::sin(std::numbers::pi * x / r); };
  if (t < r) return ramp_int(t);
  const double rise = ramp_int(r);
  if (t < kDuration - r) return rise + (t - r);
  if (t < kDuration) return rise + (kDuration - 2 * r) + (rise - ramp_int(kDuration - t));
  return 2 * rise + kDuration - 2 * r;
}

struct Plateau {
  double sum_s = 0, sum_v = 0;
  int count = 0;
  double t0 = 0, t1 = 0;
  void add(double t, double s, double v) {
    if (t < t0 || t > t1) return;
    sum_s += s, sum_v += v, ++count;
  }
  double stress() const { return count ? sum_s / count : NAN; }
  double velocity() const { return count ? sum_v / count : NAN; }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ismail 2009 §4.6.3: reflection and transmission at a density step, finite-strain TL SPH (1D)"};
  std::string out = "results/tl-density-step";
  std::vector<int> resolutions{600, 1200};
  std::vector<double> ratios{2.0, 0.5};
  app.add_option("--out", out, "output directory");
  app.add_option("--n", resolutions, "free particles over the 0.3 m bar (one run each)");
  app.add_option("--ratio", ratios, "rho2 / rho1 (one case each)");
  bool quick = false;
  app.add_flag("--quick", quick, "pipeline check: n = 300 and 600 free particles (both ratios)");
  CLI11_PARSE(app, argc, argv);
  if (quick) resolutions = {300, 600};
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(kE, kNu, 1.0);
  auto hooke = std::make_shared<Hooke<1>>(lame, UniaxialState::Stress);
  const double c1 = std::sqrt(kE / kRho1);
  CsvWriter ccsv(out + "/coefficients.csv",
                 {"ratio", "n", "dx", "incident_stress_kpa", "incident_velocity", "R_stress", "R_stress_expected",
                  "T_stress", "T_stress_expected", "R_velocity", "R_velocity_expected", "T_velocity",
                  "T_velocity_expected", "steps", "dt_ns"});
  std::string md;
  study::Summary summary;
  for (double ratio : ratios) {
    const double rho2 = ratio * kRho1, c2 = std::sqrt(kE / rho2);
    const ImpedanceStep ex = impedance_step(kRho1 * c1, rho2 * c2);
    for (int n : resolutions) {
      const double dx = kLength / n;
      const Kernel<1> kernel(KernelType::ModifiedMollifier);
      const double h = kHOverDx * dx;
      const auto disc = make_discretisation(
          make_lattice<1>(LatticeType::Line, n, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)}),
          kernel, h);
      Eigen::VectorXd rho(disc->size());
      for (int i = 0; i < disc->size(); ++i) rho[i] = disc->particles.x(i, 0) < kStep ? kRho1 : rho2;
      FiniteStrainTotalLagrangian<1> tl(disc, hooke, rho);
      std::vector<double> x_fixed;
      for (int i = 0; i < disc->size(); ++i)
        if (disc->free_slot[i] < 0) x_fixed.push_back(disc->particles.x(i, 0));
      const double v0 = -kStress / (kRho1 * c1);
      Eigen::VectorXd d(x_fixed.size());
      double t_now = 0;
      auto set_fixed = [&] {
        for (std::size_t k = 0; k < x_fixed.size(); ++k)
          d[k] = x_fixed[k] < 0 ? v0 * shape_integral(t_now - x_fixed[k] / c1) : 0.0;
        tl.set_fixed_displacement(d);
      };
      set_fixed();
      const double dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
      SecondOrderSystem sys;
      sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
      sys.set_time = [&](double t) {
        t_now = t;
        set_fixed();
      };
      sys.mass = tl.dof_mass();
      LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
      auto nearest = [&](double x) {
        int best = 0;
        for (int f = 0; f < disc->free_count(); ++f)
          if (std::abs(disc->particles.x(disc->free[f], 0) - x) < std::abs(disc->particles.x(disc->free[best], 0) - x))
            best = f;
        return best;
      };
      const int fr = nearest(kProbeR), ft = nearest(kProbeT);
      const double xr = disc->particles.x(disc->free[fr], 0), xt = disc->particles.x(disc->free[ft], 0);
      // fronts of the incident (at xr), reflected (at xr) and transmitted (at xt) waves
      const double ti = xr / c1, trf = (2 * kStep - xr) / c1, ttr = kStep / c1 + (xt - kStep) / c2;
      Plateau inc{.t0 = ti + kRise, .t1 = ti + kDuration - kRise},
          ref{.t0 = trf + kRise, .t1 = trf + kDuration - kRise}, tra{.t0 = ttr + kRise, .t1 = ttr + kDuration - kRise};
      const double t_end = std::max(trf, ttr) + kDuration + kRise;
      // each plateau window must end before a wave from the ends reaches its probe: at xr the reflected wave
      // returning from the source layers ((2 kStep + xr) / c1), at xt the transmitted wave back from the clamped end
      if (ref.t1 > (2 * kStep + xr) / c1 || tra.t1 > kStep / c1 + (2 * kLength - kStep - xt) / c2)
        throw std::logic_error("tl-density-step: an end reflection reaches a probe inside its plateau window");
      const bool base = n == resolutions.back();
      std::unique_ptr<CsvWriter> pcsv;
      if (base)
        pcsv = std::make_unique<CsvWriter>(
            out + "/probes_ratio" + format_number(ratio) + "_n" + std::to_string(n) + ".csv",
            std::vector<std::string>{"t_us", "sigma_kpa_xr", "v_xr", "sigma_kpa_xt", "v_xt"}, false);
      SnapshotFunction probes([&](const StepView& s) {
        sys.set_time(s.time);
        const Eigen::MatrixXd P = tl.stresses(s.u);
        const double sr = P(disc->free[fr], 0), st = P(disc->free[ft], 0);
        const double vr = s.v[fr], vt = s.v[ft];
        inc.add(s.time, sr, vr);
        ref.add(s.time, sr, vr);
        tra.add(s.time, st, vt);
        if (base) pcsv->row({s.time * 1e6, sr / 1e3, vr, st / 1e3, vt});
      });
      study::run_probed(stepper, dt, t_end, probes);
      const double Rs = ref.stress() / inc.stress(), Ts = tra.stress() / inc.stress();
      const double Rv = ref.velocity() / inc.velocity(), Tv = tra.velocity() / inc.velocity();
      ccsv.row({ratio, n, dx, inc.stress() / 1e3, inc.velocity(), Rs, ex.stress_reflection, Ts, ex.stress_transmission,
                Rv, ex.velocity_reflection, Tv, ex.velocity_transmission, stepper.steps(), dt * 1e9});
      auto cell = [](double v, double e) {
        return study::fixed(v, 4, true) + " (" + study::fixed(e, 4, true) + ", " + study::sig(std::abs(v - e), 2) + ")";
      };
      study::md_row(md, {study::sig(ratio, 3), std::to_string(n), study::sig(inc.stress() / 1e3, 5),
                         cell(Rs, ex.stress_reflection), cell(Ts, ex.stress_transmission),
                         cell(Rv, ex.velocity_reflection), cell(Tv, ex.velocity_transmission)});
      std::cout << "ratio " << ratio << ", n = " << n << ": R_sigma " << Rs << " (" << ex.stress_reflection
                << "), T_sigma " << Ts << " (" << ex.stress_transmission << "), R_v " << Rv << " ("
                << ex.velocity_reflection << "), T_v " << Tv << " (" << ex.velocity_transmission << ")\n";
    }
  }
  summary.set("table", md);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.set("n_base", resolutions.back());
  summary.set("c1", c1, 5);
  summary.set("probe_r", kProbeR, 3);
  summary.set("probe_t", kProbeT, 3);
  summary.write(out);
  return 0;
}
