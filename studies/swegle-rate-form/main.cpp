// Study: the Swegle test as Powell ran it, with the rate-form scheme (forms/rate_form.hpp: continuity, equation of
// state, Jaumann rate) instead of the additive pre-stress of the §3.3 model (studies/swegle). Each (formulation, xi)
// gets its full-state linear growth rate (growth/rate_form_spectrum.hpp, in the mirror class the kick excites and
// over all classes), its stability verdict (growth/stability_verdict.hpp: the semi-discrete growth of J and the
// predictor-corrector's one-step map growth at the run's dt, in the excited class, against the run's detection floor:
// S, U, I or B) and a nonlinear run (GMS predictor-corrector, integrate/rate_form_run.hpp) whose kinetic-energy
// growth is fitted. See README.md; the prose of the summary is summary.md.in.
//
// Writes to --out DIR: runs.csv, ke.csv, summary.json. Units g, cm, us (stress in Mbar).
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
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
  std::string name, label;
  RateFormOptions options;
  int layer_supports = 1;  // fixed layers (in supports) the formulation needs for an exact equilibrium
};

/// The terms of the scheme practitioners switch on, one at a time and together (MCM deck viscosity 0.06 / 1.5;
/// GMS XSPH 1/2 and artificial stress 0.3, n = 4).
std::vector<Formulation> formulations() {
  const RateFormOptions visc{.viscosity = ViscositySwitch::Compression};
  return {
      {"sph", "basic SPH (continuity by summation, rho^2 momentum)", {}},
      {"sph-xsph", "SPH + XSPH (GMS 3.6, eps = 1/2)", {.xsph = 0.5}},
      {"sph-visc", "SPH + artificial viscosity (compression switch, alpha 0.06, beta 1.5)", visc},
      {"sph-as", "SPH + GMS artificial stress (eps = 0.3, n = 4)", {.artificial_stress = 0.3}},
      {"sph-div", "SPH with continuity -rho tr L (GMS 3.9)", {.continuity = ContinuityForm::Divergence}},
      {"sph-all",
       "SPH + XSPH + viscosity + artificial stress",
       {.xsph = 0.5, .viscosity = ViscositySwitch::Compression, .artificial_stress = 0.3}},
      // Kernel corrections (Powell 1.19, 4.10, algorithm 4.2). MCM's continuity (1.32) is -rho tr L of the
      // corrected velocity gradient.
      {"ncsph",
       "NCSPH (1.19) in L and in the row momentum (1.36), continuity -rho tr L (MCM)",
       {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph},
       2},
      {"ncsph-xsph",
       "NCSPH + XSPH (eps = 1/2)",
       {.continuity = ContinuityForm::Divergence, .xsph = 0.5, .gradient = RateFormGradient::Ncsph},
       2},
      {"ncsph-anti",
       "NCSPH with antisymmetrised pair forces (momentum conserving)",
       {.continuity = ContinuityForm::Divergence,
        .gradient = RateFormGradient::Ncsph,
        .momentum = RateFormMomentum::Antisymmetric},
       2},
      {"cij", "C_ij momentum (4.10), local polish (4.9) with actual counts", {.momentum = RateFormMomentum::Cij}, 2},
      {"ssph",
       "S-SPH (algorithm 4.2), switch on in tension (4.15)-(4.17), + XSPH",
       {.xsph = 0.5, .momentum = RateFormMomentum::StabilisedSph},
       3},
      {"ssph-printed",
       "S-SPH with the switch as printed in algorithm 4.2 (on in compression), + XSPH",
       {.xsph = 0.5, .momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::AsPrinted},
       3}};
}

