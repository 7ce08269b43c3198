// `sphstab tcrit`: critical tension of a 1D lattice (Powell ch. 3) with the closed-form estimates, as CSV; with
// --correction, of the 1D forms with a corrected kernel gradient (Powell ch. 3 §4.1.1, ch. 4 §2) by the general
// affine route (critical_tension_sweep.hpp); or (--dim 2, 3) the critical pre-strain of an elastic lattice through the
// critical-load front door (critical_strain_sweep.hpp, critical_load_problem.hpp: route, memory, fallbacks). This file
// parses, validates, names the route and prints; the computing is the library's.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "parse.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/progress.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/fourier_symbol_2d.hpp"
#include "sphstab/spectral/tension_estimates.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/critical_load_problem.hpp"
#include "sphstab/stability/critical_strain_sweep.hpp"
#include "sphstab/stability/critical_tension_sweep.hpp"
#ifdef SPHSTAB_WITH_PETSC
#include "sphstab/distributed/petsc_critical_load_solver.hpp"
#endif

namespace sphstab::cli {

namespace {

struct TcritArgs {
  std::string dim = "1", lattice = "line", n = "30", kernel = "cubic", form = "conservative", h = "1.2",
              method = "both", backend = "auto", correction = "none", corrected = "auto", prestrain = "isotropic",
              criterion = "auto", route = "auto";
  // Plane strain, nu = 0.3 with E = 2.1 (Powell's Swegle test): the critical strain depends on nu only.
  std::string lambda = "1.2115384615384615", mu = "0.80769230769230769";
  bool periodic = false, compression = false;
  bool lattice_given = false, prestrain_given = false, lame_given = false, criterion_given = false,
       method_given = false, route_given = false;
};

/// Fixed layers of the lattice used with a kernel correction, in kernel supports (2h): every particle that the free
/// particles' corrected rows read then has a complete neighbourhood, so u = 0 is an equilibrium of every form and
/// correction (Powell's regular grid, ch. 3 footnote h); checked by the residual in `reason`.
constexpr int kCorrectedLayerSupports = 3;

int parse_positive_int(const std::string& s, const std::string& what) {
  return static_cast<int>(parse_integer(s, 1, 100000000, "tcrit: " + what));
}

/// "a", "a,b,c" or "a:b:step" (inclusive, values snapped to 12 significant digits).
std::vector<double> parse_h(const std::string& spec) {
  std::vector<double> hs;
  const auto range = split_list(spec, ':', "tcrit: --h");
  if (range.size() == 3) {
    const double a = parse_double(range[0], "tcrit: --h start"), b = parse_double(range[1], "tcrit: --h end"),
                 s = parse_double(range[2], "tcrit: --h step");
    if (!(s > 0) || b < a)
      throw std::invalid_argument("tcrit: --h a:b:step needs step > 0 and b >= a (got '" + spec + "')");
    const double count = std::floor((b - a) / s + 1e-9) + 1;
    if (count > 1e6) throw std::invalid_argument("tcrit: --h range has more than 10^6 values ('" + spec + "')");
    for (int i = 0; i < static_cast<int>(count); ++i) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.12g", a + i * s);
      hs.push_back(std::stod(buf));
    }
  } else if (range.size() == 1) {
    for (const auto& item : split_list(spec, ',', "tcrit: --h")) hs.push_back(parse_double(item, "tcrit: --h"));
  } else {
    throw std::invalid_argument("tcrit: --h must be a value, a comma list or a:b:step (got '" + spec + "')");
  }
  for (double h : hs) check_length(h, "tcrit: --h (h/dx, dx = 1)");
  return hs;
}

std::string num(double v) { return format_number(v, 12); }

/// A long sweep says so: when the first case's time x the number of cases exceeds a minute, an estimate on stderr,
/// then a progress line every 10 s (stdout keeps only the CSV).
class SweepProgress {
 public:
  explicit SweepProgress(long cases) : m_cases(cases), m_start(std::chrono::steady_clock::now()) {}
  void case_done() {
    ++m_done;
    if (m_done == 1 && m_cases > 1) {
      const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
      if (first * m_cases > 60) {
        std::fprintf(stderr, "tcrit: %ld cases; the first took %.3g s, so about %.3g min in all\n", m_cases, first,
                     first * m_cases / 60);
        m_line.emplace("tcrit", 10.0);
      }
    }
    if (m_line) m_line->update(static_cast<double>(m_done), static_cast<double>(m_cases));
  }

