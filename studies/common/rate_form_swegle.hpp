#pragma once
/// \file rate_form_swegle.hpp
/// The Swegle test with the rate-form scheme [Powell2012, ch. 4 §2.2], shared by the study drivers
/// studies/swegle-rate-form (which formulations grow, and does the linearisation say so), studies/swegle-nonlinear
/// (is that growth linear, amplitude-dependent or the integrator's) and studies/swegle-powell (Powell's own MCM
/// configuration, which takes the block, its residual and the growth fit from here):
/// - the options of a run (--out, --n, --t-end, --quick) and the constants of its measurement (fit onset, stop);
/// - the formulations: the terms of the scheme practitioners switch on, one at a time and together;
/// - the block with the mirror class (px, py) = (-1, +1) of its free velocity DOFs, where the kick (+x at the centre)
///   lies, the steel of the scene and the time step 0.3 h / c_P;
/// - the block's residual of equilibrium, the kinetic-energy growth of a run and the verdict at rest;
/// - the summary's numbers of the setup.
#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/growth/growth_fit.hpp"
#include "sphstab/growth/mirror_symmetry.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/problems/swegle.hpp"

namespace sphstab::study::rate_form_swegle {

/// Options of a run (CLI) and the constants of its measurement.
struct Options {
  std::string out;
  int n = 21;                 ///< free particles per side (odd)
  double t_end = 45;          ///< run length (us)
  bool quick = false;         ///< the study's quick case
  double onset = 100;         ///< the growth fit's window opens at onset x KE0
  double stop_growth = 1e10;  ///< a run stops at stop_growth x KE0
};

/// The quick case's block and run length, and what it runs (the help text of --quick).
struct QuickCase {
  int n = 9;
  double t_end = 10;
  std::string text;
};

/// Reads --out, --n, --t-end and --quick into `o` and creates o.out; with --quick, takes the quick case's n and at
/// most its t_end. Returns the exit code of `app` after --help or a command-line error (as CLI11_PARSE), else none.
inline std::optional<int> parse_options(CLI::App& app, Options& o, const QuickCase& quick, int argc, char** argv) {
  app.add_option("--out", o.out, "output directory");
  app.add_option("--n", o.n, "free particles per side (odd)")->check(CLI::Range(5, 101));
  app.add_option("--t-end", o.t_end, "run length (us)")->check(CLI::PositiveNumber);
  app.add_flag("--quick", o.quick, quick.text);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  std::filesystem::create_directories(o.out);
  if (o.quick) o.n = quick.n, o.t_end = std::min(o.t_end, quick.t_end);
  return std::nullopt;
}

struct Formulation {
  std::string name, label;
  RateFormOptions options;
  int layer_supports = 1;  // fixed layers (in supports) the formulation needs for an exact equilibrium
};

/// The terms of the scheme practitioners switch on, one at a time and together (MCM deck viscosity 0.06 / 1.5;
/// GMS XSPH 1/2 and artificial stress 0.3, n = 4).
inline std::vector<Formulation> formulations() {
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

/// The formulations of formulations() whose names are in `names`, in the table's order.
inline std::vector<Formulation> formulations(const std::vector<std::string>& names) {
  std::vector<Formulation> chosen;
  for (const Formulation& f : formulations())
    if (std::find(names.begin(), names.end(), f.name) != names.end()) chosen.push_back(f);
  return chosen;
}

/// A Swegle block and the mirror class (px, py) = (-1, +1) of its free velocity DOFs: the one a +x kick at the
/// centre excites.
struct Block {
  SwegleScene scene;
  Eigen::MatrixXd excited;
};

inline Block make_block(const SwegleOptions& so) {
  Block b{make_swegle_scene(so), {}};
  const auto& d = b.scene.discretisation;
  const Eigen::Vector2d centre = d->particles.x.row(b.scene.centre).transpose();
  b.excited = symmetry_basis(mirror_symmetry(b.scene.free_positions(), centre, 1e-9 * so.spacing), -1, 1);
  return b;
}

/// The scene's elastic material as the rate form's (E, nu, rho).
inline ElasticMaterial steel(const SwegleOptions& so) {
  return ElasticMaterial::from_young_poisson(so.youngs_modulus, so.poisson_ratio, so.density);
}

/// The runs' step, 0.3 h / c_P.
inline double time_step(const SwegleScene& scene, const ElasticMaterial& m) { return 0.3 * scene.h / m.p_wave_speed(); }

/// The scene's kick: the initial velocity of the centre particle.
inline Eigen::Vector2d kick(const SwegleScene& scene) {
  return scene.v0.segment<2>(2 * scene.discretisation->free_slot[scene.centre]);
}

/// The unkicked block's largest free acceleration against the accelerations the kick produces, v0 c_P / h (the kick
/// changes only the rates of x, rho and S at first, so its own immediate change of the accelerations is 0 at rest):
/// the run measures growth from the kick only if the block starts in equilibrium.
inline double equilibrium_residual(const RateFormScheme<2>& scheme, const SwegleScene& scene,
                                   const ElasticMaterial& m) {
  const auto& d = scene.discretisation;
  Eigen::VectorXd f;
  scheme.rate(scheme.uniform_state(), f);
  double res = 0;
  for (int i = 0; i < d->size(); ++i)
    if (scheme.velocity_offset(i) >= 0)
      res = std::max(res, f.segment<2>(scheme.velocity_offset(i)).cwiseAbs().maxCoeff());
  return res / (kick(scene).norm() * m.p_wave_speed() / d->h);
}

/// The fitted exponential growth of a run's kinetic energy over [0, t_fit_end], window from onset x KE0.
inline ExponentialGrowthFit fit_growth(const RateFormRunResult& run, double t_fit_end, double onset) {
  return fit_exponential_growth(run.times, run.kinetic_energy, run.kinetic_energy.front(), t_fit_end,
                                {.onset_factor = onset});
}

/// max KE / KE0 of a run.
inline double ke_max_over_ke0(const RateFormRunResult& run) {
  double ke_max = 0;
  for (double e : run.kinetic_energy) ke_max = std::max(ke_max, e / run.kinetic_energy.front());
  return ke_max;
}

/// The verdict at rest of `scheme` with the integrator and dt of `run`, in `basis`, against `floor`. Throws
/// std::runtime_error(who + "verdict: " + reason) unless it succeeded.
inline StabilityVerdict checked_verdict(const RateFormScheme<2>& scheme, const RateFormRunOptions& run, double floor,
                                        const Eigen::MatrixXd& basis, const std::string& who = "") {
  const StabilityVerdict v = stability_verdict(scheme, scheme.uniform_state(), run, {.floor = floor, .basis = basis});
  if (v.status != Status::Successful) throw std::runtime_error(who + "verdict: " + v.reason);
  return v;
}

/// The summary's numbers of the setup: n, particles, c_P, dt, t_end, onset, stop_growth.
inline void summarise_setup(Summary& s, const Options& o, const SwegleScene& scene, const ElasticMaterial& m,
                            double dt) {
  s.set("n", o.n);
  s.set("particles", scene.discretisation->size());
  s.set("c_P", m.p_wave_speed(), 4);
  s.set("dt", dt, 4);
  s.set("t_end", o.t_end, 4);
  s.set("onset", o.onset, 3);
  s.set("stop_growth", o.stop_growth, 3);
}

/// The summary's wall times (s): linear analyses, runs and the whole study since t0.
inline void summarise_walls(Summary& s, double linear, double runs, Clock::time_point t0) {
  s.set("wall_linear", linear, 3);
  s.set("wall_runs", runs, 3);
  s.set("wall_total", seconds_since(t0), 3);
}

}  // namespace sphstab::study::rate_form_swegle
