// `sphstab jacobian elastic|rate-form --out DIR`: the linearisations of sphstab exported in Matrix Market
// (io/matrix_market.hpp), with the map from rows to particles, so that users can bring their own solvers.
//   - elastic: A(load) = A0 + load A1 of a lattice with fixed layers (jacobian/linearisation.hpp): the analytic 1D
//     Jacobian [Powell2012, (3.40)] (load: the pre-tension T) or the analytic 2D one (load: the pre-strain e);
//     DIR/A0.mtx, DIR/A1.mtx, DIR/dofs.csv (dof, particle, component, x[, y]). The critical load is the smallest
//     load at which A(load) loses definiteness (stability/critical_load.hpp; `sphstab tcrit` computes it).
//   - rate-form: J = dF/dy of the rate-form scheme at its uniform state (forms/rate_form.hpp; coloured complex step,
//     exact to rounding); DIR/J.mtx, DIR/state.csv (index, particle, variable, x[, y]).
// Every file starts with "%" comment lines naming the case.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "rate_form_args.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/matrix_market.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace sphstab::cli {

namespace {

struct ElasticArgs {
  // Plane strain, nu = 0.3 with E = 2.1, as `sphstab tcrit --dim 2`.
  std::string dim = "2", lattice = "square", n = "16", kernel = "cubic", form = "conservative", h = "1.3",
              lambda = "1.2115384615384615", mu = "0.80769230769230769", prestrain = "isotropic", out;
};

struct RateFormJacobianArgs {
  RateFormArgs scheme;
  std::string out;
};

std::filesystem::path output_dir(const std::string& out, const std::string& who) {
  if (out.empty()) throw std::invalid_argument(who + ": --out DIR is required");
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out))
    throw std::invalid_argument(who + ": cannot create the directory --out '" + out + "'");
  return out;
}

void run_elastic(const ElasticArgs& a) {
  const int dim = static_cast<int>(parse_integer(a.dim, 1, 2, "jacobian elastic: --dim"));
  const int n = static_cast<int>(parse_integer(a.n, 1, 100000000, "jacobian elastic: --n"));
  const double h = parse_double(a.h, "jacobian elastic: --h");
  check_length(h, "jacobian elastic: --h (h/dx, dx = 1)");
  const MomentumForm form = parse_momentum_form(a.form);
  const KernelType kt = parse_kernel_type(a.kernel);
  const std::filesystem::path dir = output_dir(a.out, "jacobian elastic");
  std::string header = "sphstab jacobian elastic: dim " + a.dim + ", kernel " + kernel_name(kt) + ", h/dx " + a.h +
                       ", form " + momentum_form_name(form) + ", n " + a.n + " free per side, fixed layers";
  Linearisation lin;
  std::string load;
  if (dim == 1) {
    const double support = Kernel<1>(kt).support_radius(h);
    require_memory(400.0 * n * (1 + 2 * support), "jacobian elastic: --dim 1 --n " + a.n);
    const Kernel<1> kernel(kt);
    lin = analytic_jacobian_1d(tension_lattice_1d(kernel, h, n), kernel, h, form);
    load = "pre-tension T (Powell (3.40); A = A0 + T A1)";
  } else {
    const LatticeType type = parse_lattice_type(a.lattice);
    const PreStrainKind kind = parse_prestrain_kind(a.prestrain);
    const ElasticMaterial material = ElasticMaterial::from_lame(parse_double(a.lambda, "jacobian elastic: --lambda"),
                                                                parse_double(a.mu, "jacobian elastic: --mu"), 1.0);
    material.validate("jacobian elastic");
    const Kernel<2> kernel(kt);
    const double support = kernel.support_radius(h), side = n + 2 * std::floor(support + 2);
    require_memory(
        side * side * (25 + 66 * (1 + M_PI * support * support)) + 192.0 * n * n * (1 + 4 * M_PI * support * support),
        "jacobian elastic: --dim 2 --n " + a.n);
    lin = analytic_jacobian_2d(*make_discretisation(strain_lattice_2d(type, kernel, h, n), kernel, h), material, form,
                               kind);
    load = std::string(kind == PreStrainKind::Isotropic ? "isotropic" : "uniaxial-x") +
           " pre-strain e (A = A0 + e A1); lattice " + lattice_name(type) + ", lambda " + a.lambda + ", mu " + a.mu;
  }
  header += "\nload: " + load + "\nrows and columns: the dofs of dofs.csv (free particles, components interleaved)";
  write_matrix_market((dir / "A0.mtx").string(), lin.A0, header + "\nA0: A at zero load");
  write_matrix_market((dir / "A1.mtx").string(), lin.A1, header + "\nA1: dA/dload");
  std::vector<std::string> cols = {"dof", "particle", "component", "x"};
  if (dim == 2) cols.push_back("y");
  CsvWriter w((dir / "dofs.csv").string(), cols, false);
  for (int f = 0; f < lin.free_count(); ++f)
    for (int c = 0; c < lin.dofs_per_particle; ++c) {
      std::vector<CsvCell> row = {static_cast<long>(f * lin.dofs_per_particle + c),
                                  static_cast<long>(lin.free_index[f]), std::string(c == 0 ? "x" : "y"), lin.x(f, 0)};
      if (dim == 2) row.push_back(lin.x(f, 1));
      w.row(row);
    }
  std::printf("wrote %s/A0.mtx, A1.mtx (%d x %d, %ld and %ld stored entries), dofs.csv\n", a.out.c_str(), lin.dofs(),
              lin.dofs(), static_cast<long>(lin.A0.nonZeros()), static_cast<long>(lin.A1.nonZeros()));
}

