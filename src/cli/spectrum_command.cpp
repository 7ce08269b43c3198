// `sphstab spectrum`: the full-state spectrum of the rate-form scheme (forms/rate_form.hpp) on a lattice at a uniform
// volume strain xi: growth rate max Re lambda(J), the dominant wavevector of the unstable mode, the equilibrium
// residual, as CSV (growth/rate_form_spectrum.hpp: complex-step J, exact at-rest reduction).
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/particles/bravais_lattice.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"

namespace sphstab::cli {

namespace {

struct SpectrumArgs {
  std::string dim = "2", lattice, n = "12", kernel = "cubic", h = "1.3", xi = "1.02", youngs = "2.1", poisson = "0.3",
              density = "7.8", dx = "0.01", xsph = "0", viscosity = "off", alpha = "0.06", beta = "1.5",
              artificial_stress = "0", continuity = "summation";
  bool periodic = false;
};

std::string num(double v) { return format_number(v, 10); }

template <int Dim>
void run(const SpectrumArgs& a, LatticeType type, int n, const std::vector<KernelType>& kernels,
         const std::vector<double>& hs, const std::vector<double>& xis, const RateFormMaterial& material,
         const RateFormOptions& options, double dx) {
  std::string out =
      "dim,lattice,N,periodic,kernel,h_over_dx,xi,density,pressure,states,reduced,growth_rate,lambda_imag,"
      "mode_kx_over_pi,mode_ky_over_pi,equilibrium_residual,status,reason\n";
  for (KernelType kt : kernels)
    for (double h : hs) {
      const Kernel<Dim> kernel(kt);
      const ParticleSet<Dim> set = make_lattice<Dim>(
          type, n, {.spacing = dx, .support_radius = kernel.support_radius(h * dx), .periodic = a.periodic});
      const auto disc = make_discretisation(set, kernel, h * dx);
      for (double xi : xis) {
        const double rho = material.density / xi;
        const RateFormScheme<Dim> scheme(disc, material, options, rho);
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
            kx = dominant_wavenumber(s.mode, x.col(0), a.periodic).k_projection;
          } else {
            const WavevectorEstimate k = dominant_wavevector(s.mode, Eigen::MatrixX2d(x), bravais_lattice_2d(type, dx));
            kx = k.kx_over_pi;
            ky = k.ky_over_pi;
          }
        }
        out += csv_line({std::to_string(Dim), lattice_name(type), std::to_string(n), a.periodic ? "1" : "0",
                         kernel_name(kt), num(h), num(xi), num(rho),
                         num(material.bulk_modulus * (rho / material.density - 1)), std::to_string(s.states),
                         std::to_string(s.reduced), num(s.growth_rate), num(std::abs(s.lambda.imag())), num(kx),
                         num(ky), num(f.cwiseAbs().maxCoeff()), status_name(s.status), s.reason});
      }
    }
  std::fputs(out.c_str(), stdout);
}