 private:
  long m_cases, m_done = 0;
  std::chrono::steady_clock::time_point m_start;
  std::optional<ProgressLine> m_line;
};

/// The sweep of a --dim 2 or --dim 3 run: pre-strain kind, material (rho = 1: it cancels in e_crit), kernels, forms
/// and h values, validated in this order.
struct ElasticSweep {
  PreStrainKind kind;
  ElasticMaterial material = ElasticMaterial::from_lame(1.0, 1.0, 1.0);
  std::vector<KernelType> kernels;
  std::vector<MomentumForm> forms;
  std::vector<double> hs;
};

ElasticSweep parse_elastic_sweep(const TcritArgs& a) {
  ElasticSweep sw;
  sw.kind = parse_prestrain_kind(a.prestrain);
  sw.material =
      ElasticMaterial::from_lame(parse_double(a.lambda, "tcrit: --lambda"), parse_double(a.mu, "tcrit: --mu"), 1.0);
  sw.material.validate("tcrit");
  for (const auto& k : split_list(a.kernel, ',', "tcrit: --kernel")) sw.kernels.push_back(parse_kernel_type(k));
  for (const auto& f : split_list(a.form, ',', "tcrit: --form")) sw.forms.push_back(parse_momentum_form(f));
  if (sw.kernels.empty() || sw.forms.empty())
    throw std::invalid_argument("tcrit: --kernel and --form must not be empty");
  sw.hs = parse_h(a.h);
  return sw;
}

/// Shared row of the --dim 2 and --dim 3 tables (the infinite-lattice columns NaN where not computed).
template <int Dim>
std::vector<std::string> critical_prestrain_row(const ElasticLatticeProblem<Dim>& p, LoadDirection sign,
                                                const CriticalLoadResult& r, double e_inf, double inf_kx,
                                                double inf_ky) {
  return {kernel_name(p.kernel),
          momentum_form_name(p.form),
          lattice_name(p.lattice),
          std::to_string(p.n),
          p.periodic ? "1" : "0",
          prestrain_kind_name(p.prestrain),
          load_direction_name(sign),
          num(p.h),
          "critical-prestrain",
          r.method,
          r.backend,
          criterion_name(r.criterion),
          num(r.load),
          num(r.load_eigen),
          num(r.load_bisection),
          num(r.relative_difference),
          mechanism_name(r.mechanism),
          num(e_inf),
          num(r.symbol ? r.symbol->e : CriticalLoadResult::nan),
          num(r.mode_wavevector.kx_over_pi),
          num(r.mode_wavevector.ky_over_pi),
          num(r.mode_wavevector.peak_fraction),
          num(inf_kx),
          num(inf_ky),
          status_name(r.status),
          r.reason};
}

const char* kCriticalPrestrainHeader =
    "kernel,form,lattice,N,periodic,prestrain,direction,h_over_dx,quantity,method,backend,criterion,ecrit,ecrit_eig,"
    "ecrit_bisect,rel_diff,mechanism,ecrit_infinite,ecrit_symbol,mode_kx_over_pi,mode_ky_over_pi,"
    "mode_peak_fraction,infinite_kx_over_pi,infinite_ky_over_pi,status,reason\n";

/// --route petsc: the PETSc/SLEPc backend's solver (library sphstab_petsc) in a session for the rest of the process.
DistributedCriticalLoadSolver petsc_solver() {
#ifdef SPHSTAB_WITH_PETSC
  ensure_petsc_session();
  return petsc_critical_load_solver();
#else
  throw std::invalid_argument("tcrit: --route petsc needs sphstab built with SPHSTAB_WITH_PETSC (PETSc and SLEPc)");
#endif
}

/// A --dim 2 or --dim 3 sweep (critical_strain_sweep.hpp: every case through the critical-load front door, route and
/// memory checked for every case before anything is computed, so a refusal is one error line and an empty stdout) as
/// CSV. `label` gives the memory refusal's text for a route and an h.
template <int Dim, class Label>
void run_lattice_sweep(const TcritArgs& a, const ElasticSweep& sw, ElasticLatticeProblem<Dim> p,
                       CriticalLoadRouteOptions opt, Label&& label) {
  if (opt.route == CriticalLoadRoute::Distributed) opt.distributed = petsc_solver();
  p.material = sw.material;
  p.prestrain = sw.kind;
  SweepProgress progress(static_cast<long>(sw.kernels.size() * sw.hs.size() * sw.forms.size()));
  const CriticalStrainSweep<Dim> sweep{
      .base = p,
      .kernels = sw.kernels,
      .hs = sw.hs,
      .forms = sw.forms,
      .direction = a.compression ? LoadDirection::Compression : LoadDirection::Tension,
      .options = opt,
      .memory_label = [&](CriticalLoadRoute route, const ElasticLatticeProblem<Dim>& q) { return label(route, q.h); },
      .on_case = [&] { progress.case_done(); }};
  std::string out = kCriticalPrestrainHeader;
  for (const CriticalStrainCase<Dim>& c : critical_strain_sweep(sweep))
    out += csv_line(critical_prestrain_row(c.problem, sweep.direction, c.result, c.infinite.e, c.infinite.kx_over_pi,
                                           c.infinite.ky_over_pi));
  std::fputs(out.c_str(), stdout);
}

/// --route, or the route that --method implies: lobpcg is the matrix-free route; a periodic lattice the symbol route;
/// otherwise the assembled route (the front door's own choice, auto, only when asked: it would run a lattice too
/// large for the assembled route matrix-free instead of refusing it).
CriticalLoadRoute tcrit_route(const TcritArgs& a, bool lobpcg) {
  if (a.route_given) {
    const CriticalLoadRoute r = parse_critical_load_route(a.route);
    if (lobpcg && r != CriticalLoadRoute::MatrixFree)
      throw std::invalid_argument("tcrit: --method lobpcg is the matrix-free route (got --route " + a.route + ")");
    return r;
  }
  if (lobpcg) return CriticalLoadRoute::MatrixFree;
  return a.periodic ? CriticalLoadRoute::Symbol : CriticalLoadRoute::Assembled;
}

/// "--method lobpcg " or "--route NAME " for messages (empty for the assembled route asked by --method).
std::string route_flag(const TcritArgs& a, CriticalLoadRoute route) {
  if (route == CriticalLoadRoute::MatrixFree && !a.route_given) return "--method lobpcg ";
  if (!a.route_given || route == CriticalLoadRoute::Assembled || route == CriticalLoadRoute::Auto) return "";
  return "--route " + a.route + " ";
}

/// --dim 3: critical pre-strain of an n x n x n cubic lattice with fixed layers (matrix-free block LOBPCG unless
/// --route says otherwise).
void run_tcrit_3d(const TcritArgs& a) {
  if (a.method_given && a.method != "lobpcg")
    throw std::invalid_argument("tcrit: --dim 3 has one route, --method lobpcg (got '" + a.method + "')");
  if (a.lattice_given && parse_lattice_type(a.lattice) != LatticeType::Cubic)
    throw std::invalid_argument("tcrit: --lattice '" + a.lattice + "' is not available in 3D (use cubic)");
  if (a.periodic || a.correction != "none" || a.corrected != "auto" || a.backend != "auto" || a.criterion != "auto")
    throw std::invalid_argument(
        "tcrit: --dim 3 takes no --periodic, --correction, --corrected-operator, --backend or --criterion (fixed "
        "layers, matrix-free definiteness)");
  const int n = parse_positive_int(a.n, "--n");
  if (n < 2) throw std::invalid_argument("tcrit: --dim 3 needs --n >= 2 (got " + a.n + ")");
  const ElasticSweep sw = parse_elastic_sweep(a);
  CriticalLoadRouteOptions opt;
  opt.route = a.route_given ? tcrit_route(a, false) : CriticalLoadRoute::MatrixFree;
  run_lattice_sweep<3>(a, sw, {.lattice = LatticeType::Cubic, .n = n}, opt, [&](CriticalLoadRoute route, double h) {
    const std::string flag = route == CriticalLoadRoute::MatrixFree ? "" : route_flag(a, route);
    return "tcrit: --dim 3 " + flag + "--n " + std::to_string(n) +
           " with h/dx = " + num(Kernel<3>(sw.kernels[0]).support_radius(h) / 2);
  });
}

/// --dim 2: critical pre-strain e_crit of an n x n lattice (fixed layers: analytic Jacobian, bisection + eigen, or
/// matrix-free; periodic: exact Fourier symbols) with the infinite-lattice limit.
void run_tcrit_2d(const TcritArgs& a) {
  const LatticeType type = parse_lattice_type(a.lattice_given ? a.lattice : std::string("square"));
  if (type != LatticeType::Square && type != LatticeType::Hexagonal && type != LatticeType::FaceCentred)
    throw std::invalid_argument("tcrit: --lattice '" + a.lattice +
                                "' does not exist in 2D (use square, hex or face-centred)");
  if (a.correction != "none")
    throw std::invalid_argument("tcrit: --correction '" + a.correction + "' is not available yet (valid: none)");
  if (a.corrected != "auto")  // issue 36: it was accepted and ignored
    throw std::invalid_argument("tcrit: --corrected-operator applies only to a 1D --correction (2D: none)");
  const int n = parse_positive_int(a.n, "--n");
  if (a.periodic && n < 2) throw std::invalid_argument("tcrit: --periodic needs --n >= 2");
  if (a.periodic && type != LatticeType::Square && n % 2 != 0)
    throw std::invalid_argument("tcrit: periodic hex/face-centred lattices need an even --n (got " + a.n + ")");
  const ElasticSweep sw = parse_elastic_sweep(a);
  // lobpcg: the matrix-free preconditioned block LOBPCG (matrix_free_critical_load.hpp, BlockLobpcg), O(N) memory
  const bool lobpcg = a.method == "lobpcg";
  CriticalLoadRouteOptions opt;
  opt.route = tcrit_route(a, lobpcg);
  if (opt.route == CriticalLoadRoute::MatrixFree) {
    const std::string flag = lobpcg ? "--method lobpcg" : "--route matrix-free";
    if (a.periodic || type != LatticeType::Square)
      throw std::invalid_argument("tcrit: " + flag + " needs a square lattice with fixed layers (not --periodic)");
    if (a.backend != "auto" || a.criterion != "auto")
      throw std::invalid_argument("tcrit: " + flag + " takes no --backend or --criterion (definiteness, matrix-free)");
  }
  opt.assembled = CriticalLoadOptions::strain_2d();
  opt.assembled.method = lobpcg ? CriticalLoadMethod::Eigen : parse_critical_load_method(a.method);
  opt.assembled.backend = parse_eigen_backend(a.backend);
  opt.assembled.criterion = parse_criterion(a.criterion);
  opt.assembled.want_mode = true;
  for (double h : sw.hs) {
    const double support = Kernel<2>(sw.kernels[0]).support_radius(h);
    if (a.periodic && n * (type == LatticeType::Hexagonal ? std::sqrt(3.0) / 2 : 1.0) < 2 * support)
      throw std::invalid_argument("tcrit: periodic box of --n " + a.n +
                                  " is shorter than twice the support 2h = " + num(support) + " (increase --n)");
  }
  run_lattice_sweep<2>(a, sw, {.lattice = type, .n = n, .periodic = a.periodic}, opt,
                       [&](CriticalLoadRoute route, double h) {
                         return "tcrit: --dim 2 " + route_flag(a, route) + "--n " + std::to_string(n) +
                                " with h/dx = " + num(Kernel<2>(sw.kernels[0]).support_radius(h) / 2);
                       });
}

void run_tcrit(const TcritArgs& a) {
  // Validate everything before printing anything.
  const int dim = static_cast<int>(parse_integer(a.dim, 1, 3, "tcrit: --dim"));
  if (dim == 3) return run_tcrit_3d(a);
  if (dim == 2) return run_tcrit_2d(a);
  if (a.prestrain_given || a.lame_given || a.criterion_given)
    throw std::invalid_argument("tcrit: --prestrain, --lambda, --mu and --criterion need --dim 2 or 3");
  if (a.route_given) throw std::invalid_argument("tcrit: --route needs --dim 2 or 3 (1D: --method and --backend)");
  if (parse_lattice_type(a.lattice) != LatticeType::Line)
    throw std::invalid_argument("tcrit: --lattice '" + a.lattice + "' does not exist in 1D (use line)");
  const Correction correction = parse_correction(a.correction);
  const CorrectedOperator corrected = parse_corrected_operator(a.corrected);
  if (correction == Correction::None && corrected != CorrectedOperator::Auto)
    throw std::invalid_argument("tcrit: --corrected-operator applies only with a --correction other than none");
  if (correction != Correction::None && a.periodic)
    throw std::invalid_argument(
        "tcrit: --periodic is only available with --correction none (the general route does "
        "not deflate the translation null mode of a periodic lattice)");
  const LoadDirection direction = a.compression ? LoadDirection::Compression : LoadDirection::Tension;
  const int nfree = parse_positive_int(a.n, "--n");
  std::vector<KernelType> kernels;
  for (const auto& k : split_list(a.kernel, ',', "tcrit: --kernel")) kernels.push_back(parse_kernel_type(k));
  std::vector<MomentumForm> forms;
  for (const auto& f : split_list(a.form, ',', "tcrit: --form")) forms.push_back(parse_momentum_form(f));
  if (kernels.empty() || forms.empty()) throw std::invalid_argument("tcrit: --kernel and --form must not be empty");
  const std::vector<double> hs = parse_h(a.h);
  const CriticalLoadMethod method = parse_critical_load_method(a.method);
  const EigenBackend backend = parse_eigen_backend(a.backend);
  SweepProgress progress(static_cast<long>(kernels.size() * hs.size() * forms.size()));
  const CriticalTensionSweep sweep{.n = nfree,
                                   .periodic = a.periodic,
                                   .direction = direction,
                                   .kernels = kernels,
                                   .hs = hs,
                                   .forms = forms,
                                   .correction = correction,
                                   .corrected = corrected,
                                   .method = method,
                                   .backend = backend,
                                   .corrected_layer_supports = kCorrectedLayerSupports,
                                   .memory_label =
                                       [&](double h) {
                                         return "tcrit: --n " + std::to_string(nfree) +
                                                " with h/dx = " + num(Kernel<1>(kernels[0]).support_radius(h) / 2);
                                       },
                                   .on_case = [&] { progress.case_done(); }};
  const std::vector<CriticalTensionCase> cases = critical_tension_sweep(sweep);

  // Rows are collected first so that an error on any row leaves stdout empty (one error line, exit 1). Corrected
  // routes have no closed-form estimates or symbols (NaN) and fixed layers (periodic 0).
  std::string out =
      "kernel,form,N,periodic,h_over_dx,method,backend,tcrit,tcrit_eig,tcrit_bisect,rel_diff,t_first_minor,"
      "t_second_minor,t_nn,t_nn_minor,t_swegle,tcrit_infinite,tcrit_symbol,mode_k_over_pi,status,reason,criterion\n";
  const double nan = CriticalLoad::nan;
  for (const CriticalTensionCase& c : cases) {
    const CriticalLoad& r = c.result;
    TensionEstimates1D e;
    e.first_minor = e.second_minor = e.nearest_neighbour = e.nearest_neighbour_minor = e.swegle = nan;
    if (c.estimates) e = *c.estimates;
    out += csv_line({kernel_name(c.kernel),
                     momentum_form_name(c.form),
                     std::to_string(nfree),
                     a.periodic && correction == Correction::None ? "1" : "0",
                     num(c.h),
                     a.method,
                     c.backend,
                     num(r.load),
                     num(r.load_eigen),
                     num(r.load_bisection),
                     num(r.relative_difference),
                     num(e.first_minor),
                     num(e.second_minor),
                     num(e.nearest_neighbour),
                     num(e.nearest_neighbour_minor),
                     num(e.swegle),
                     num(c.infinite),
                     num(c.symbol),
                     num(c.mode_k_over_pi),
                     status_name(r.status),
                     c.reason,
                     c.criterion});
  }
  std::fputs(out.c_str(), stdout);
}

}  // namespace

