#include "rate_form_args.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "parse.hpp"
#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/forms/stabilised_sph.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/operators/local_polish.hpp"

namespace sphstab::cli {

namespace {

/// The items of a value-or-list option; with lists = false exactly one.
std::vector<std::string> items(const std::string& text, bool lists, const std::string& what) {
  std::vector<std::string> out = split_list(text, ',', what);
  if (!lists && out.size() != 1)
    throw std::invalid_argument(what + " takes one value here (got '" + text + "'; `sphstab spectrum` sweeps lists)");
  return out;
}

}  // namespace

void add_rate_form_options(CLI::App& cmd, RateFormArgs& a, bool lists) {
  a.given = [&cmd](const std::string& option) { return cmd.count(option) > 0; };
  const std::string list = lists ? " or comma list" : "", value_list = lists ? ", value or comma list" : "";
  cmd.add_option("--dim", a.dim, "1 or 2 (default " + a.dim + ")");
  cmd.add_option("--lattice", a.lattice, "line (1D); square, hex, face-centred (2D; default square)");
  cmd.add_option("--n", a.n, "free particles per side (default " + a.n + "; fixed layers added unless --periodic)");
  cmd.add_flag("--periodic", a.periodic, "periodic lattice (no fixed layers)");
  cmd.add_option("--kernel", a.kernel, "kernel name" + list + " (default " + a.kernel + ")");
  cmd.add_option("--h", a.h, "h/dx" + value_list + " (default " + a.h + ")");
  cmd.add_option("--xi", a.xi, "volume strain V/V0 > 0" + value_list + " (default " + a.xi + "; > 1 tension)");
  cmd.add_option("--dx", a.dx, "lattice spacing (default " + a.dx + ")");
  cmd.add_option("--youngs", a.youngs, "Young's modulus E > 0 (default " + a.youngs + ", Mbar)");
  cmd.add_option("--poisson", a.poisson, "Poisson's ratio in (-1, 1/2) (default " + a.poisson + ")");
  cmd.add_option("--density", a.density, "rho0 > 0 at zero pressure (default " + a.density + ")");
  cmd.add_option("--continuity", a.continuity, "summation (GMS 3.8) | divergence (-rho tr L)");
  cmd.add_option("--xsph", a.xsph, "XSPH epsilon (GMS 3.6), >= 0 (default " + a.xsph + ")");
  cmd.add_option("--viscosity", a.viscosity, "off | compression | always");
  cmd.add_option("--alpha", a.alpha, "viscosity alpha (default " + a.alpha + ")");
  cmd.add_option("--beta", a.beta, "viscosity beta (default " + a.beta + ")");
  cmd.add_option("--bulk-viscosity", a.bulk_viscosity,
                 "Q1,Q2: MCM's bulk viscosity q = rho h (Q1 h d^2 - Q2 c0 d) where the velocity divergence d < 0 (the "
                 "MCM deck's QBVC,LBVC: 1.5,0.06), both >= 0 (default " +
                     a.bulk_viscosity + ": off)");
  cmd.add_option("--artificial-stress", a.artificial_stress,
                 "GMS artificial stress epsilon, >= 0 (default " + a.artificial_stress + ")");
  cmd.add_option(
      "--gradient", a.gradient,
      "kernel gradient of L, continuity and momentum: plain | ncsph (Powell 1.19) (default " + a.gradient + ")");
  cmd.add_option("--momentum", a.momentum,
                 "momentum equation: symmetric (Powell 1.36) | antisymmetric | cij (4.10) | ssph (S-SPH, algorithm "
                 "4.2) (default " +
                     a.momentum +
                     "; fixed layers: 2 supports for ncsph, antisymmetric, cij, 3 for ssph, 4 with "
                     "--first-step-shepard)");
  cmd.add_option("--switch-rule", a.switch_rule,
                 "S-SPH switch: tension (4.15-4.17) | as-printed | always | never (default " + a.switch_rule + ")");
  cmd.add_flag(
      "--first-step-shepard", a.first_step_shepard,
      "S-SPH: the means of algorithm 4.1 of the first-step Shepard gradient, Powell (4.18) (MCM's; default off)");
  cmd.add_option("--counting", a.counting,
                 "n_i of the cij/ssph means: actual | boundary-level (Powell Fig. 4.3) (default " + a.counting + ")");
  cmd.add_option("--pair-loop", a.pair_loop,
                 "auto (pairs where they apply, else rows) | rows (every pair from both sides) | pairs (each pair "
                 "once, rates equal to rows' to rounding, about twice as fast: results/gms-speed; plain gradient, "
                 "symmetric or antisymmetric momentum); both the same bits on any thread count (default " +
                     a.pair_loop + ")");
}

namespace {

/// An option typed where it does nothing is a mistake, not a no-op (issue 36).
void refuse_if_idle(const RateFormArgs& a, const std::string& c, const char* option, bool applies,
                    const std::string& why) {
  if (!applies && a.given && a.given(option)) throw std::invalid_argument(c + option + " has no effect " + why);
}

}  // namespace

RateFormSetup parse_rate_form_args(const RateFormArgs& a, const std::string& command, bool lists, long min_n,
                                   long max_n_1d, long max_n_2d) {
  const std::string c = command + ": ";
  RateFormSetup s;
  s.dim = static_cast<int>(parse_integer(a.dim, 1, 2, c + "--dim"));
  s.lattice = parse_lattice_type(a.lattice.empty() ? (s.dim == 1 ? "line" : "square") : a.lattice);
  if ((s.dim == 1) != (s.lattice == LatticeType::Line) || s.lattice == LatticeType::Cubic)
    throw std::invalid_argument(c + "--lattice " + lattice_name(s.lattice) + " does not exist in " +
                                std::to_string(s.dim) + "D (1D: line; 2D: square, hex, face-centred)");
  s.n = static_cast<int>(parse_integer(a.n, min_n, s.dim == 1 ? max_n_1d : max_n_2d, c + "--n"));
  s.periodic = a.periodic;
  for (const auto& k : items(a.kernel, lists, c + "--kernel")) s.kernels.push_back(parse_kernel_type(k));
  for (const auto& v : items(a.h, lists, c + "--h")) s.h_over_dx.push_back(parse_double(v, c + "--h"));
  for (const auto& v : items(a.xi, lists, c + "--xi")) s.xi.push_back(parse_double(v, c + "--xi"));
  s.dx = parse_double(a.dx, c + "--dx");
  check_length(s.dx, c + "--dx");
  for (double h : s.h_over_dx) check_length(h * s.dx, c + "--h x --dx");
  for (double xi : s.xi)
    if (!(xi > 0)) throw std::invalid_argument(c + "--xi must be > 0 (got " + format_number(xi, 10) + ")");
  s.material = ElasticMaterial::from_young_poisson(parse_double(a.youngs, c + "--youngs"),
                                                   parse_double(a.poisson, c + "--poisson"),
                                                   parse_double(a.density, c + "--density"));
  RateFormOptions& o = s.options;
  o.continuity = parse_continuity_form(a.continuity);
  o.xsph = parse_double(a.xsph, c + "--xsph");
  o.viscosity = parse_viscosity_switch(a.viscosity);
  o.viscosity_alpha = parse_double(a.alpha, c + "--alpha");
  o.viscosity_beta = parse_double(a.beta, c + "--beta");
  const std::vector<std::string> bulk = split_list(a.bulk_viscosity, ',', c + "--bulk-viscosity");
  if (bulk.size() != 2)
    throw std::invalid_argument(c + "--bulk-viscosity takes two values Q1,Q2 (got '" + a.bulk_viscosity + "')");
  o.bulk_viscosity_quadratic = parse_double(bulk[0], c + "--bulk-viscosity Q1");
  o.bulk_viscosity_linear = parse_double(bulk[1], c + "--bulk-viscosity Q2");
  if (!(o.bulk_viscosity_quadratic >= 0) || !(o.bulk_viscosity_linear >= 0))
    throw std::invalid_argument(c + "--bulk-viscosity: Q1 and Q2 must be >= 0 (got '" + a.bulk_viscosity + "')");
  o.artificial_stress = parse_double(a.artificial_stress, c + "--artificial-stress");
  o.gradient = parse_rate_form_gradient(a.gradient);
  o.momentum = parse_rate_form_momentum(a.momentum);
  o.switch_rule = parse_switch_rule(a.switch_rule);
  o.counting = parse_neighbour_counting(a.counting);
  const bool viscous = o.viscosity != ViscositySwitch::Off;
  refuse_if_idle(a, c, "--alpha", viscous, "with --viscosity off");
  refuse_if_idle(a, c, "--beta", viscous, "with --viscosity off");
  refuse_if_idle(a, c, "--switch-rule", o.momentum == RateFormMomentum::StabilisedSph, "without --momentum ssph");
  o.first_step_shepard = a.first_step_shepard;
  refuse_if_idle(a, c, "--first-step-shepard", o.momentum == RateFormMomentum::StabilisedSph,
                 "without --momentum ssph");
  refuse_if_idle(a, c, "--counting",
                 o.momentum == RateFormMomentum::Cij || o.momentum == RateFormMomentum::StabilisedSph,
                 "without --momentum cij or ssph");
  const bool pairs_apply = o.gradient == RateFormGradient::Plain &&
                           (o.momentum == RateFormMomentum::Symmetric || o.momentum == RateFormMomentum::Antisymmetric);
  // auto: the fastest loop that applies (issue 35: the pair loop agrees with the row loop to rounding).
  o.pair_loop = a.pair_loop == "auto" ? (pairs_apply ? PairLoop::Pairs : PairLoop::Rows) : parse_pair_loop(a.pair_loop);
  if (o.pair_loop == PairLoop::Pairs && !pairs_apply)
    throw std::invalid_argument(c +
                                "--pair-loop pairs needs --gradient plain and --momentum symmetric or antisymmetric");
  return s;
}

RateFormBlockOptions block_options(const RateFormSetup& s, KernelType kernel, double h_over_dx, double xi,
                                   double kick) {
  return {.lattice = s.lattice,
          .n = s.n,
          .periodic = s.periodic,
          .kernel = kernel,
          .h_over_dx = h_over_dx,
          .spacing = s.dx,
          .xi = xi,
          .material = s.material,
          .scheme = s.options,
          .kick = kick};
}

void require_run_length(double t_end, double dt, long particles, const std::string& who) {
  const double steps = std::ceil(t_end / dt - 1e-9);
  const double work = steps * static_cast<double>(particles);
  if (!(work <= kMaxParticleSteps))
    throw std::invalid_argument(who + ": t_end / dt = " + format_number(steps, 3) + " steps of " +
                                std::to_string(particles) + " particles (" + format_number(work, 3) +
                                " particle-steps, more than " + format_number(kMaxParticleSteps, 3) +
                                ", about a day at 1 us each); shorten --t-end or raise the time step");
}

namespace {

double positive(const std::string& text, const std::string& what) {
  const double v = parse_double(text, what);
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(what + " must be finite and > 0 (got " + text + ")");
  return v;
}

}  // namespace

VerdictSetup parse_verdict_args(const VerdictArgs& a, const std::string& command) {
  const std::string c = command + ": ";
  VerdictSetup v;
  if (a.integrator.empty()) {
    if (!a.dt.empty() || !a.t_end.empty() || !a.energy_ratio.empty())
      throw std::invalid_argument(c + "--dt, --t-end and --energy-ratio belong to a verdict: give --integrator");
    return v;
  }
  v.on = true;
  select_rate_form_integrator(v.run, a.integrator);
  if (a.dt.empty() || a.t_end.empty())
    throw std::invalid_argument(c + "--integrator needs --dt and --t-end (the verdict is for that run)");
  const double dt = positive(a.dt, c + "--dt"), t_end = positive(a.t_end, c + "--t-end");
  const long steps =
      std::max(1L, checked_floor_count(std::ceil(t_end / dt - 1e-9), 1L << 53, c + "steps --t-end / --dt"));
  v.run.dt = t_end / static_cast<double>(steps);
  v.run.t_end = t_end;
  const double ratio = a.energy_ratio.empty() ? 100.0 : parse_double(a.energy_ratio, c + "--energy-ratio");
  if (!(ratio > 1) || !std::isfinite(ratio))
    throw std::invalid_argument(c + "--energy-ratio must be finite and > 1 (got " + a.energy_ratio + ")");
  v.floor = detection_floor(t_end, ratio);
  return v;
}

void add_verdict_options(CLI::App& cmd, VerdictArgs& a) {
  cmd.add_option("--integrator", a.integrator,
                 "pc | pc1 | leapfrog: add the stability verdict of a run with this integrator (needs --dt and "
                 "--t-end): map_growth = ln rho(M) / dt of the one-step map, floor = ln(--energy-ratio) / (2 t_end), "
                 "verdict S | U | I | B (growth/stability_verdict.hpp; at rest with pc or a viscosity-free leapfrog "
                 "reduced exactly, otherwise dense in the whole state)");
  cmd.add_option("--dt", a.dt, "the verdict's time step > 0 (reduced to t_end / ceil(t_end / dt) as in `run`)");
  cmd.add_option("--t-end", a.t_end, "the verdict's run length > 0");
  cmd.add_option("--energy-ratio", a.energy_ratio,
                 "kinetic-energy growth the run detects, > 1 (default 100): the floor is ln(ratio) / (2 t_end)");
}

BlockSize block_size(const RateFormSetup& s) {
  const double support = 2 * s.h_over_dx.front();  // in dx
  const double layers =
      s.periodic ? 0 : fixed_layers_needed(rate_form_layer_supports(s.options) * support * s.dx, s.dx);
  return {.free = std::pow(double(s.n), s.dim), .particles = std::pow(s.n + 2 * layers, s.dim)};
}

double BlockSize::within(const RateFormSetup& s, double radius) const {
  const double r = radius * 2 * s.h_over_dx.front();
  return s.dim == 1 ? 1 + 2 * r : 1 + M_PI * r * r;
}

}  // namespace sphstab::cli
