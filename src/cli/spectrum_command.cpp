// `sphstab spectrum`: the full-state spectrum of the rate-form scheme (forms/rate_form.hpp) on a lattice at a uniform
// volume strain xi: growth rate max Re lambda(J), the dominant wavevector of the unstable mode, the equilibrium
// residual, as CSV (growth/rate_form_spectrum.hpp: complex-step J, exact at-rest reduction). The scheme's options are
// rate_form_args.hpp's, shared with `sphstab run`. With --integrator, --dt and --t-end each row also carries the
// stability verdict of that run (growth/stability_verdict.hpp): the one-step map's growth, the run's detection floor,
// the class S/U/I/B.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "rate_form_args.hpp"
#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/particles/bravais_lattice.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"

namespace sphstab::cli {

namespace {

std::string num(double v) { return format_number(v, 10); }

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

double positive(const std::string& text, const std::string& what) {
  const double v = parse_double(text, what);
  if (!(v > 0) || !std::isfinite(v)) throw std::invalid_argument(what + " must be finite and > 0 (got " + text + ")");
  return v;
}

VerdictSetup parse_verdict_args(const VerdictArgs& a) {
  VerdictSetup v;
  if (a.integrator.empty()) {
    if (!a.dt.empty() || !a.t_end.empty() || !a.energy_ratio.empty())
      throw std::invalid_argument("spectrum: --dt, --t-end and --energy-ratio belong to a verdict: give --integrator");
    return v;
  }
  v.on = true;
  if (a.integrator == "pc1")
    v.run.reuse_corrector_rate = true;
  else if (a.integrator == "leapfrog")
    v.run.integrator = RateFormIntegrator::Leapfrog;
  else if (a.integrator != "pc")
    throw std::invalid_argument("spectrum: unknown --integrator '" + a.integrator + "' (valid: pc, pc1, leapfrog)");
  if (a.dt.empty() || a.t_end.empty())
    throw std::invalid_argument("spectrum: --integrator needs --dt and --t-end (the verdict is for that run)");
  const double dt = positive(a.dt, "spectrum: --dt"), t_end = positive(a.t_end, "spectrum: --t-end");
  const long steps =
      std::max(1L, checked_floor_count(std::ceil(t_end / dt - 1e-9), 1L << 53, "spectrum: steps --t-end / --dt"));
  v.run.dt = t_end / static_cast<double>(steps);
  v.run.t_end = t_end;
  const double ratio = a.energy_ratio.empty() ? 100.0 : parse_double(a.energy_ratio, "spectrum: --energy-ratio");
  if (!(ratio > 1) || !std::isfinite(ratio))
    throw std::invalid_argument("spectrum: --energy-ratio must be finite and > 1 (got " + a.energy_ratio + ")");
  v.floor = detection_floor(t_end, ratio);
  return v;
}

template <int Dim>
void run(const RateFormSetup& setup, const VerdictSetup& verdict) {
  const RateFormMaterial& material = setup.material;
  std::string out =
      "dim,lattice,N,periodic,kernel,h_over_dx,xi,density,pressure,states,reduced,growth_rate,lambda_imag,"
      "mode_kx_over_pi,mode_ky_over_pi,equilibrium_residual,status,reason";
  if (verdict.on)
    out +=
        ",integrator,dt,floor,map_growth,map_spectral_radius,integrator_excess,map_mode_kx_over_pi,map_mode_ky_over_pi,"
        "verdict,verdict_status,verdict_reason";
  out += "\n";
  for (KernelType kt : setup.kernels)
    for (double h : setup.h_over_dx) {
      const auto disc = make_rate_form_discretisation<Dim>(setup, kt, h);
      for (double xi : setup.xi) {
        const double rho = material.density / xi;
        const RateFormScheme<Dim> scheme(disc, material, setup.options, rho);
        const Eigen::VectorXd y = scheme.uniform_state();
        Eigen::VectorXd f;
        scheme.rate(y, f);
        const RateFormSpectrum s = rate_form_spectrum(scheme, y, {.want_mode = true});
        double kx = NAN, ky = NAN;
        // Growth below 1e-9 of the largest |lambda| is rounding of a neutral spectrum: no unstable mode to locate.
        const bool unstable = s.status == Status::Successful &&
                              s.growth_rate > 1e-9 * (s.eigenvalues.size() ? s.eigenvalues.cwiseAbs().maxCoeff() : 0.0);
        if (unstable) {
          const Eigen::MatrixXd x = disc->free_positions();
          if constexpr (Dim == 1) {
            kx = dominant_wavenumber(s.mode, x.col(0), setup.periodic).k_projection;
          } else {
            const WavevectorEstimate k =
                dominant_wavevector(s.mode, Eigen::MatrixX2d(x), bravais_lattice_2d(setup.lattice, setup.dx));
            kx = k.kx_over_pi;
            ky = k.ky_over_pi;
          }
        }
        std::vector<std::string> row{std::to_string(Dim),
                                     lattice_name(setup.lattice),
                                     std::to_string(setup.n),
                                     setup.periodic ? "1" : "0",
                                     kernel_name(kt),
                                     num(h),
                                     num(xi),
                                     num(rho),
                                     num(material.bulk_modulus * (rho / material.density - 1)),
                                     std::to_string(s.states),
                                     std::to_string(s.reduced),
                                     num(s.growth_rate),
                                     num(std::abs(s.lambda.imag())),
                                     num(kx),
                                     num(ky),
                                     num(f.cwiseAbs().maxCoeff()),
                                     status_name(s.status),
                                     s.reason};
        if (verdict.on) {
          StabilityVerdictOptions vo{.floor = verdict.floor};
          if constexpr (Dim == 2) vo.lattice = bravais_lattice_2d(setup.lattice, setup.dx);
          const StabilityVerdict v = stability_verdict(scheme, y, verdict.run, vo);
          // Where the map's growth lives (NaN unless it grows above the floor): for class I, the integrator's mode.
          row.insert(row.end(), {v.integrator, num(v.dt), num(v.floor), num(v.map_growth), num(v.map_spectral_radius),
                                 num(v.integrator_excess), num(v.map_mode.kx_over_pi), num(v.map_mode.ky_over_pi),
                                 v.status == Status::Successful ? v.letter() : "", status_name(v.status), v.reason});
        }
        out += csv_line(row);
      }
    }
  std::fputs(out.c_str(), stdout);
}

void run_spectrum(const RateFormArgs& a, const VerdictArgs& va) {
  const RateFormSetup setup = parse_rate_form_args(a, "spectrum", true, 2, 4000, 40);
  const VerdictSetup verdict = parse_verdict_args(va);
  for (double h : setup.h_over_dx) {  // the reduced problem is dense: 2 x free DOFs squared
    const double free = setup.dim == 1 ? setup.n : double(setup.n) * setup.n;
    require_dense_memory(static_cast<long>(2 * setup.dim * free), 3, "spectrum: --n " + a.n + " h/dx " + num(h));
  }
  if (setup.dim == 1)
    run<1>(setup, verdict);
  else
    run<2>(setup, verdict);
}

}  // namespace

void register_spectrum_command(CLI::App& app) {
  auto a = std::make_shared<RateFormArgs>();
  auto va = std::make_shared<VerdictArgs>();
  auto* cmd = app.add_subcommand(
      "spectrum",
      "Full-state spectrum of the rate-form scheme (continuity, EOS, Jaumann rate; XSPH, viscosity, artificial stress "
      "switchable) on a lattice at volume strain xi = V/V0: growth rate max Re lambda(J) and the unstable mode's "
      "wavevector; CSV");
  add_rate_form_options(*cmd, *a, true);
  cmd->get_option("--viscosity")->description("off | compression | always (linearised at rest: compression = off)");
  cmd->add_option("--integrator", va->integrator,
                  "pc | pc1 | leapfrog: add the stability verdict of a run with this integrator (needs --dt and "
                  "--t-end): map_growth = ln rho(M) / dt of the one-step map, floor = ln(--energy-ratio) / (2 t_end), "
                  "verdict S | U | I | B (growth/stability_verdict.hpp; at rest with pc or a viscosity-free leapfrog reduced exactly, otherwise dense in the whole state)");
  cmd->add_option("--dt", va->dt, "the verdict's time step > 0 (reduced to t_end / ceil(t_end / dt) as in `run`)");
  cmd->add_option("--t-end", va->t_end, "the verdict's run length > 0");
  cmd->add_option("--energy-ratio", va->energy_ratio,
                  "kinetic-energy growth the run detects, > 1 (default 100): the floor is ln(ratio) / (2 t_end)");
  cmd->callback([a, va] { run_spectrum(*a, *va); });
}

}  // namespace sphstab::cli