void register_tcrit_command(CLI::App& app) {
  auto args = std::make_shared<TcritArgs>();
  auto* cmd = app.add_subcommand(
      "tcrit",
      "Critical tension T_crit of a 1D lattice (smallest T > 0 with A(T) = K - n T L not "
      "positive definite, Powell 3.40) with the estimates 3.42/3.49/3.43/3.51/Swegle; with "
      "--correction, of the corrected forms (criterion pd, or real-positive-spectrum and "
      "symmetric-part-pd when A is not symmetric); with --dim 2 the critical PRE-STRAIN e_crit of a 2D lattice (column "
      "ecrit; signed: < 0 with --compression) from the analytic Jacobian A(e) = A0 + e A1; with --dim 3 that of a "
      "cubic "
      "lattice, matrix-free; CSV");
  cmd->add_option("--dim", args->dim, "Dimension (1, 2, or 3: cubic lattice, --method lobpcg only)");
  cmd->add_option("--lattice", args->lattice, "Lattice: line (1D); square, hex, face-centred (2D; default square)")
      ->each([args](const std::string&) { args->lattice_given = true; });
  cmd->add_option("--n", args->n,
                  "Number of FREE particles (2D: per side); fixed layers are added to complete neighbourhoods");
  cmd->add_option("--kernel", args->kernel, "Kernel name or comma list (see `sphstab kernels`)");
  cmd->add_option("--form", args->form, "uncorrected|plus|minus|conservative, or a comma list");
  cmd->add_option("--h", args->h, "h/dx: value, comma list or a:b:step (support radius 2h)");
  cmd->add_option("--method", args->method,
                  "eig|bisect|both (default both); --dim 2: also lobpcg, the matrix-free preconditioned block LOBPCG "
                  "for large square blocks (results/critical-strain-large); --dim 3: lobpcg only (the default)")
      ->each([args](const std::string&) { args->method_given = true; });
  cmd->add_option("--route", args->route,
                  "--dim 2/3: auto|assembled|matrix-free|symbol|petsc (critical_load_problem.hpp; auto: periodic -> "
                  "symbol, 3D -> matrix-free, 2D -> assembled unless it exceeds the memory limit, then matrix-free; "
                  "petsc: the PETSc/SLEPc backend when built with it). Default: --method lobpcg -> matrix-free, "
                  "--periodic -> symbol, else assembled (2D) or matrix-free (3D)")
      ->each([args](const std::string&) { args->route_given = true; });
  cmd->add_option("--backend", args->backend, "Eigen route: auto|dense|spectra (auto: dense up to 200 DOF)");
  cmd->add_option("--correction", args->correction,
                  "1D kernel correction: none|minus|shepard|column-shepard|ncsph|local-polish|mean-polish|"
                  "shepard-column-polish (not none: A(T) = A0 + T A1 by complex step, fixed layers 3 supports thick)");
  cmd->add_option("--corrected-operator", args->corrected,
                  "With a correction: auto|divergence|strain|both (auto: divergence, strain for conservative)");
  cmd->add_flag("--compression", args->compression,
                "Critical compression: the largest T < 0 (2D: e < 0) at which the criterion fails (reported negative)");
  cmd->add_flag("--periodic", args->periodic,
                "Periodic lattice (1D: translation, and the sawtooth for even N, deflated; 2D: exact Fourier symbols)");
  cmd->add_option("--prestrain", args->prestrain, "2D: isotropic|uniaxial (uniaxial along x, plane strain)")
      ->each([args](const std::string&) { args->prestrain_given = true; });
  cmd->add_option("--lambda", args->lambda, "2D: Lame lambda (default 1.2115: E = 2.1, nu = 0.3)")
      ->each([args](const std::string&) { args->lame_given = true; });
  cmd->add_option("--mu", args->mu, "2D: shear modulus mu (default 0.8077: E = 2.1, nu = 0.3)")
      ->each([args](const std::string&) { args->lame_given = true; });
  cmd->add_option("--criterion", args->criterion,
                  "2D: auto|definiteness|spectrum|symmetric-part (auto: definiteness for symmetric A, the dense "
                  "eigenvalue criterion for non-symmetric A up to 1200 DOF, else symmetric-part)")
      ->each([args](const std::string&) { args->criterion_given = true; });
  cmd->callback([args] { run_tcrit(*args); });
}

}  // namespace sphstab::cli
