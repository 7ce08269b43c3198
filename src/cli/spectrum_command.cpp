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

template <int Dim>
void run(const RateFormSetup& setup, const VerdictSetup& verdict) {
  const ElasticMaterial& material = setup.material;
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
      const auto disc = rate_form_block_discretisation<Dim>(block_options(setup, kt, h));
      for (double xi : setup.xi) {
        const double rho = material.density() / xi;
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
                                     num(material.bulk_modulus() * (rho / material.density() - 1)),
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
  const VerdictSetup verdict = parse_verdict_args(va, "spectrum");
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
  add_verdict_options(*cmd, *va);
  cmd->callback([a, va] { run_spectrum(*a, *va); });
}

}  // namespace sphstab::cli
