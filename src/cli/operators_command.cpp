// `sphstab operators`: assemble W, G (and H) on a lattice, apply a kernel correction, write Matrix Market files.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "commands.hpp"
#include "parse.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/io/matrix_market.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab::cli {

namespace {

struct OperatorsArgs {
  int dim = 0;
  std::string lattice;
  int n = 0;
  std::string kernel = "cubic";
  double h_over_dx = std::numeric_limits<double>::quiet_NaN();
  double dx = 1.0;
  std::string correction = "none";
  std::string counting = "actual";
  bool first_step_shepard = false;
  bool polish_free = false;
  bool periodic = false;
  int fixed_layers = -1;
  double perturb = 0.0;
  std::string seed = "1";
  bool hessian = false;
  std::string out;
};

constexpr long kMaxDenseParticles = 5000;  // dense polishes write N^2 entries
const char* const kAxis[3] = {"x", "y", "z"};

int lattice_dimension(LatticeType t) {
  switch (t) {
    case LatticeType::Line:
      return 1;
    case LatticeType::Cubic:
      return 3;
    default:
      return 2;
  }
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

void require_finite(double v, bool positive, const char* option) {
  if (!std::isfinite(v) || (positive ? !(v > 0) : !(v >= 0)))
    throw std::invalid_argument(std::string(option) + " must be finite and " + (positive ? "> 0" : ">= 0") + " (got " +
                                number(v) + ")");
}

double max_abs(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

template <int Dim>
void write_particles(const std::string& path, const ParticleSet<Dim>& p) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot open '" + path + "' for writing");
  std::fprintf(f, "index");
  for (int a = 0; a < Dim; ++a) std::fprintf(f, ",%s", kAxis[a]);
  std::fprintf(f, ",volume,role,depth\n");
  for (int i = 0; i < p.size(); ++i) {
    std::fprintf(f, "%d", i);
    for (int a = 0; a < Dim; ++a) std::fprintf(f, ",%.17g", p.x(i, a));
    std::fprintf(f, ",%.17g,%s,%d\n", p.volume[i], p.role[i] == Role::Free ? "free" : "fixed", p.depth[i]);
  }
  const bool ok = !std::ferror(f);
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("error writing '" + path + "'");
}

template <int Dim>
void run(const OperatorsArgs& args, const std::string& command_line) {
  const LatticeType type = parse_lattice_type(args.lattice);
  if (lattice_dimension(type) != Dim)
    throw std::invalid_argument("--lattice " + lattice_name(type) + " needs --dim " +
                                std::to_string(lattice_dimension(type)) + " (got --dim " + std::to_string(Dim) + ")");
  if (args.n <= 0) throw std::invalid_argument("--n must be > 0 (got " + std::to_string(args.n) + ")");
  require_finite(args.h_over_dx, true, "--h");
  check_length(args.dx, "--dx");
  check_length(args.h_over_dx * args.dx, "smoothing length h = --h x --dx");
  require_finite(args.perturb, false, "--perturb");
  if (args.fixed_layers < -1)
    throw std::invalid_argument("--fixed-layers must be >= 0, or -1 for as many as the support needs (got " +
                                std::to_string(args.fixed_layers) + ")");
  if (args.periodic && args.fixed_layers > 0)
    throw std::invalid_argument("--fixed-layers " + std::to_string(args.fixed_layers) +
                                " does not apply to --periodic (a periodic lattice has no fixed layers)");
  const Correction correction = parse_correction(args.correction);
  const NeighbourCounting counting = parse_neighbour_counting(args.counting);
  const Kernel<Dim> kernel(parse_kernel_type(args.kernel));
  const double h = args.h_over_dx * args.dx;

  LatticeOptions lopt;
  lopt.spacing = args.dx;
  lopt.fixed_layers = args.fixed_layers;
  lopt.support_radius = kernel.support_radius(h);
  lopt.periodic = args.periodic;
  lopt.perturbation = args.perturb;
  lopt.seed = parse_unsigned(args.seed, "--seed");
  const ParticleSet<Dim> set = make_lattice<Dim>(type, args.n, lopt);
  if (correction_is_dense(correction) && set.size() > kMaxDenseParticles)
    throw std::invalid_argument("--correction " + correction_name(correction) + " is dense (N^2 entries); N = " +
                                std::to_string(set.size()) + " exceeds " + std::to_string(kMaxDenseParticles));
  const NeighbourList nl = find_neighbours(set, kernel.support_radius(h));
  const Operators<Dim, double> ops =
      assemble_operators<Dim, double>(set, nl, kernel, h, {.kernel = true, .gradient = true, .hessian = args.hessian});

  CorrectionOptions<Dim> copt;
  copt.counting = counting;
  copt.polish_free_only = args.polish_free;
  std::array<ShepardReference, Dim> reference;
  if (args.first_step_shepard) {
    for (int a = 0; a < Dim; ++a) reference[a] = shepard_reference(ops.W, ops.G[a]);
    copt.reference = &reference;
  }
  // Called for "none" too, so that options which do not apply to the correction are rejected.
  const std::array<SparseMatrix<>, Dim> corrected = apply_correction<Dim, double>(correction, set, nl, ops, copt);

  // All computed: now write.
  std::filesystem::path out(args.out);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out))
    throw std::runtime_error("cannot create output directory '" + args.out + "'");
  const std::string header = "written by: " + command_line + "\nrow i = particle i (particles.csv index + 1)";
  write_particles((out / "particles.csv").string(), set);
  write_matrix_market((out / "W.mtx").string(), ops.W, header + "\nW_ij = W(|x_i - x_j|, h) V_j");
  std::printf(
      "sphstab operators: %d-D %s lattice, n = %d: %d particles (%d free), h = %g, kernel %s, %ld stored "
      "entries per operator\n",
      Dim, lattice_name(type).c_str(), args.n, set.size(), set.count(Role::Free), h, kernel_name(kernel.type()).c_str(),
      static_cast<long>(nl.nonzeros()));
  std::printf("file,nonzeros_stored,max_abs_row_sum,max_abs_column_sum\n");
  auto report = [&](const std::string& name, const SparseMatrix<>& m) {
    Eigen::VectorXd ones = Eigen::VectorXd::Ones(m.cols());
    Eigen::VectorXd rows = m * ones;
    Eigen::VectorXd cols = SparseMatrix<>(m.transpose()) * Eigen::VectorXd::Ones(m.rows());
    std::printf("%s,%ld,%.3e,%.3e\n", name.c_str(), static_cast<long>(m.nonZeros()), max_abs(rows), max_abs(cols));
  };
  report("W.mtx", ops.W);
  for (int a = 0; a < Dim; ++a) {
    const std::string g = std::string("G_") + kAxis[a] + ".mtx";
    write_matrix_market((out / g).string(), ops.G[a],
                        header + "\nG_ij = dW(|x_i - x_j|, h)/dx_i^" + kAxis[a] + " V_j, G_ii = 0 (stored)");
    report(g, ops.G[a]);
  }
  if (correction != Correction::None)
    for (int a = 0; a < Dim; ++a) {
      const std::string g = "G_" + correction_name(correction) + "_" + kAxis[a] + ".mtx";
      write_matrix_market((out / g).string(), corrected[a],
                          header + "\ngradient matrix of axis " + kAxis[a] + " with correction " +
                              correction_name(correction) +
                              (correction_is_dense(correction) ? " (dense: all N^2 entries stored)" : ""));
      report(g, corrected[a]);
    }
  if (args.hessian)
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) {
        const std::string name = std::string("H_") + kAxis[a] + kAxis[b] + ".mtx";
        write_matrix_market((out / name).string(), ops.H[a][b],
                            header + "\nH_ij = d2W/dx_i^" + kAxis[a] + " dx_i^" + kAxis[b] + " V_j (i != j), H_ii = 0");
        report(name, ops.H[a][b]);
      }
  std::printf("wrote %s\n", out.string().c_str());
}

}  // namespace

