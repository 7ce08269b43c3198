// Study: is the growth of the rate-form Swegle runs linear, nonlinear or made by the time integrator? For each
// (formulation, xi) the full-state linear growth rate (growth/rate_form_spectrum.hpp) is compared with the fitted
// kinetic-energy growth of runs kicked at four amplitudes v0, with the GMS predictor-corrector and with Powell's
// leap-frog (integrate/rate_form_run.hpp), and, for the predictor-corrector at the smallest kick, at dt and dt/2
// (integrator-made growth falls as dt^3). Each (formulation, xi, integrator, dt) gets its stability verdict
// (growth/stability_verdict.hpp, in the mirror class the kick excites): S, U, I or B from the semi-discrete growth,
// the integrator's one-step map growth and the run's detection floor. See README.md; the prose of the summary is
// summary.md.in.
//
// Writes to --out DIR: runs.csv, summary.json. Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/swegle.hpp"

using namespace sphstab;

namespace {

struct Formulation {
  std::string name;
  RateFormOptions options;
};

std::vector<Formulation> formulations() {
  const RateFormOptions ncsph{.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph};
  RateFormOptions anti = ncsph;
  anti.momentum = RateFormMomentum::Antisymmetric;
  const RateFormOptions ssph{.xsph = 0.5, .momentum = RateFormMomentum::StabilisedSph};
  RateFormOptions printed = ssph;
  printed.switch_rule = SwitchRule::AsPrinted;
  return {{"sph", {}}, {"ncsph", ncsph}, {"ncsph-anti", anti}, {"ssph", ssph}, {"ssph-printed", printed}};
}

std::string integrator_name(RateFormIntegrator integrator) {
  return integrator == RateFormIntegrator::Leapfrog ? "leapfrog" : "predictor-corrector";
}

struct Measured {
  RateFormRunResult run;
  ExponentialGrowthFit fit;
  double ke_max = 0;  // max KE / KE0
  // Fit over the pre-saturation window only: it ends when KE first reaches 1e-2 of its maximum (growth, if any, is
  // then still exponential). Separates a growth RATE that depends on v0 from a growth that saturates.
  ExponentialGrowthFit early;
  std::string status;  // run_status_name, or "exception"
  double wall = 0;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Swegle test, rate-form scheme: linear, nonlinear or integrator-made growth?"};
  std::string out = "results/swegle-nonlinear";
  int n = 11;
  double t_end = 30, onset = 100, stop_growth = 1e10;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles per side (odd)")->check(CLI::Range(5, 101));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out);

  const std::vector<double> xis = {0.98, 1.02};
  const std::vector<double> v0s = {1e-10, 1e-4, 1e-2};  // 1e-7 dropped for run time (it matched 1e-10)
  const std::vector<RateFormIntegrator> integrators = {RateFormIntegrator::PredictorCorrector,
                                                       RateFormIntegrator::Leapfrog};
  SwegleOptions so;
  so.n = n;
  so.layer_supports = 3;  // S-SPH reads neighbours of neighbours: every corrected form starts in exact equilibrium
  const SwegleScene scene = make_swegle_scene(so);
  const auto& disc = scene.discretisation;
  // Mirror class (px, py) = (-1, +1) of the free velocity DOFs: the one a +x kick at the centre excites.
  Eigen::VectorXd pos(2 * disc->free_count());
  for (int f = 0; f < disc->free_count(); ++f) pos.segment<2>(2 * f) = disc->particles.x.row(disc->free[f]).transpose();
  const Eigen::Vector2d centre = disc->particles.x.row(scene.centre).transpose();
  const Eigen::MatrixXd excited = symmetry_basis(mirror_symmetry(pos, centre, 1e-9 * so.spacing), -1, 1);

  const RateFormMaterial steel = RateFormMaterial::from_youngs(2.1, 0.3, 7.8);
  const double cp = steel.p_wave_speed(), dt = 0.3 * scene.h / cp;

