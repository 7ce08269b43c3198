#pragma once
// The options of the rate-form scheme (forms/rate_form.hpp) shared by `sphstab spectrum` and `sphstab run`: the
// lattice, the kernel, the material and the switchable terms, registered on a subcommand as text and converted by
// strict parsing (parse.hpp) into a RateFormSetup. One definition of every option, its help text and its checks, so
// that the two commands cannot drift apart.
#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/rate_form_block.hpp"

namespace sphstab::cli {

/// The options as typed (parsed by parse_rate_form_args). A command sets its own defaults before registering them
/// (the help text quotes the values found here).
struct RateFormArgs {
  std::string dim = "2", lattice, n = "12", kernel = "cubic", h = "1.3", xi = "1.02", youngs = "2.1", poisson = "0.3",
              density = "7.8", dx = "0.01", xsph = "0", viscosity = "off", alpha = "0.06", beta = "1.5",
              artificial_stress = "0", continuity = "summation", gradient = "plain", momentum = "symmetric",
              switch_rule = "tension", counting = "actual", pair_loop = "auto", bulk_viscosity = "0,0";
  bool periodic = false;
  bool first_step_shepard = false;  ///< --first-step-shepard: the means of Powell's (4.18) in S-SPH
  /// Whether an option was typed (set by add_rate_form_options): an option that does nothing in the combination
  /// given is refused by parse_rate_form_args.
  std::function<bool(const std::string&)> given;
};

/// Registers --dim, --lattice, --n, --periodic, --kernel, --h, --xi, --dx, --youngs, --poisson, --density,
/// --continuity, --xsph, --viscosity, --alpha, --beta, --bulk-viscosity, --artificial-stress, --gradient, --momentum,
/// --switch-rule,
/// --counting and --pair-loop on `cmd`, bound to `a` (which must outlive the parse). `lists`: --kernel, --h and --xi
/// accept comma lists (a sweep) rather than one value.
void add_rate_form_options(CLI::App& cmd, RateFormArgs& a, bool lists);

/// The parsed options. kernels, h_over_dx and xi hold one entry each unless the command accepts lists.
struct RateFormSetup {
  int dim = 2;
  LatticeType lattice = LatticeType::Square;
  int n = 0;  ///< free particles per side
  bool periodic = false;
  std::vector<KernelType> kernels;
  std::vector<double> h_over_dx, xi;
  double dx = 0;
  ElasticMaterial material = ElasticMaterial::from_bulk_shear(1.0, 0.0, 1.0);
  RateFormOptions options;
};

/// Parses and checks `a`; every error is a one-line std::invalid_argument prefixed "<command>: --option" (or the
/// library's own message for an unknown name or a material outside its range). --n must lie in [min_n, max_n_1d] in
/// 1D and [min_n, max_n_2d] in 2D. With lists = false, a comma list in --kernel, --h or --xi is an error.
RateFormSetup parse_rate_form_args(const RateFormArgs& a, const std::string& command, bool lists, long min_n,
                                   long max_n_1d, long max_n_2d);

/// The block of problems/rate_form_block.hpp with `setup`'s lattice, spacing, material and terms, this kernel, h/dx
/// and volume strain, and the kick V0 (the library builds the lattice, the scheme and the kick).
RateFormBlockOptions block_options(const RateFormSetup& setup, KernelType kernel, double h_over_dx, double xi = 1.0,
                                   double kick = 0.0);

/// The size of `setup`'s block before it is built, for the memory estimates of run and jacobian: the free particles
/// (n^dim), all particles (with the fixed layers of rate_form_layer_supports), and the particles within `radius` kernel
/// supports of one particle (1 + 2 r in 1D, 1 + pi r^2 in 2D, r = radius x 2 h / dx; 2 h the cubic spline's support).
struct BlockSize {
  double free = 0, particles = 0;
  double within(const RateFormSetup& setup, double radius) const;
};
BlockSize block_size(const RateFormSetup& setup);

/// Particle-steps above which a run is refused before it starts: 1e11, about a day at the scheme's ~1 µs per
/// particle-step on one core (results/gms-speed), so a --t-end or --dt that cannot finish is an error, not a hang.
inline constexpr double kMaxParticleSteps = 1e11;

/// Refuses (one-line std::invalid_argument prefixed `who`) a run of ceil(t_end / dt) steps over `particles` particles
/// beyond kMaxParticleSteps, naming the step count and the work; t_end and dt are finite and > 0.
void require_run_length(double t_end, double dt, long particles, const std::string& who);

/// The verdict options as typed; all empty: no verdict columns.
struct VerdictArgs {
  std::string integrator, dt, t_end, energy_ratio;
};

/// The run a verdict is for: the integrator at the run's dt (reduced to t_end / ceil(t_end / dt) as `sphstab run`
/// does) and the floor ln(energy_ratio) / (2 t_end).
struct VerdictSetup {
  bool on = false;
  RateFormRunOptions run;
  double floor = 0;
};

/// Registers --integrator, --dt, --t-end and --energy-ratio (the run a verdict is for) on `cmd`, bound to `a`.
void add_verdict_options(CLI::App& cmd, VerdictArgs& a);

/// Parses `a` (errors prefixed "<command>: "): empty when no option was given; --integrator needs --dt and --t-end.
VerdictSetup parse_verdict_args(const VerdictArgs& a, const std::string& command);

}  // namespace sphstab::cli