void run_spectrum(const SpectrumArgs& a) {
  const int dim = static_cast<int>(parse_integer(a.dim, 1, 2, "spectrum: --dim"));
  const LatticeType type = parse_lattice_type(a.lattice.empty() ? (dim == 1 ? "line" : "square") : a.lattice);
  if ((dim == 1) != (type == LatticeType::Line) || type == LatticeType::Cubic)
    throw std::invalid_argument("spectrum: --lattice " + lattice_name(type) + " does not exist in " +
                                std::to_string(dim) + "D (1D: line; 2D: square, hex, face-centred)");
  const int n = static_cast<int>(parse_integer(a.n, 2, dim == 1 ? 4000 : 40, "spectrum: --n"));
  std::vector<KernelType> kernels;
  for (const auto& k : split_list(a.kernel, ',', "spectrum: --kernel")) kernels.push_back(parse_kernel_type(k));
  std::vector<double> hs, xis;
  for (const auto& s : split_list(a.h, ',', "spectrum: --h")) hs.push_back(parse_double(s, "spectrum: --h"));
  for (const auto& s : split_list(a.xi, ',', "spectrum: --xi")) xis.push_back(parse_double(s, "spectrum: --xi"));
  const double dx = parse_double(a.dx, "spectrum: --dx");
  check_length(dx, "spectrum: --dx");
  for (double h : hs) check_length(h * dx, "spectrum: --h x --dx");
  for (double xi : xis)
    if (!(xi > 0)) throw std::invalid_argument("spectrum: --xi must be > 0 (got " + num(xi) + ")");
  const RateFormMaterial material = RateFormMaterial::from_youngs(parse_double(a.youngs, "spectrum: --youngs"),
                                                                  parse_double(a.poisson, "spectrum: --poisson"),
                                                                  parse_double(a.density, "spectrum: --density"));
  RateFormOptions o;
  o.continuity = parse_continuity_form(a.continuity);
  o.xsph = parse_double(a.xsph, "spectrum: --xsph");
  o.viscosity = parse_viscosity_switch(a.viscosity);
  o.viscosity_alpha = parse_double(a.alpha, "spectrum: --alpha");
  o.viscosity_beta = parse_double(a.beta, "spectrum: --beta");
  o.artificial_stress = parse_double(a.artificial_stress, "spectrum: --artificial-stress");
  for (double h : hs) {  // the reduced problem is dense: 2 x free DOFs squared
    const double free = dim == 1 ? n : double(n) * n;
    require_dense_memory(static_cast<long>(2 * dim * free), 3, "spectrum: --n " + a.n + " h/dx " + num(h));
  }
  if (dim == 1)
    run<1>(a, type, n, kernels, hs, xis, material, o, dx);
  else
    run<2>(a, type, n, kernels, hs, xis, material, o, dx);
}

}  // namespace

void register_spectrum_command(CLI::App& app) {
  auto a = std::make_shared<SpectrumArgs>();
  auto* cmd = app.add_subcommand(
      "spectrum",
      "Full-state spectrum of the rate-form scheme (continuity, EOS, Jaumann rate; XSPH, viscosity, artificial stress "
      "switchable) on a lattice at volume strain xi = V/V0: growth rate max Re lambda(J) and the unstable mode's "
      "wavevector; CSV");
  cmd->add_option("--dim", a->dim, "1 or 2 (default 2)");
  cmd->add_option("--lattice", a->lattice, "line (1D); square, hex, face-centred (2D; default square)");
  cmd->add_option("--n", a->n, "free particles per side (default 12; fixed layers added unless --periodic)");
  cmd->add_flag("--periodic", a->periodic, "periodic lattice (no fixed layers)");
  cmd->add_option("--kernel", a->kernel, "kernel name or comma list (default cubic)");
  cmd->add_option("--h", a->h, "h/dx, value or comma list (default 1.3)");
  cmd->add_option("--xi", a->xi, "volume strain V/V0 > 0, value or comma list (default 1.02; > 1 tension)");
  cmd->add_option("--dx", a->dx, "lattice spacing (default 0.01)");
  cmd->add_option("--youngs", a->youngs, "Young's modulus E > 0 (default 2.1, Mbar)");
  cmd->add_option("--poisson", a->poisson, "Poisson's ratio in (-1, 1/2) (default 0.3)");
  cmd->add_option("--density", a->density, "rho0 > 0 at zero pressure (default 7.8)");
  cmd->add_option("--continuity", a->continuity, "summation (GMS 3.8) | divergence (-rho tr L)");
  cmd->add_option("--xsph", a->xsph, "XSPH epsilon (GMS 3.6), >= 0 (default 0)");
  cmd->add_option("--viscosity", a->viscosity, "off | compression | always (linearised at rest: compression = off)");
  cmd->add_option("--alpha", a->alpha, "viscosity alpha (default 0.06)");
  cmd->add_option("--beta", a->beta, "viscosity beta (default 1.5)");
  cmd->add_option("--artificial-stress", a->artificial_stress, "GMS artificial stress epsilon, >= 0 (default 0)");
  cmd->callback([a] { run_spectrum(*a); });
}

}  // namespace sphstab::cli
