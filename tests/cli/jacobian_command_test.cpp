// `sphstab jacobian` in-process (cli_harness.hpp): the exported A0, A1 are the analytic Jacobians built here
// (round-trip exact), the dof map names the free particles and their positions, the exported rate-form J matches
// central differences of the scheme's rate, and bad input is one error line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "rate_form_args.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/matrix_market.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace sphstab {
namespace jacobian_command_test {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sphstab_jacobian_test_" + std::to_string(getpid())) / name;
}

test::CliOutcome run(const std::vector<std::string>& args, const std::string& tag) {
  return test::run_cli_in_child(args, scratch(tag) / "io", 2e9, 120);
}

void expect_equal(const SparseMatrix<>& a, const SparseMatrix<>& b, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  EXPECT_EQ(SparseMatrix<>(a - b).norm(), 0.0) << what;
  EXPECT_GT(a.norm(), 0.0) << what;
}

void expect_dof_map(const std::filesystem::path& dir, const Linearisation& lin, int dim) {
  const CsvTable t = read_csv((dir / "dofs.csv").string());
  ASSERT_EQ(static_cast<int>(t.rows.size()), lin.dofs());
  const std::vector<double> dof = t.numeric_column("dof"), particle = t.numeric_column("particle"),
                            x = t.numeric_column("x");
  for (int k = 0; k < lin.dofs(); ++k) {
    const int f = k / lin.dofs_per_particle;
    EXPECT_EQ(dof[k], k);
    EXPECT_EQ(particle[k], lin.free_index[f]);
    EXPECT_EQ(x[k], lin.x(f, 0));
    if (dim == 2) EXPECT_EQ(t.numeric_column("y")[k], lin.x(f, 1));
  }
}

TEST(JacobianCommand, ElasticExportsAreTheAnalyticJacobians) {
  {
    const std::filesystem::path dir = scratch("e2");
    const test::CliOutcome r = run({"jacobian", "elastic", "--out", dir.string(), "--n", "6", "--h", "1.5", "--lattice",
                                    "hex", "--prestrain", "uniaxial", "--form", "conservative"},
                                   "e2");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Kernel<2> kernel(KernelType::CubicSpline);
    const ElasticMaterial m = ElasticMaterial::from_lame(1.2115384615384615, 0.80769230769230769, 1.0);
    const Linearisation lin = analytic_jacobian_2d(
        *make_discretisation(strain_lattice_2d(LatticeType::Hexagonal, kernel, 1.5, 6), kernel, 1.5), m,
        MomentumForm::Conservative, PreStrainKind::UniaxialX);
    expect_equal(read_matrix_market((dir / "A0.mtx").string()), lin.A0, "2D A0");
    expect_equal(read_matrix_market((dir / "A1.mtx").string()), lin.A1, "2D A1");
    expect_dof_map(dir, lin, 2);
  }
  {
    const std::filesystem::path dir = scratch("e1");
    const test::CliOutcome r =
        run({"jacobian", "elastic", "--dim", "1", "--out", dir.string(), "--n", "12", "--form", "plus"}, "e1");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Kernel<1> kernel(KernelType::CubicSpline);
    const Linearisation lin =
        analytic_jacobian_1d(tension_lattice_1d(kernel, 1.3, 12), kernel, 1.3, MomentumForm::Plus);
    expect_equal(read_matrix_market((dir / "A0.mtx").string()), lin.A0, "1D A0");
    expect_equal(read_matrix_market((dir / "A1.mtx").string()), lin.A1, "1D A1");
    expect_dof_map(dir, lin, 1);
  }
}