template <int Dim>
void export_rate_form(const RateFormSetup& s, const std::filesystem::path& dir, const std::string& out) {
  const auto disc = rate_form_block_discretisation<Dim>(block_options(s, s.kernels.front(), s.h_over_dx.front()));
  const RateFormScheme<Dim> scheme(disc, s.material, s.options, s.material.density() / s.xi.front());
  const Eigen::VectorXd y = scheme.uniform_state();
  const SparseMatrix<> J = jacobian(scheme, y);
  write_matrix_market((dir / "J.mtx").string(), J,
                      "sphstab jacobian rate-form: " + scheme.name() + ", volume strain xi " +
                          format_number(s.xi.front()) +
                          "\nJ = dF/dy at the uniform state (coloured complex step); rows and columns: state.csv");
  std::vector<std::string> cols = {"index", "particle", "variable", "x"};
  if (Dim == 2) cols.push_back("y");
  CsvWriter w((dir / "state.csv").string(), cols, false);
  const ParticleSet<Dim>& p = disc->particles;
  const std::vector<std::string> xs = Dim == 1 ? std::vector<std::string>{"x"} : std::vector<std::string>{"x", "y"};
  const std::vector<std::string> stress =
      Dim == 1 ? std::vector<std::string>{"S_xx"} : std::vector<std::string>{"S_xx", "S_yy", "S_xy"};
  for (int i = 0; i < p.size(); ++i) {
    auto put = [&](int index, const std::string& var) {
      std::vector<CsvCell> row = {static_cast<long>(index), static_cast<long>(i), var, p.x(i, 0)};
      if (Dim == 2) row.push_back(p.x(i, Dim - 1));
      w.row(row);
    };
    if (scheme.position_offset(i) >= 0)
      for (int a = 0; a < Dim; ++a) put(scheme.position_offset(i) + a, xs[a]);
    if (scheme.velocity_offset(i) >= 0)
      for (int a = 0; a < Dim; ++a) put(scheme.velocity_offset(i) + a, "v" + xs[a]);
    if (scheme.density_offset(i) >= 0) put(scheme.density_offset(i), "rho");
    if (scheme.stress_offset(i) >= 0)
      for (int c = 0; c < RateFormScheme<Dim>::kStress; ++c) put(scheme.stress_offset(i) + c, stress[c]);
  }
  std::printf("wrote %s/J.mtx (%ld x %ld, %ld stored entries), state.csv\n", out.c_str(), static_cast<long>(J.rows()),
              static_cast<long>(J.cols()), static_cast<long>(J.nonZeros()));
}