  const auto measure = [&](const RateFormScheme<2>& scheme, double v0, RateFormIntegrator integrator, double step) {
    Eigen::VectorXd y = scheme.uniform_state();
    scheme.set_velocity(y, scene.centre, Eigen::Vector2d(v0, 0));
    Measured m;
    const auto tr = study::Clock::now();
    // A run can end in an exception (the NCSPH moment matrix turns singular when particles clump at large v0): the
    // observer keeps the kinetic-energy series up to the last record before it.
    std::vector<double> times, kinetic;
    try {
      m.run = run_rate_form(scheme, y,
                            {.dt = step,
                             .t_end = t_end,
                             .record_every = 10,
                             .energy_growth = stop_growth,
                             .observer =
                                 [&](long, double t, const Eigen::VectorXd& state) {
                                   times.push_back(t);
                                   kinetic.push_back(scheme.kinetic_energy(state));
                                 },
                             .integrator = integrator});
      m.status = run_status_name(m.run.status);
    } catch (const std::exception& e) {
      std::printf("  run ended by an exception: %s\n", e.what());
      m.status = "exception";
      m.run.times = times;
      m.run.kinetic_energy = kinetic;
      m.run.time = times.back();
      m.run.dt = step;
    }
    m.wall = study::seconds_since(tr);
    const double ke0 = m.run.kinetic_energy.front();
    m.fit = fit_exponential_growth(m.run.times, m.run.kinetic_energy, ke0, m.run.times.back(), {.onset_factor = onset});
    for (double e : m.run.kinetic_energy) m.ke_max = std::max(m.ke_max, e / ke0);
    double t_sat = m.run.times.back();
    for (std::size_t k = 0; k < m.run.times.size(); ++k)
      if (m.run.kinetic_energy[k] >= 1e-2 * m.ke_max * ke0) {
        t_sat = m.run.times[k];
        break;
      }
    m.early = fit_exponential_growth(m.run.times, m.run.kinetic_energy, ke0, t_sat, {.onset_factor = onset});
    return m;
  };

  std::ofstream runs_csv(out + "/runs.csv");
  runs_csv << "formulation,xi,v0,integrator,dt,gamma_linear,gamma_measured,grew,status,t_stop,ke_max_over_ke0,"
              "gamma_linear_class,gamma_map_class,verdict,floor,ratio,fit_r2,fit_t_begin,fit_t_end,gamma_bound,"
              "gamma_presaturation,presaturation_t_end,wall\n";
  const double floor = detection_floor(t_end, onset);  // the slowest growth the fit can see in t_end
  const auto verdict = [&](const RateFormScheme<2>& scheme, RateFormIntegrator integrator, double step) {
    const StabilityVerdict v = stability_verdict(scheme, scheme.uniform_state(), {.dt = step, .integrator = integrator},
                                                 {.floor = floor, .basis = excited});
    if (v.status != Status::Successful) throw std::runtime_error("verdict: " + v.reason);
    return v;
  };
  const auto write_row = [&](const std::string& form, double xi, double v0, RateFormIntegrator integrator,
                             const RateFormSpectrum& all, const RateFormSpectrum& cls, const StabilityVerdict& v,
                             const Measured& m) {
    runs_csv << csv_line({form,
                          format_number(xi),
                          format_number(v0),
                          integrator_name(integrator),
                          format_number(m.run.dt, 8),
                          format_number(all.growth_rate, 8),
                          format_number(m.fit.gamma, 8),
                          m.fit.grew ? "1" : "0",
                          m.status,
                          format_number(m.run.time, 6),
                          format_number(m.ke_max, 6),
                          format_number(cls.growth_rate, 8),
                          format_number(v.map_growth, 8),
                          v.letter(),
                          format_number(floor, 6),
                          format_number(m.fit.grew ? m.fit.gamma / all.growth_rate : NAN, 6),
                          format_number(m.fit.fit.r2, 8),
                          format_number(m.fit.fit.t_begin, 6),
                          format_number(m.fit.fit.t_end, 6),
                          format_number(m.fit.gamma_bound, 6),
                          format_number(m.early.gamma, 8),
                          format_number(m.early.fit.t_end, 6),
                          format_number(m.wall, 3)});
    runs_csv.flush();
  };