/// One (formulation, xi) of the table: its verdict and its run.
struct Cell {
  std::string letter;
  double gamma_j = NAN, gamma_m = NAN, measured = NAN;
  bool grew = false;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Swegle test with the rate-form SPH scheme: full-state linear versus measured growth"};
  std::string out = "results/swegle-rate-form";
  int n = 21;
  double t_end = 45, onset = 100, stop_growth = 1e10;
  app.add_option("--out", out, "output directory");
  app.add_option("--n", n, "free particles per side (odd)")->check(CLI::Range(5, 101));
  app.add_option("--t-end", t_end, "run length (us)")->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);
  const auto t0 = study::Clock::now();
  std::filesystem::create_directories(out);

  const std::vector<double> xis = {0.96, 0.98, 0.99, 1.0, 1.01, 1.02, 1.04};
  SwegleOptions so;
  so.n = n;
  // Scenes with fixed layers of 1, 2, 3 supports (block, centre particle, kick direction) and, for each, the mirror
  // class (px, py) = (-1, +1) of the free velocity DOFs, where the kick (+x at the centre) lies.
  struct SceneClass {
    SwegleScene scene;
    Eigen::MatrixXd excited;
  };
  std::vector<SceneClass> scenes;
  for (int layers = 1; layers <= 3; ++layers) {
    SwegleOptions sl = so;
    sl.layer_supports = layers;
    SceneClass sc{make_swegle_scene(sl), {}};
    const auto& d = sc.scene.discretisation;
    Eigen::VectorXd pos(2 * d->free_count());
    for (int f = 0; f < d->free_count(); ++f) pos.segment<2>(2 * f) = d->particles.x.row(d->free[f]).transpose();
    const Eigen::Vector2d centre = d->particles.x.row(sc.scene.centre).transpose();
    sc.excited = symmetry_basis(mirror_symmetry(pos, centre, 1e-9 * so.spacing), -1, 1);
    scenes.push_back(std::move(sc));
  }
  const SwegleScene& scene = scenes[0].scene;
  const auto& disc = scene.discretisation;
  const Eigen::MatrixXd& excited = scenes[0].excited;
  const RateFormMaterial steel = RateFormMaterial::from_youngs(so.youngs_modulus, so.poisson_ratio, so.density);
  const double cp = steel.p_wave_speed(), dt = 0.3 * scene.h / cp;
  const double detect = std::log(onset) / (2 * t_end);  // slowest growth that reaches the onset within t_end

  std::ofstream runs_csv(out + "/runs.csv"), ke_csv(out + "/ke.csv");
  runs_csv << "formulation,xi,density,pressure,gamma_linear_class,lambda_imag_class,gamma_linear_all,gamma_map_class,"
              "invariance_residual,structure_residual,equilibrium_residual,gamma_measured,grew,fit_t_begin,fit_t_end,"
              "fit_r2,ratio,"
              "verdict,floor,integrator_excess,map_predicts_growth,status,steps,t_stop,ke_max_over_ke0,wall_linear,"
              "wall_run,layer_supports,particles\n";
  ke_csv << "formulation,xi,t,kinetic\n";
  std::string table, ratios_table;
  double ratio_min = 1e300, ratio_max = -1e300, smooth_min = 1e300, smooth_max = -1e300, wall_linear = 0, wall_runs = 0;
  int agree = 0, cases = 0, comparable = 0;
  std::map<std::string, int> classes;  // verdict letter -> count
  std::map<std::string, std::map<double, Cell>> cells;  // formulation -> xi -> verdict and run
  std::string disagreements;  // runs whose growth the map does not predict (or the reverse)
  double eq_res_max = 0;  // largest equilibrium residual over the kick's acceleration scale
  for (const Formulation& form : formulations()) {
    std::vector<std::string> row{"**" + form.name + "**"};
    for (double xi : xis) {
      const double rho = so.density / xi;
      const SceneClass& sc = scenes[form.layer_supports - 1];
      const auto& fdisc = sc.scene.discretisation;
      const RateFormScheme<2> scheme(fdisc, steel, form.options, rho);
      Eigen::VectorXd y = scheme.uniform_state();
      auto tl = study::Clock::now();
      const RateFormSpectrum all = rate_form_spectrum(scheme, y);
      const RateFormSpectrum cls = rate_form_spectrum(scheme, y, {.basis = sc.excited});
      double w_lin = study::seconds_since(tl);
      wall_linear += w_lin;
      // Residual of the unkicked state against the accelerations the kick produces, v0 c_P / h (the kick changes
      // only the rates of x, rho and S at first, so its own immediate change of the accelerations is 0 at rest):
      // the run measures growth from the kick only if the block starts in equilibrium.
      Eigen::VectorXd f_eq;
      scheme.rate(y, f_eq);
      const Eigen::Vector2d kick = sc.scene.v0.segment<2>(2 * fdisc->free_slot[sc.scene.centre]);
      scheme.set_velocity(y, sc.scene.centre, kick);
      const double kick_acc = kick.norm() * steel.p_wave_speed() / fdisc->h;
      double eq_res = 0;
      for (int i = 0; i < fdisc->size(); ++i)
        if (scheme.velocity_offset(i) >= 0)
          eq_res = std::max(eq_res, f_eq.segment<2>(scheme.velocity_offset(i)).cwiseAbs().maxCoeff());
      eq_res_max = std::max(eq_res_max, eq_res / kick_acc);
      tl = study::Clock::now();
      const RateFormRunResult run =
          run_rate_form(scheme, y, {.dt = dt, .t_end = t_end, .record_every = 10, .energy_growth = stop_growth});
      const double w_run = study::seconds_since(tl);
      wall_runs += w_run;
      for (std::size_t k = 0; k < run.times.size(); ++k)
        ke_csv << csv_line(
            {form.name, format_number(xi), format_number(run.times[k], 8), format_number(run.kinetic_energy[k], 8)});
      const double ke0 = run.kinetic_energy.front();
      const ExponentialGrowthFit fit =
          fit_exponential_growth(run.times, run.kinetic_energy, ke0, run.times.back(), {.onset_factor = onset});
      double ke_max = 0;
      for (double e : run.kinetic_energy) ke_max = std::max(ke_max, e / ke0);
      // The verdict at the run's dt (run_rate_form rounds dt to t_end / steps), in the excited class, at rest.
      tl = study::Clock::now();
      const StabilityVerdict v = stability_verdict(scheme, scheme.uniform_state(), {.dt = run.dt},
                                                   {.floor = detect, .basis = sc.excited});
      if (v.status != Status::Successful) throw std::runtime_error(form.name + ": verdict: " + v.reason);
      w_lin += study::seconds_since(tl);
      wall_linear += study::seconds_since(tl);
      ++classes[v.letter()];
      const bool lin_unstable = cls.growth_rate > detect;
      const bool map_unstable = v.map_growth > detect;  // what the run at this dt amplifies
      const bool measured_unstable = fit.grew;
      const double ratio = fit.grew && lin_unstable ? fit.gamma / cls.growth_rate : NAN;
      ++cases;
      agree += map_unstable == measured_unstable;
      cells[form.name][xi] = {v.letter(), v.semi_discrete_growth, v.map_growth, fit.gamma, fit.grew};
      if (map_unstable != measured_unstable)
        disagreements += "- `" + form.name + "`, ξ = " + study::sig(xi) + ": " + v.letter() + ", γ_J " +
                         study::sig(v.semi_discrete_growth, 3) + ", γ_M " + study::sig(v.map_growth, 3) + " /µs; run " +
                         (fit.grew ? "grew at " + study::sig(fit.gamma, 3) + " /µs" : "stayed below the window") + "\n";
      if (std::isfinite(ratio)) {
        ++comparable;
        ratio_min = std::min(ratio_min, ratio);
        ratio_max = std::max(ratio_max, ratio);
        if (form.options.viscosity == ViscositySwitch::Off) {  // smooth terms: the linear theory applies
          smooth_min = std::min(smooth_min, ratio);
          smooth_max = std::max(smooth_max, ratio);
        }
      }
      runs_csv << csv_line({form.name,
                            format_number(xi),
                            format_number(rho, 8),
                            format_number(steel.bulk_modulus * (rho / steel.density - 1), 8),
                            format_number(cls.growth_rate, 8),
                            format_number(std::abs(cls.lambda.imag()), 8),
                            format_number(all.growth_rate, 8),
                            format_number(v.map_growth, 8),
                            format_number(cls.invariance_residual, 3),
                            format_number(all.structure_residual, 3),
                            format_number(eq_res / kick_acc, 3),
                            format_number(fit.gamma, 8),
                            fit.grew ? "1" : "0",
                            format_number(fit.fit.t_begin, 6),
                            format_number(fit.fit.t_end, 6),
                            format_number(fit.fit.r2, 8),
                            format_number(ratio, 6),
                            v.letter(),
                            format_number(detect, 6),
                            format_number(v.integrator_excess, 6),
                            map_unstable ? "1" : "0",
                            run_status_name(run.status),
                            std::to_string(run.steps),
                            format_number(run.time, 6),
                            format_number(ke_max, 6),
                            format_number(w_lin, 3),
                            format_number(w_run, 3),
                            std::to_string(form.layer_supports),
                            std::to_string(fdisc->size())});
      // Class, then gamma_J / gamma_M, then the run's measured rate (or "-" when it stayed below the window).
      const std::string letter = v.verdict == VerdictClass::Stable ? "S" : "**" + v.letter() + "**";
      row.push_back(letter + " " + study::sig(std::max(v.semi_discrete_growth, 0.0), 2) + " / " +
                    study::sig(std::max(v.map_growth, 0.0), 2) + " · " + (fit.grew ? study::sig(fit.gamma, 2) : "–"));
      std::printf("%-9s xi %.2f: %s (J %.4g, map %.4g), all classes %.4g, measured %.4g (%s), ratio %.3f, %s "
                  "(%.1f + %.1f s)\n",
                  form.name.c_str(), xi, v.letter().c_str(), cls.growth_rate, v.map_growth, all.growth_rate, fit.gamma,
                  fit.grew ? "grew" : "bounded", ratio, run.message.c_str(), w_lin, w_run);
      std::fflush(stdout);
      study::md_row(ratios_table, {form.name, study::fixed(xi, 2), study::sig(cls.growth_rate, 4),
                                   study::sig(all.growth_rate, 4), study::sig(fit.gamma, 4), study::fixed(ratio, 3)});
    }
    study::md_row(table, row);
  }

  // Is the growth at xi = 1 (linearly neutral) made by the time integrator? Measured gamma versus dt, GMS positions
  // and corrected (trapezoid) positions, against the one-step map's rate: an integrator-made growth falls as dt^3.
  std::ofstream dt_csv(out + "/dt_study.csv");
  dt_csv << "formulation,xi,positions,dt,t_end,gamma_measured,gamma_map_class,verdict,grew\n";
  std::string dt_table;
  std::map<std::string, double> dt_ratio;  // measured / map at the study's dt, per position update
  for (double scale : {1.0, 0.5}) {  // the same t_end: at dt/2 the map grows 8x slower
    const RateFormScheme<2> scheme(disc, steel, {}, so.density);
    Eigen::VectorXd y = scheme.uniform_state();
    scheme.set_velocity(y, scene.centre, scene.v0.segment<2>(2 * disc->free_slot[scene.centre]));
    for (PositionUpdate pu : {PositionUpdate::Gms, PositionUpdate::Trapezoid}) {
      const RateFormRunResult run = run_rate_form(
          scheme, y,
          {.dt = scale * dt, .positions = pu, .t_end = t_end, .record_every = 10, .energy_growth = stop_growth});
      const ExponentialGrowthFit fit = fit_exponential_growth(run.times, run.kinetic_energy, run.kinetic_energy.front(),
                                                              run.times.back(), {.onset_factor = onset});
      // The exact one-step map of this position update (stability_verdict's reduced route), in the excited class.
      const StabilityVerdict mv = stability_verdict(scheme, scheme.uniform_state(), {.dt = run.dt, .positions = pu},
                                                    {.floor = detect, .basis = excited});
      const double map = mv.map_growth;
      if (scale == 1.0) dt_ratio[pu == PositionUpdate::Gms ? "gms" : "trapezoid"] = fit.grew ? fit.gamma / map : NAN;
      const std::string name = pu == PositionUpdate::Gms ? "gms" : "trapezoid";
      dt_csv << csv_line({"sph", "1", name, format_number(run.dt, 8), format_number(t_end, 6),
                          format_number(fit.gamma, 8), format_number(map, 8), mv.letter(), fit.grew ? "1" : "0"});
      study::md_row(dt_table, {name, study::sig(run.dt, 4), fit.grew ? study::sig(fit.gamma, 4) : "– (below the window)",
                               study::sig(map, 4), mv.letter()});
      std::printf("dt study: %s dt %.4g: measured %.4g, map %.4g (%s)\n", name.c_str(), run.dt, fit.gamma, map,
                  mv.letter().c_str());
    }
  }

  study::Summary s;
  s.set("dt_table", dt_table);
  s.set("dt_ratio_gms", dt_ratio["gms"], 3);
  s.set("dt_ratio_trapezoid", dt_ratio["trapezoid"], 3);
  s.set("n", n);
  s.set("particles", disc->size());
  s.set("states", RateFormScheme<2>(disc, steel).size());
  s.set("reduced", 2 * disc->free_count());
  s.set("class_size", static_cast<int>(excited.cols()));
  s.set("bulk_modulus", steel.bulk_modulus, 4);
  s.set("shear_modulus", steel.shear_modulus, 4);
  s.set("c_P", cp, 4);
  s.set("dt", dt, 4);
  s.set("t_end", t_end, 4);
  s.set("onset", onset, 3);
  s.set("stop_growth", stop_growth, 3);
  s.set("detect", detect, 3);
  s.set("xi_list", "0.96, 0.98, 0.99, 1, 1.01, 1.02, 1.04");
  s.set("stability_table", table);
  s.set("ratios_table", ratios_table);
  s.set("cases", cases);
  s.set("disagreements", disagreements.empty() ? "- none" : disagreements);
  // Per formulation, the class at each xi of one side of 1 (the rows of the statement table below).
  const auto classes_of = [&](const std::string& name, int side) {
    std::string t;
    for (const auto& [xi, c] : cells.at(name))
      if ((side > 0 && xi > 1) || (side < 0 && xi < 1))
        t += (t.empty() ? "" : ", ") + study::sig(xi) + " " + c.letter;
      else if (side == 0 && xi == 1)
        t = c.letter;
    return t;
  };
  for (const char* name : {"sph", "ncsph", "ncsph-xsph", "ncsph-anti", "cij", "ssph", "ssph-printed", "sph-xsph"}) {
    s.set(std::string("tension_") + name, classes_of(name, 1));
    s.set(std::string("compression_") + name, classes_of(name, -1));
  }
  for (const char* name : {"sph", "ncsph", "cij", "ssph", "sph-as", "sph-all"})
    s.set(std::string("neutral_") + name, classes_of(name, 0));
  // "lo–hi" at 2 significant digits, one value when both round alike, "–" for none.
  const auto range = [](double lo, double hi) {
    if (lo > hi) return std::string("–");
    return study::sig(lo, 2) == study::sig(hi, 2) ? study::sig(lo, 2) : study::sig(lo, 2) + "–" + study::sig(hi, 2);
  };
  // The ratio of basic SPH's rate to the formulation's over the xi where both grow on one side of 1: gamma_J of
  // both (linear), or the runs' measured rates (for the viscosity, whose switch the linearisation takes as off).
  const auto cut = [&](const std::string& name, int side, bool measured) {
    double lo = 1e300, hi = -1e300;
    for (const auto& [xi, c] : cells.at(name)) {
      const Cell& b = cells.at("sph").at(xi);
      if ((side > 0) != (xi > 1) || xi == 1) continue;
      const bool both = measured ? c.grew && b.grew : c.gamma_j > detect && b.gamma_j > detect;
      if (!both) continue;
      const double r = measured ? b.measured / c.measured : b.gamma_j / c.gamma_j;
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
    return range(lo, hi);
  };
  s.set("ssph_tension_cut", cut("ssph", 1, false));
  s.set("xsph_tension_cut", cut("sph-xsph", 1, false));
  s.set("xsph_compression_cut", cut("sph-xsph", -1, false));
  s.set("visc_compression_cut", cut("sph-visc", -1, true));
  double map_lo = 1e300, map_hi = -1e300;  // the integrator's rate where it alone grows
  for (const auto& [name, row] : cells)
    for (const auto& [xi, c] : row)
      if (c.letter == "I") map_lo = std::min(map_lo, c.gamma_m), map_hi = std::max(map_hi, c.gamma_m);
  s.set("integrator_rate_range", range(map_lo, map_hi));
  for (const char* c : {"S", "U", "I", "B"}) s.set(std::string("class_") + c, classes[c]);
  s.set("agree", agree);
  s.set("comparable", comparable);
  s.set("ratio_min", comparable ? ratio_min : NAN, 3);
  s.set("ratio_max", comparable ? ratio_max : NAN, 3);
  s.set("smooth_ratio_min", smooth_min, 3);
  s.set("smooth_ratio_max", smooth_max, 3);
  s.set("equilibrium_residual", eq_res_max, 2);
  s.set("wall_linear", wall_linear, 3);
  s.set("wall_runs", wall_runs, 3);
  s.set("wall_total", study::seconds_since(t0), 3);
  s.write(out);
  std::printf("linear and measured verdicts agree in %d of %d runs; ratio measured/linear %.3f..%.3f over %d\n", agree,
              cases, ratio_min, ratio_max, comparable);
  return 0;
}