void register_operators_command(CLI::App& app) {
  auto args = std::make_shared<OperatorsArgs>();
  auto* cmd = app.add_subcommand("operators",
                                 "Assemble W, G (and H) on a lattice, apply a kernel correction, write Matrix Market "
                                 "files and particles.csv");
  cmd->add_option("--dim", args->dim, "Dimension: 1, 2 or 3")->required();
  cmd->add_option("--lattice", args->lattice, "line (1D) | square | hex | face-centred (2D) | cubic (3D)")->required();
  cmd->add_option("--n", args->n, "Free particles per side (n^dim free particles)")->required();
  cmd->add_option("--kernel", args->kernel, "Kernel name (see `sphstab kernels`)")->capture_default_str();
  cmd->add_option("--h", args->h_over_dx, "Smoothing length h / dx (support radius 2h)")->required();
  cmd->add_option("--dx", args->dx, "Lattice spacing dx")->capture_default_str();
  cmd->add_option("--correction", args->correction,
                  "none | minus | shepard | column-shepard | ncsph | local-polish | mean-polish | "
                  "shepard-column-polish")
      ->capture_default_str();
  cmd->add_option("--counting", args->counting,
                  "local-polish neighbour counts: actual | boundary-level (Powell Fig. 4.3)")
      ->capture_default_str();
  cmd->add_flag("--first-step-shepard", args->first_step_shepard,
                "local-polish: take the means of the first-step Shepard gradient (Powell 4.18), reference = this "
                "configuration");
  cmd->add_flag("--polish-free", args->polish_free, "mean-polish: polish the free-free block only (N = free count)");
  cmd->add_flag("--periodic", args->periodic, "Periodic box, no fixed layers");
  cmd->add_option("--fixed-layers", args->fixed_layers, "Fixed layers around the free block (-1: enough for 2h)")
      ->capture_default_str();
  cmd->add_option("--perturb", args->perturb, "Random displacement of free particles, uniform in [-P, P] dx")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Seed of the perturbation")->capture_default_str();
  cmd->add_flag("--hessian", args->hessian, "Also write H_ab.mtx (a <= b)");
  cmd->add_option("--out", args->out, "Output directory (created)")->required();
  cmd->callback([args] {
    const std::string line =
        "sphstab operators --dim " + std::to_string(args->dim) + " --lattice " + args->lattice + " --n " +
        std::to_string(args->n) + " --kernel " + args->kernel + " --h " + number(args->h_over_dx) + " --dx " +
        number(args->dx) + " --correction " + args->correction + " --counting " + args->counting +
        (args->first_step_shepard ? " --first-step-shepard" : "") + (args->polish_free ? " --polish-free" : "") +
        (args->periodic ? " --periodic" : "") + " --fixed-layers " + std::to_string(args->fixed_layers) +
        " --perturb " + number(args->perturb) + " --seed " + args->seed;
    switch (args->dim) {
      case 1:
        run<1>(*args, line);
        break;
      case 2:
        run<2>(*args, line);
        break;
      case 3:
        run<3>(*args, line);
        break;
      default:
        throw std::invalid_argument("--dim must be 1, 2 or 3 (got " + std::to_string(args->dim) + ")");
    }
  });
}

}  // namespace sphstab::cli