/// Peak memory of the exported J, estimated before the scheme is built (issue 36: --n 1000 needed ~39 GB unannounced):
/// the scheme as a run's (run_command.cpp) and about 32 bytes per stored entry of J (the pattern, its transpose and
/// positions, the matrix's values and indices; measured 1.56 GB resident for 54 M entries, a 2D 200 x 200 block). A
/// particle's rows (its state entries) reach the state entries of the particles within `hops` supports
/// (RateFormScheme::pattern(): 1; 2 with XSPH or the antisymmetric / C_ij momentum; 3 for S-SPH), with the mean state
/// entries per particle on both sides (a block's edges make the count an upper bound, tight for large blocks).
void require_jacobian_memory(const RateFormSetup& s, const std::string& what) {
  const BlockSize b = block_size(s);
  const RateFormMomentum m = s.options.momentum;
  const int hops = std::max(m == RateFormMomentum::Symmetric       ? 1
                            : m == RateFormMomentum::StabilisedSph ? 3
                                                                   : 2,
                            s.options.xsph > 0 ? 2 : 1);
  // State entries: x, v, rho, S of a free particle; rho, S of a fixed one (evolving: the default).
  const double stress = s.dim == 1 ? 1 : 3,
               state = b.free * (2 * s.dim + 1 + stress) + (b.particles - b.free) * (1 + stress);
  const double entries = state * std::min(b.within(s, hops), b.particles) * (state / b.particles);
  require_memory(b.particles * (250 + 40 * std::min(b.within(s, 1), b.particles)) + 32 * entries,
                 what + " (about " + format_number(entries, 3) + " stored entries in J)");
}

void run_rate_form_jacobian(const RateFormJacobianArgs& a) {
  const RateFormSetup s = parse_rate_form_args(a.scheme, "jacobian rate-form", false, 1, 1'000'000, 1'000);
  require_jacobian_memory(s, "jacobian rate-form: --dim " + std::to_string(s.dim) + " --n " + std::to_string(s.n));
  const std::filesystem::path dir = output_dir(a.out, "jacobian rate-form");
  if (s.dim == 1)
    export_rate_form<1>(s, dir, a.out);
  else
    export_rate_form<2>(s, dir, a.out);
}

}  // namespace

void register_jacobian_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("jacobian", "Export a linearisation in Matrix Market with its row map (--out DIR)");
  cmd->require_subcommand(1);
  auto e = std::make_shared<ElasticArgs>();
  auto* el = cmd->add_subcommand(
      "elastic", "A0.mtx, A1.mtx (A = A0 + load A1, the critical-load engine's input) and dofs.csv of a lattice");
  el->add_option("--out", e->out, "output directory (created)")->required();
  el->add_option("--dim", e->dim, "1 (load: pre-tension T) or 2 (load: pre-strain e; default)");
  el->add_option("--lattice", e->lattice, "2D: square|hex|face-centred (default square)");
  el->add_option("--n", e->n, "free particles per side (default 16)");
  el->add_option("--kernel", e->kernel, "kernel name (default cubic)");
  el->add_option("--form", e->form, "momentum form: conservative|plus|minus|... (default conservative)");
  el->add_option("--h", e->h, "h / dx (default 1.3)");
  el->add_option("--lambda", e->lambda, "2D: Lame lambda (default: E = 2.1, nu = 0.3, plane strain)");
  el->add_option("--mu", e->mu, "2D: shear modulus mu");
  el->add_option("--prestrain", e->prestrain, "2D: isotropic|uniaxial (default isotropic)");
  el->callback([e, el] {
    // The 2D options do nothing in 1D (issue 36): refused with the reason rather than ignored.
    if (e->dim == "1")
      for (const char* option : {"--lattice", "--lambda", "--mu", "--prestrain"})
        if (el->count(option) > 0)
          throw std::invalid_argument(std::string("jacobian elastic: ") + option +
                                      " applies to --dim 2 only (1D: a line under pre-tension T)");
    run_elastic(*e);
  });
  auto r = std::make_shared<RateFormJacobianArgs>();
  auto* rf =
      cmd->add_subcommand("rate-form", "J.mtx (dF/dy at the uniform state) and state.csv of the rate-form scheme");
  rf->add_option("--out", r->out, "output directory (created)")->required();
  add_rate_form_options(*rf, r->scheme, false);
  rf->callback([r] { run_rate_form_jacobian(*r); });
}

}  // namespace sphstab::cli
