// `sphstab tcrit`: critical tension of a 1D lattice (Powell ch. 3) with the closed-form estimates, as CSV.
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "sphstab/forms/momentum_form.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_tension.hpp"
#include "sphstab/stability/fourier_symbol.hpp"
#include "sphstab/stability/tension_estimates.hpp"

namespace sphstab::cli {

namespace {

struct TcritArgs {
  std::string dim = "1", lattice = "line", n = "30", kernel = "cubic", form = "conservative", h = "1.2",
              method = "both", backend = "auto", correction = "none";
  bool periodic = false;
};

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
  if (a.correction != "none")
    throw std::invalid_argument("tcrit: --correction '" + a.correction +
                                "' is not available yet (valid: none)");  // hook for kernel corrections
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
      "t_second_minor,t_nn,t_nn_minor,t_swegle,tcrit_infinite,tcrit_symbol,mode_k_over_pi,status,reason\n";
  for (KernelType type : kernels) {
    Kernel<1> kernel(type);
    for (double h : hs) {
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, nfree, a.periodic);
      const TensionJacobian1d jac = analytic_jacobian_1d(set, kernel, h);
      for (MomentumForm form : forms) {
        const int n = initial_stress_multiplier(form);
        const CriticalTension r = critical_tension(jac, n, opt);
        const TensionEstimates1d e = tension_estimates_1d(kernel, h, 1.0, n);
        const SymbolCriticalTension inf = critical_tension_infinite_1d(kernel, h, 1.0, n);
        const double symbol =
            a.periodic ? critical_tension_periodic_symbol_1d(kernel, h, 1.0, nfree, n).tcrit : CriticalTension::nan;
        const std::vector<std::string> row{kernel_name(type),
                                           momentum_form_name(form),
                                           std::to_string(nfree),
                                           a.periodic ? "1" : "0",
                                           num(h),
                                           a.method,
                                           r.eigen_backend.empty() ? "none" : r.eigen_backend,
                                           num(r.tcrit),
                                           num(r.tcrit_eigen),
                                           num(r.tcrit_bisection),
                                           num(r.relative_difference),
                                           num(e.first_minor),
                                           num(e.second_minor),
                                           num(e.nearest_neighbour),
                                           num(e.nearest_neighbour_minor),
                                           num(e.swegle),
                                           num(inf.tcrit),
                                           num(symbol),
                                           num(r.mode_wavenumber.k_projection),
                                           status_name(r.status),
                                           csv_field(r.reason)};
        for (size_t c = 0; c < row.size(); ++c) out += (c ? "," : "") + row[c];
        out += "\n";
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
                                 "positive definite, Powell 3.40) with the estimates 3.42/3.49/3.43/3.51/Swegle; CSV");
  cmd->add_option("--dim", args->dim, "Dimension (1; 2 is not yet supported)");
  cmd->add_option("--lattice", args->lattice, "Lattice (line)");
  cmd->add_option("--n", args->n, "Number of FREE particles (fixed layers are added to complete neighbourhoods)");
  cmd->add_option("--kernel", args->kernel, "Kernel name or comma list (see `sphstab kernels`)");
  cmd->add_option("--form", args->form, "uncorrected|plus|minus|conservative, or a comma list");
  cmd->add_option("--h", args->h, "h/dx: value, comma list or a:b:step (support radius 2h)");
  cmd->add_option("--method", args->method, "eig|bisect|both (default both)");
  cmd->add_option("--backend", args->backend, "Eigen route: auto|dense|spectra (auto: dense up to 200 DOF)");
  cmd->add_option("--correction", args->correction, "Kernel correction (none; others not yet available)");
  cmd->add_flag("--periodic", args->periodic, "Periodic lattice (translation, and the sawtooth for even N, deflated)");
  cmd->callback([args] { run_tcrit(*args); });
}

}  // namespace sphstab::cli
