// Runs the built `sphstab operators` program (path in SPHSTAB_CLI) and reads its files back.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sphstab/io/matrix_market.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/operators/shepard.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace operators_command_test {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("sphstab_cli_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir.parent_path());
  return dir;
}

struct CliRun {
  int exit_code = -1;
  std::string out, err;
};

CliRun run_cli(const std::string& arguments, const fs::path& logs) {
  fs::create_directories(logs);
  const std::string cmd = std::string(SPHSTAB_CLI) + " " + arguments + " > " + (logs / "stdout").string() + " 2> " +
                          (logs / "stderr").string();
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::stringstream o, e;
  o << std::ifstream(logs / "stdout").rdbuf();
  e << std::ifstream(logs / "stderr").rdbuf();
  r.out = o.str();
  r.err = e.str();
  return r;
}

double max_diff(const SparseMatrix<>& a, const SparseMatrix<>& b) {
  return (Eigen::MatrixXd(a) - Eigen::MatrixXd(b)).cwiseAbs().maxCoeff();
}

TEST(OperatorsCommand, WritesOperatorsThatMatchTheLibrary) {
  fs::path out = scratch("square");
  CliRun r = run_cli(
      "operators --dim 2 --lattice square --n 4 --kernel wendland-c2 --h 1.3 --correction shepard "
      "--perturb 0.1 --seed 3 --hessian --out " +
          out.string(),
      scratch("square_logs"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;

  Kernel<2> k(KernelType::WendlandC2);
  auto set = make_lattice<2>(LatticeType::Square, 4,
                             {.spacing = 1.0, .support_radius = k.support_radius(1.3), .perturbation = 0.1, .seed = 3});
  auto nl = find_neighbours(set, k.support_radius(1.3));
  auto ops = assemble_operators<2, double>(set, nl, k, 1.3, {true, true, true});

  SparseMatrix<> w = read_matrix_market((out / "W.mtx").string());
  SparseMatrix<> gy = read_matrix_market((out / "G_y.mtx").string());
  SparseMatrix<> gs = read_matrix_market((out / "G_shepard_x.mtx").string());
  SparseMatrix<> hxy = read_matrix_market((out / "H_xy.mtx").string());
  ASSERT_EQ(w.rows(), set.size());
  EXPECT_EQ(w.nonZeros(), nl.nonzeros());  // the full pattern, explicit zeros included
  // %.17g: the files hold the library's doubles exactly.
  EXPECT_EQ(max_diff(w, ops.W), 0.0);
  EXPECT_EQ(max_diff(gy, ops.G[1]), 0.0);
  EXPECT_EQ(max_diff(hxy, ops.H[0][1]), 0.0);
  EXPECT_EQ(max_diff(gs, shepard_gradient(ops.W, ops.G[0])), 0.0);
  Eigen::VectorXd rows = gs * Eigen::VectorXd::Ones(gs.cols());
  EXPECT_LT(rows.cwiseAbs().maxCoeff(), 1e-13);  // Shepard gradient rows sum to zero (round-off)
  for (const char* f : {"G_x.mtx", "G_shepard_y.mtx", "H_xx.mtx", "H_yy.mtx"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out / "H_yx.mtx"));

  std::ifstream csv(out / "particles.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "index,x,y,volume,role,depth");
  std::getline(csv, line);
  EXPECT_EQ(line.substr(0, 2), "0,");
  EXPECT_NE(line.find(",free,"), std::string::npos) << line;
  int rows_read = 1;
  while (std::getline(csv, line)) ++rows_read;
  EXPECT_EQ(rows_read, set.size());
}

TEST(OperatorsCommand, DensePolishWritesEveryEntry) {
  fs::path out = scratch("polish");
  CliRun r = run_cli(
      "operators --dim 1 --lattice line --n 10 --h 1.3 --correction mean-polish --perturb 0.2 --out " + out.string(),
      scratch("polish_logs"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  SparseMatrix<> p = read_matrix_market((out / "G_mean-polish_x.mtx").string());
  EXPECT_EQ(p.nonZeros(), p.rows() * p.cols());
  Eigen::MatrixXd d(p);
  EXPECT_LT(d.rowwise().sum().cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(d.colwise().sum().cwiseAbs().maxCoeff(), 1e-12);
}

TEST(OperatorsCommand, BadInputGivesOneErrorLineAndExitCode1) {
  const std::string ok = " --out " + scratch("bad").string();
  const std::vector<std::string> bad = {
      "operators --dim 1 --lattice line --n 10 --h 0" + ok,
      "operators --dim 1 --lattice line --n 10 --h -1.3" + ok,
      "operators --dim 1 --lattice line --n 10 --h nan" + ok,
      "operators --dim 1 --lattice line --n 10 --h inf" + ok,
      "operators --dim 1 --lattice line --n 0 --h 1.3" + ok,
      "operators --dim 1 --lattice line --n -4 --h 1.3" + ok,
      "operators --dim 1 --lattice line --n abc --h 1.3" + ok,
      "operators --dim 1 --lattice line --n 10 --h 1.3 --kernel nosuch" + ok,
      "operators --dim 1 --lattice zigzag --n 10 --h 1.3" + ok,
      "operators --dim 1 --lattice line --n 10 --h 1.3 --correction shepherd" + ok,
      "operators --dim 1 --lattice square --n 10 --h 1.3" + ok,
      "operators --dim 4 --lattice line --n 10 --h 1.3" + ok,
      "operators --dim 1 --lattice line --n 10 --h 1.3 --perturb nan" + ok,
      "operators --dim 1 --lattice line --n 10 --h 1.3 --dx 0" + ok,
      "operators --dim 1 --lattice line --n 10 --h 1.3 --counting boundary-level" + ok,  // not local-polish
      "operators --dim 1 --lattice line --n 10 --h 0.3 --correction ncsph" + ok,         // singular NCSPH
      "operators --dim 2 --lattice hex --n 5 --h 1.3 --periodic" + ok,                   // odd periodic hex
      "operators --dim 1 --lattice line --n 10 --h 1.3",                                 // no --out
  };
  for (const std::string& args : bad) {
    CliRun r = run_cli(args, scratch("bad_logs"));
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("sphstab: error: ", 0), 0u) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    std::printf("%-80s -> %s", args.substr(0, args.find(" --out")).c_str(), r.err.c_str());
  }
  EXPECT_FALSE(fs::exists(scratch("bad").string() + "/W.mtx"));  // nothing written on error
  CliRun singular = run_cli("operators --dim 1 --lattice line --n 10 --h 0.3 --correction ncsph" + ok, scratch("s"));
  EXPECT_NE(singular.err.find("particle 0"), std::string::npos) << singular.err;
}

}  // namespace
}  // namespace sphstab