TEST(JacobianCommand, RateFormJacobianMatchesCentralDifferences) {
  const std::filesystem::path dir = scratch("rf");
  const std::vector<std::string> scheme_args = {
      "--n", "4", "--xsph", "0.5", "--artificial-stress", "0.3", "--continuity", "divergence"};
  std::vector<std::string> args = {"jacobian", "rate-form", "--out", dir.string()};
  args.insert(args.end(), scheme_args.begin(), scheme_args.end());
  const test::CliOutcome r = run(args, "rf");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const SparseMatrix<> J = read_matrix_market((dir / "J.mtx").string());
  // The same scheme, from the command's own option parsing.
  cli::RateFormArgs a;
  a.n = "4", a.xsph = "0.5", a.artificial_stress = "0.3", a.continuity = "divergence";
  const cli::RateFormSetup s = cli::parse_rate_form_args(a, "test", false, 1, 1000, 1000);
  const auto disc = rate_form_block_discretisation<2>(cli::block_options(s, s.kernels.front(), s.h_over_dx.front()));
  const RateFormScheme<2> scheme(disc, s.material, s.options, s.material.density() / s.xi.front());
  ASSERT_EQ(J.rows(), scheme.size());
  const Eigen::VectorXd y = scheme.uniform_state();
  const Eigen::MatrixXd Jd(J);
  double worst = 0;
  for (int k = 0; k < scheme.size(); k += 7) {
    const double d = 1e-6 * std::max(1.0, std::abs(y[k]));
    Eigen::VectorXd yp = y, ym = y, fp, fm;
    yp[k] += d, ym[k] -= d;
    scheme.rate(yp, fp);
    scheme.rate(ym, fm);
    const Eigen::VectorXd col = (fp - fm) / (2 * d);
    worst = std::max(worst, (col - Jd.col(k)).norm() / std::max(Jd.col(k).norm(), 1e-300));
  }
  EXPECT_LT(worst, 1e-6);
  const CsvTable t = read_csv((dir / "state.csv").string());
  ASSERT_EQ(static_cast<Eigen::Index>(t.rows.size()), J.rows());
  const std::vector<double> index = t.numeric_column("index"), particle = t.numeric_column("particle");
  const std::vector<std::string> var = t.text_column("variable");
  for (std::size_t q = 0; q < t.rows.size(); ++q) {
    const int i = static_cast<int>(particle[q]);
    const int k = static_cast<int>(index[q]);
    if (var[q] == "x") EXPECT_EQ(k, scheme.position_offset(i));
    if (var[q] == "vy") EXPECT_EQ(k, scheme.velocity_offset(i) + 1);
    if (var[q] == "rho") EXPECT_EQ(k, scheme.density_offset(i));
    if (var[q] == "S_xy") EXPECT_EQ(k, scheme.stress_offset(i) + 2);
  }
  std::vector<double> sorted = index;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t q = 0; q < sorted.size(); ++q) EXPECT_EQ(sorted[q], static_cast<double>(q));  // every row once
}

TEST(JacobianCommand, RateFormMemoryIsEstimatedBeforeBuilding) {
  // Issue 36: `--max-memory 1M jacobian rate-form` built J anyway, and --n 1000 (~40 GB) started unannounced. The
  // refusal names its estimate of J's stored entries; it must bracket the count of the J that the same options write
  // (within [1, 2] x: generous enough to refuse before the pattern exists, tight enough to allow what fits).
  for (const std::vector<std::string>& options : {std::vector<std::string>{"--n", "8"},
                                                  {"--n", "7", "--xsph", "0.5"},
                                                  {"--n", "6", "--momentum", "ssph"},
                                                  {"--n", "6", "--momentum", "cij", "--h", "1.5"},
                                                  {"--dim", "1", "--n", "1000"}}) {
    std::vector<std::string> args = {"--max-memory", "1M", "jacobian", "rate-form", "--out", scratch("mem").string()};
    args.insert(args.end(), options.begin(), options.end());
    const test::CliOutcome refused = run(args, "mem");
    EXPECT_EQ(refused.exit_code, 1) << options[1];
    const auto at = refused.err.find("(about ");
    ASSERT_NE(at, std::string::npos) << refused.err;
    const double estimate = std::stod(refused.err.substr(at + 7));
    args.erase(args.begin(), args.begin() + 2);
    const test::CliOutcome made = run(args, "mem");
    ASSERT_EQ(made.exit_code, 0) << made.err;
    const double entries = static_cast<double>(read_matrix_market((scratch("mem") / "J.mtx").string()).nonZeros());
    EXPECT_GE(estimate, entries) << options[1] << " " << options.back();
    EXPECT_LE(estimate, 2 * entries) << options[1] << " " << options.back();
  }
}

TEST(JacobianCommand, BadInputIsOneLine) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"jacobian"}, "subcommand"},
      {{"jacobian", "elastic"}, "--out"},
      {{"jacobian", "elastic", "--out", "/proc/sphstab_no"}, "cannot create"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--h", "0"}, "--h"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--dim", "3"}, "--dim"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--form", "sideways"}, "sideways"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--prestrain", "shear"}, "pre-strain 'shear'"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--mu", "-1"}, "mu"},
      {{"jacobian", "rate-form", "--out", scratch("bad").string(), "--n", "0"}, "--n"},
      {{"jacobian", "rate-form", "--out", scratch("bad").string(), "--kernel", "box"}, "box"},
      // 2D options in 1D (issue 36: accepted and ignored before)
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--dim", "1", "--lattice", "hex"},
       "--lattice applies to --dim 2 only"},
      {{"jacobian", "elastic", "--out", scratch("bad").string(), "--dim", "1", "--lambda", "2"},
       "--lambda applies to --dim 2 only"},
  };
  test::expect_one_line_errors(cases, [](const std::vector<std::string>& args) { return run(args, "bad"); });
}

}  // namespace jacobian_command_test
}  // namespace sphstab
