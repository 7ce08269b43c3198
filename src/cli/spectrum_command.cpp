// `sphstab spectrum`: the full-state spectrum of the rate-form scheme (forms/rate_form.hpp) on a lattice at a uniform
// volume strain xi: growth rate max Re lambda(J), the dominant wavevector of the unstable mode, the equilibrium
// residual, as CSV (growth/rate_form_spectrum.hpp: complex-step J, exact at-rest reduction). The scheme's options are
// rate_form_args.hpp's, shared with `sphstab run`.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rate_form_args.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/particles/bravais_lattice.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"

namespace sphstab::cli {

namespace {

std::string num(double v) { return format_number(v, 10); }

template <int Dim>
void run(const RateFormSetup& setup) {
  const RateFormMaterial& material = setup.material;
  std::string out =
      "dim,lattice,N,periodic,kernel,h_over_dx,xi,density,pressure,states,reduced,growth_rate,lambda_imag,"
      "mode_kx_over_pi,mode_ky_over_pi,equilibrium_residual,status,reason\n";
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
        out += csv_line({std::to_string(Dim), lattice_name(setup.lattice), std::to_string(setup.n),
                         setup.periodic ? "1" : "0", kernel_name(kt), num(h), num(xi), num(rho),
                         num(material.bulk_modulus * (rho / material.density - 1)), std::to_string(s.states),
                         std::to_string(s.reduced), num(s.growth_rate), num(std::abs(s.lambda.imag())), num(kx),
                         num(ky), num(f.cwiseAbs().maxCoeff()), status_name(s.status), s.reason});
      }
    }
  std::fputs(out.c_str(), stdout);
}

void run_spectrum(const RateFormArgs& a) {
  const RateFormSetup setup = parse_rate_form_args(a, "spectrum", true, 2, 4000, 40);
  for (double h : setup.h_over_dx) {  // the reduced problem is dense: 2 x free DOFs squared
    const double free = setup.dim == 1 ? setup.n : double(setup.n) * setup.n;
    require_dense_memory(static_cast<long>(2 * setup.dim * free), 3, "spectrum: --n " + a.n + " h/dx " + num(h));
  }
  if (setup.dim == 1)
    run<1>(setup);
  else
    run<2>(setup);
}

}  // namespace

void register_spectrum_command(CLI::App& app) {
  auto a = std::make_shared<RateFormArgs>();
  auto* cmd = app.add_subcommand(
      "spectrum",
      "Full-state spectrum of the rate-form scheme (continuity, EOS, Jaumann rate; XSPH, viscosity, artificial stress "
      "switchable) on a lattice at volume strain xi = V/V0: growth rate max Re lambda(J) and the unstable mode's "
      "wavevector; CSV");
  add_rate_form_options(*cmd, *a, true);
  cmd->get_option("--viscosity")->description("off | compression | always (linearised at rest: compression = off)");
  cmd->callback([a] { run_spectrum(*a); });
}

}  // namespace sphstab::cli