  std::string table, dt_table, semi_list, integrator_list, stable_list, amplitude_list, low_r2;
  double wall_linear = 0, wall_runs = 0;
  for (const Formulation& form : formulations()) {
    for (double xi : xis) {
      const RateFormScheme<2> scheme(disc, steel, form.options, steel.density / xi);
      const Eigen::VectorXd y_rest = scheme.uniform_state();
      auto tl = study::Clock::now();
      const RateFormSpectrum all = rate_form_spectrum(scheme, y_rest);
      const RateFormSpectrum cls = rate_form_spectrum(scheme, y_rest, {.basis = excited});
      // The verdicts of the three (integrator, dt) the runs use, in the excited class.
      const StabilityVerdict vpc = verdict(scheme, RateFormIntegrator::PredictorCorrector, dt);
      const StabilityVerdict vlf = verdict(scheme, RateFormIntegrator::Leapfrog, dt);
      const StabilityVerdict vhalf = verdict(scheme, RateFormIntegrator::PredictorCorrector, 0.5 * dt);
      wall_linear += study::seconds_since(tl);
      std::vector<std::string> row{"**" + form.name + "**", study::fixed(xi, 2), study::sig(all.growth_rate, 4),
                                   vpc.letter() + " / " + vlf.letter()};
      const std::string label = "`" + form.name + "` ξ = " + study::fixed(xi, 2);
      std::map<RateFormIntegrator, std::map<double, Measured>> runs;
      for (RateFormIntegrator integrator : integrators)
        for (double v0 : v0s) {
          const Measured m = measure(scheme, v0, integrator, dt);
          wall_runs += m.wall;
          const StabilityVerdict& v = integrator == RateFormIntegrator::Leapfrog ? vlf : vpc;
          write_row(form.name, xi, v0, integrator, all, cls, v, m);
          std::string cell = m.fit.grew ? study::sig(m.fit.gamma, 4) : "S";
          if (m.early.grew && (!m.fit.grew || std::abs(m.early.gamma / m.fit.gamma - 1) > 0.05))
            cell += " [" + study::sig(m.early.gamma, 4) + "]";
          if (m.status != "completed") cell += " (" + m.status + ")";
          row.push_back(cell);
          if (m.fit.grew && m.fit.fit.r2 < 0.5)
            low_r2 += "- " + label + ", " + integrator_name(integrator) + ", v0 = " + study::sig(v0, 1) + ": γ " +
                      study::sig(m.fit.gamma, 3) + ", r² " + study::sig(m.fit.fit.r2, 2) + "\n";
          std::printf(
              "%-12s xi %.2f %-19s v0 %.0e: %s, gamma linear %.5g (class %.5g, map %.5g), measured %.5g (%s), "
              "pre-saturation %.5g, %s t %.3g (%.1f s)\n",
              form.name.c_str(), xi, integrator_name(integrator).c_str(), v0, v.letter().c_str(), all.growth_rate,
              cls.growth_rate, v.map_growth, m.fit.gamma, m.fit.grew ? "grew" : "bounded", m.early.gamma,
              m.status.c_str(), m.run.time, m.wall);
          std::fflush(stdout);
          runs[integrator][v0] = m;
        }
      study::md_row(table, row);
      // dt dependence, predictor-corrector at the smallest kick: dt/2.
      const Measured half = measure(scheme, v0s.front(), RateFormIntegrator::PredictorCorrector, 0.5 * dt);
      wall_runs += half.wall;
      write_row(form.name, xi, v0s.front(), RateFormIntegrator::PredictorCorrector, all, cls, vhalf, half);
      const Measured& pc = runs[RateFormIntegrator::PredictorCorrector][v0s.front()];
      const Measured& lf = runs[RateFormIntegrator::Leapfrog][v0s.front()];
      const auto measured = [](const Measured& m) {
        return m.fit.grew ? study::sig(m.fit.gamma, 3) : "– (KE max " + study::sig(m.ke_max, 2) + " KE0)";
      };
      study::md_row(dt_table, {"**" + form.name + "**", study::fixed(xi, 2), study::sig(all.growth_rate, 4),
                               study::sig(pc.fit.gamma, 4), study::sig(half.fit.gamma, 4),
                               study::sig(vpc.map_growth, 3) + " " + vpc.letter(),
                               study::sig(vhalf.map_growth, 3) + " " + vhalf.letter()});
      // The verdict lists of the summary, from the classes and the smallest kick's runs.
      const std::string runs_text = "measured PC " + measured(pc) + ", LF " + measured(lf) + ", PC at dt/2 " +
                                    measured(half);
      if (vpc.verdict == VerdictClass::SemiDiscrete || vpc.verdict == VerdictClass::Both)
        semi_list += "- " + label + ": " + vpc.letter() + " (LF " + vlf.letter() + ", dt/2 " + vhalf.letter() +
                     "), γ_J = " + study::sig(vpc.semi_discrete_growth, 4) + "; " + runs_text + "\n";
      else if (vpc.verdict == VerdictClass::Integrator)
        integrator_list += "- " + label + ": I at dt (γ_M = " + study::sig(vpc.map_growth, 3) + "), " +
                           vhalf.letter() + " at dt/2 (γ_M = " + study::sig(vhalf.map_growth, 3) + "), LF " +
                           vlf.letter() + "; " + runs_text + "\n";
      else
        stable_list += "- " + label + ": S (LF " + vlf.letter() + "); " + runs_text + "\n";
      // Growth the verdict does not predict at the largest kick: amplitude-dependent.
      for (RateFormIntegrator integrator : integrators) {
        const Measured& big = runs[integrator][v0s.back()];
        const StabilityVerdict& v = integrator == RateFormIntegrator::Leapfrog ? vlf : vpc;
        if (big.fit.grew && !(v.map_growth > floor))
          amplitude_list += "- " + label + ", " + integrator_name(integrator) + ", v0 = " +
                            study::sig(v0s.back(), 1) + ": grew at " + study::sig(big.fit.gamma, 3) + " /µs (r² " +
                            study::sig(big.fit.fit.r2, 2) + "), the map predicts " + v.letter() + "; " + big.status +
                            " at t = " + study::sig(big.run.time, 3) + " µs\n";
      }
      std::printf("%-12s xi %.2f dt/2: measured %.5g (%s)\n", form.name.c_str(), xi, half.fit.gamma,
                  half.fit.grew ? "grew" : "bounded");
    }
  }

