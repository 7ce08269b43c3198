// `sphstab tcrit`: critical tension of a 1D lattice (Powell ch. 3) with the closed-form estimates, as CSV; with
// --correction, of the 1D forms with a corrected kernel gradient (Powell ch. 3 §4.1.1, ch. 4 §2) by the general
// affine route (affine_critical_tension.hpp).
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/affine_critical_tension.hpp"
#include "sphstab/stability/critical_tension.hpp"
#include "sphstab/stability/fourier_symbol.hpp"
#include "sphstab/stability/tension_estimates.hpp"

namespace sphstab::cli {

namespace {

struct TcritArgs {
  std::string dim = "1", lattice = "line", n = "30", kernel = "cubic", form = "conservative", h = "1.2",
              method = "both", backend = "auto", correction = "none", corrected = "auto";
  bool periodic = false, compression = false;
};

/// Fixed layers of the lattice used with a kernel correction, in kernel supports (2h): every particle that the free
/// particles' corrected rows read then has a complete neighbourhood, so u = 0 is an equilibrium of every form and
/// correction (Powell's regular grid, ch. 3 footnote h); checked by the residual in `reason`.
constexpr int kCorrectedLayerSupports = 3;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) out.push_back(item);
  return out;
}

double parse_double(const std::string& s, const std::string& what) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v))
    throw std::invalid_argument("tcrit: " + what + " must be a finite number (got '" + s + "')");
  return v;
}

int parse_positive_int(const std::string& s, const std::string& what) {
  size_t used = 0;
  long v = 0;
  try {
    v = std::stol(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || v < 1 || v > 100000000)
    throw std::invalid_argument("tcrit: " + what + " must be a positive integer (got '" + s + "')");
  return static_cast<int>(v);
}

/// "a", "a,b,c" or "a:b:step" (inclusive, values snapped to 12 significant digits).
std::vector<double> parse_h(const std::string& spec) {
  std::vector<double> hs;
  const auto range = split(spec, ':');
  if (range.size() == 3) {
    const double a = parse_double(range[0], "--h start"), b = parse_double(range[1], "--h end"),
                 s = parse_double(range[2], "--h step");
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
    for (const auto& item : split(spec, ',')) hs.push_back(parse_double(item, "--h"));
  } else {
    throw std::invalid_argument("tcrit: --h must be a value, a comma list or a:b:step (got '" + spec + "')");
  }
  if (hs.empty()) throw std::invalid_argument("tcrit: --h is empty");
  for (double h : hs)
    if (!(h > 0)) throw std::invalid_argument("tcrit: --h values must be > 0 (got " + std::to_string(h) + ")");
  return hs;
}

std::string num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return buf;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void run_tcrit(const TcritArgs& a) {
  // Validate everything before printing anything.
  const int dim = parse_positive_int(a.dim, "--dim");
  if (dim == 2 || dim == 3)
    throw std::invalid_argument("tcrit: --dim " + a.dim + " is not yet supported (only --dim 1)");
  if (dim != 1) throw std::invalid_argument("tcrit: --dim must be 1 (got '" + a.dim + "')");
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
  for (const auto& k : split(a.kernel, ',')) kernels.push_back(parse_kernel_type(k));
  std::vector<MomentumForm> forms;
  for (const auto& f : split(a.form, ',')) forms.push_back(parse_momentum_form(f));
  if (kernels.empty() || forms.empty()) throw std::invalid_argument("tcrit: --kernel and --form must not be empty");
  const std::vector<double> hs = parse_h(a.h);
  CriticalTensionOptions opt;
  opt.method = parse_tcrit_method(a.method);
  opt.backend = parse_eigen_backend(a.backend);
  opt.want_mode = opt.method != TcritMethod::Bisection;

  // Rows are collected first so that an error on any row leaves stdout empty (one error line, exit 1).
  std::string out =
      "kernel,form,N,periodic,h_over_dx,method,backend,tcrit,tcrit_eig,tcrit_bisect,rel_diff,t_first_minor,"
      "t_second_minor,t_nn,t_nn_minor,t_swegle,tcrit_infinite,tcrit_symbol,mode_k_over_pi,status,reason,criterion\n";
  auto add_row = [&out](const std::vector<std::string>& row) {
    for (size_t c = 0; c < row.size(); ++c) out += (c ? "," : "") + row[c];
    out += "\n";
  };
  const double nan = CriticalTension::nan;
  for (KernelType type : kernels) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      if (correction == Correction::None) {
        // Plain kernel: the analytic Jacobian K - n T L (Powell 3.40) and the closed-form estimates.
        const ParticleSet<1> set = tension_lattice_1d(kernel, h, nfree, a.periodic);
        TensionJacobian1d jac = analytic_jacobian_1d(set, kernel, h);
        if (a.compression) jac.L = SparseMatrix<>(-jac.L);  // A(T) = K + |T| n L for T < 0
        const double sign = a.compression ? -1.0 : 1.0;
        for (MomentumForm form : forms) {
          const int n = initial_stress_multiplier(form);
          const CriticalTension r = critical_tension(jac, n, opt);
          const TensionEstimates1d e = tension_estimates_1d(kernel, h, 1.0, n);
          const SymbolCriticalTension inf = critical_tension_infinite_1d(kernel, h, 1.0, n);
          const double symbol =
              a.periodic && !a.compression ? critical_tension_periodic_symbol_1d(kernel, h, 1.0, nfree, n).tcrit : nan;
          const bool t = !a.compression;  // the estimates are tension formulas
          add_row({kernel_name(type),
                   momentum_form_name(form),
                   std::to_string(nfree),
                   a.periodic ? "1" : "0",
                   num(h),
                   a.method,
                   r.eigen_backend.empty() ? "none" : r.eigen_backend,
                   num(sign * r.tcrit),
                   num(sign * r.tcrit_eigen),
                   num(sign * r.tcrit_bisection),
                   num(r.relative_difference),
                   num(t ? e.first_minor : nan),
                   num(t ? e.second_minor : nan),
                   num(t ? e.nearest_neighbour : nan),
                   num(t ? e.nearest_neighbour_minor : nan),
                   num(t ? e.swegle : nan),
                   num(t ? inf.tcrit : nan),
                   num(symbol),
                   num(r.mode_wavenumber.k_projection),
                   status_name(r.status),
                   csv_field(a.compression ? "compression: T < 0 searched as K + |T| n L; " + r.reason : r.reason),
                   criterion_name(StabilityCriterion::PositiveDefinite)});
        }
        continue;
      }
      // Corrected kernel: complex-step A(T) = A0 + T A1 of the force function, then the general criteria.
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, nfree, false, kCorrectedLayerSupports);
      auto disc = make_discretisation(set, kernel, h);
      Eigen::VectorXd x(disc->free_count());
      for (int f = 0; f < disc->free_count(); ++f) x[f] = set.x(disc->free[f], 0);
      const auto provider = make_gradient_provider<1>(correction);
      AffineCriticalOptions aopt;
      aopt.symmetric = opt;
      for (MomentumForm form : forms) {
        WaveForm1D force(disc, form, 0.0, provider, {.corrected = corrected});
        const ForceCriticalLoad load = critical_load(force, direction, x, aopt);
        std::string note = "corrected " + force.name().substr(force.name().rfind('/') + 1) + "; fixed layers " +
                           std::to_string(kCorrectedLayerSupports) + " supports";
        if (load.residual_relative > 1e-10)
          note += "; WARNING u = 0 is not an equilibrium (max|a(0)|/max|A0| = " + num(load.residual_relative) + ")";
        for (const AffineCriticalTension& r : load.results) {
          const bool pd = r.criterion != StabilityCriterion::RealPositiveSpectrum;
          const double sign = a.compression ? -1.0 : 1.0;
          const std::string backend =
              pd ? (r.pd.eigen_backend.empty() ? "none" : r.pd.eigen_backend) : std::string("dgeev");
          add_row({kernel_name(type),
                   momentum_form_name(form),
                   std::to_string(nfree),
                   "0",
                   num(h),
                   a.method,
                   backend,
                   num(r.tcrit),
                   num(pd ? sign * r.pd.tcrit_eigen : nan),
                   num(pd ? sign * r.pd.tcrit_bisection : r.tcrit),
                   num(pd ? r.pd.relative_difference : nan),
                   num(nan),
                   num(nan),
                   num(nan),
                   num(nan),
                   num(nan),
                   num(nan),
                   num(nan),
                   num(r.mode_wavenumber.k_projection),
                   status_name(r.status),
                   csv_field(note + "; " + r.reason),
                   criterion_name(r.criterion)});
        }
      }
    }
  }
  std::fputs(out.c_str(), stdout);
}

}  // namespace