  // Block size: the full-state growth rate at rest of each formulation against n (same fixed layers, same h). A
  // verdict of "neutral" on the n x n block of the runs can be a finite-size effect: the critical tension of a
  // block falls towards the infinite lattice's (studies/dispersion-rate-form) as n grows.
  std::ofstream size_csv(out + "/block_size.csv");
  size_csv << "formulation,xi,n,gamma_linear,lambda_imag\n";
  const std::vector<int> sizes = {9, 11, 13, 15, 17, 21};
  std::string size_table, size_onsets;
  for (const Formulation& form : formulations())
    for (double xi : xis) {
      std::vector<std::string> row{"**" + form.name + "**", study::fixed(xi, 2)};
      int last_neutral = 0, first_growing = 0, growing = 0;
      for (int m : sizes) {
        SwegleOptions sm = so;
        sm.n = m;
        const SwegleScene sc = make_swegle_scene(sm);
        const RateFormScheme<2> scheme(sc.discretisation, steel, form.options, steel.density / xi);
        const auto tl = study::Clock::now();
        const RateFormSpectrum all = rate_form_spectrum(scheme, scheme.uniform_state());
        wall_linear += study::seconds_since(tl);
        // Growth below 1e-9 of the largest |lambda| is rounding of a neutral spectrum.
        const bool grows = all.growth_rate > 1e-9 * all.eigenvalues.cwiseAbs().maxCoeff();
        size_csv << csv_line({form.name, format_number(xi), std::to_string(m), format_number(all.growth_rate, 8),
                              format_number(std::abs(all.lambda.imag()), 8)});
        row.push_back(grows ? study::sig(all.growth_rate, 3) : "0");
        if (grows) {
          ++growing;
          if (!first_growing) first_growing = m;
        } else {
          last_neutral = m;
        }
      }
      const std::string who = "`" + form.name + "` ξ = " + study::fixed(xi, 2) + ": ";
      const auto side = [](int m) { return std::to_string(m) + " × " + std::to_string(m); };
      if (growing == static_cast<int>(sizes.size()))
        size_onsets += "- " + who + "unstable at every size\n";
      else if (growing == 0)
        size_onsets += "- " + who + "neutral at every size\n";
      else if (last_neutral < first_growing)
        size_onsets += "- " + who + "neutral up to " + side(last_neutral) + ", unstable from " + side(first_growing) +
                       "\n";
      else
        size_onsets += "- " + who + "neutral and unstable sizes interleave (" + std::to_string(growing) + " of " +
                       std::to_string(sizes.size()) + " unstable)\n";
      study::md_row(size_table, row);
      std::printf("%-12s xi %.2f block sizes done (%.0f s)\n", form.name.c_str(), xi, study::seconds_since(t0));
      std::fflush(stdout);
    }

  study::Summary s;
  s.set("size_table", size_table);
  s.set("size_onsets", size_onsets);
  s.set("n", n);
  s.set("particles", disc->size());
  s.set("c_P", cp, 4);
  s.set("dt", dt, 4);
  s.set("t_end", t_end, 4);
  s.set("onset", onset, 3);
  s.set("stop_growth", stop_growth, 3);
  s.set("table", table);
  s.set("dt_table", dt_table);
  s.set("floor", floor, 3);
  const auto list = [](const std::string& l) { return l.empty() ? std::string("- none\n") : l; };
  s.set("semi_list", list(semi_list));
  s.set("integrator_list", list(integrator_list));
  s.set("stable_list", list(stable_list));
  s.set("amplitude_list", list(amplitude_list));
  s.set("low_r2_list", list(low_r2));
  s.set("wall_linear", wall_linear, 3);
  s.set("wall_runs", wall_runs, 3);
  s.set("wall_total", study::seconds_since(t0), 3);
  s.write(out);
  std::printf("wall: linear %.1f s, runs %.1f s, total %.1f s\n", wall_linear, wall_runs, study::seconds_since(t0));
  return 0;
}