void register_tcrit_command(CLI::App& app) {
  auto args = std::make_shared<TcritArgs>();
  auto* cmd = app.add_subcommand("tcrit",
                                 "Critical tension T_crit of a 1D lattice (smallest T > 0 with A(T) = K - n T L not "
                                 "positive definite, Powell 3.40) with the estimates 3.42/3.49/3.43/3.51/Swegle; with "
                                 "--correction, of the corrected forms (criterion pd, or real-positive-spectrum and "
                                 "symmetric-part-pd when A is not symmetric); CSV");
  cmd->add_option("--dim", args->dim, "Dimension (1; 2 is not yet supported)");
  cmd->add_option("--lattice", args->lattice, "Lattice (line)");
  cmd->add_option("--n", args->n, "Number of FREE particles (fixed layers are added to complete neighbourhoods)");
  cmd->add_option("--kernel", args->kernel, "Kernel name or comma list (see `sphstab kernels`)");
  cmd->add_option("--form", args->form, "uncorrected|plus|minus|conservative, or a comma list");
  cmd->add_option("--h", args->h, "h/dx: value, comma list or a:b:step (support radius 2h)");
  cmd->add_option("--method", args->method, "eig|bisect|both (default both)");
  cmd->add_option("--backend", args->backend, "Eigen route: auto|dense|spectra (auto: dense up to 200 DOF)");
  cmd->add_option("--correction", args->correction,
                  "Kernel correction: none|minus|shepard|column-shepard|ncsph|local-polish|mean-polish|"
                  "shepard-column-polish (not none: A(T) = A0 + T A1 by complex step, fixed layers 3 supports thick)");
  cmd->add_option("--corrected-operator", args->corrected,
                  "With a correction: auto|divergence|strain|both (auto: divergence, strain for conservative)");
  cmd->add_flag("--compression", args->compression,
                "Critical compression: the largest T < 0 at which the criterion fails (reported negative)");
  cmd->add_flag("--periodic", args->periodic, "Periodic lattice (translation, and the sawtooth for even N, deflated)");
  cmd->callback([args] { run_tcrit(*args); });
}

}  // namespace sphstab::cli
