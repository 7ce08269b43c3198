// `sphstab tcrit` end to end: CSV shape, agreement with the library, bad input handling.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/jacobian/matrix_free_linearisation.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/matrix_free_critical_load.hpp"

namespace sphstab {
namespace tcrit_command_test {

struct CliRun {
  int status = -1;
  std::string out;
};

/// Runs the CLI with `args`; stdout and stderr are captured together when `merge`.
CliRun run(const std::string& args, bool merge = false) {
  const std::string cmd = std::string(SPHSTAB_CLI) + " " + args + (merge ? " 2>&1" : " 2>/dev/null");
  CliRun r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int st = pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

std::vector<std::string> lines(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string line;
  while (std::getline(ss, line)) out.push_back(line);
  return out;
}

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

/// `args` fails with exit status 1 and exactly one line "sphstab: error: ...".
void expect_one_error_line(const std::string& args) {
  CliRun r = run(args, true);
  EXPECT_EQ(r.status, 1) << args;
  auto ls = lines(r.out);
  ASSERT_EQ(ls.size(), 1u) << args << ":\n" << r.out;
  EXPECT_EQ(ls[0].rfind("sphstab: error: ", 0), 0u) << args << ": " << ls[0];
}

TEST(TcritCommand, PrintsCsvAgreeingWithLibrary) {
  CliRun r = run("tcrit --dim 1 --lattice line --n 30 --kernel cubic --form conservative --h 0.8:3.0:0.05");
  ASSERT_EQ(r.status, 0);
  auto ls = lines(r.out);
  ASSERT_EQ(ls.size(), 1u + 45u);
  auto header = fields(ls[0]);
  for (const char* col : {"kernel", "form", "N", "h_over_dx", "tcrit", "t_first_minor", "t_second_minor", "t_nn",
                          "t_nn_minor", "t_swegle", "tcrit_infinite", "reason"})
    EXPECT_NE(std::find(header.begin(), header.end(), col), header.end()) << col;
  auto col = [&](const char* name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
  // Row h = 1.25 (index 9): compare with the library.
  auto row = fields(ls[1 + 9]);
  EXPECT_EQ(row[col("h_over_dx")], "1.25");
  Kernel<1> cubic(KernelType::CubicSpline);
  const CriticalLoad ref =
      critical_tension_1d(tension_lattice_1d(cubic, 1.25, 30), cubic, 1.25, MomentumForm::Conservative);
  EXPECT_NEAR(std::stod(row[col("tcrit")]) / ref.load, 1.0, 1e-11);  // printed with 12 significant digits
  EXPECT_NEAR(std::stod(row[col("t_first_minor")]), 0.104, 1e-12);
  EXPECT_EQ(row[col("N")], "30");
}

TEST(TcritCommand, MinusFormAndPeriodic) {
  CliRun r = run("tcrit --n 20 --kernel wendland-c2 --form minus --h 1.3");
  ASSERT_EQ(r.status, 0);
  auto ls = lines(r.out);
  ASSERT_EQ(ls.size(), 2u);
  EXPECT_NE(ls[1].find(",inf,"), std::string::npos);
  CliRun p = run("tcrit --n 40 --kernel cubic --h 1.0 --periodic --method eig");
  ASSERT_EQ(p.status, 0);
  auto pl = lines(p.out);
  ASSERT_EQ(pl.size(), 2u);
  EXPECT_NE(pl[1].find("sawtooth"), std::string::npos);
}

TEST(TcritCommand, NoNeighbourInsideTheSupportIsTheSameNumericalIssueForEveryRoute) {
  // h = 0.3 dx: support 0.6 dx, no pair interacts. Plain forms (minus included), a corrected form and 2D all give
  // nan with status numerical-issue (one engine), never inf or a "successful" value.
  for (const char* args : {"tcrit --n 30 --h 0.3 --form minus,plus",
                           "tcrit --n 30 --h 0.3 --form plus --correction shepard", "tcrit --dim 2 --n 6 --h 0.3"}) {
    CliRun r = run(args);
    ASSERT_EQ(r.status, 0) << args;
    const auto ls = lines(r.out);
    const auto header = fields(ls[0]);
    auto col = [&](const std::string& name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
    const std::string load = std::string(args).find("--dim 2") != std::string::npos ? "ecrit" : "tcrit";
    ASSERT_GE(ls.size(), 2u) << args;
    for (std::size_t i = 1; i < ls.size(); ++i) {
      const auto row = fields(ls[i]);
      EXPECT_EQ(row[col(load)], "nan") << args << ": " << ls[i];
      EXPECT_EQ(row[col("status")], "numerical-issue") << args << ": " << ls[i];
    }
  }
}

TEST(TcritCommand, CorrectionAddsCriterionColumn) {
  // Plain rows: criterion = definiteness.
  CliRun plain = run("tcrit --n 30 --kernel cubic --form conservative --h 1.25");
  ASSERT_EQ(plain.status, 0);
  auto pl = lines(plain.out);
  ASSERT_EQ(pl.size(), 2u);
  auto header = fields(pl[0]);
  ASSERT_EQ(header.back(), "criterion");
  auto col = [&](const char* name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
  EXPECT_EQ(fields(pl[1])[col("criterion")], "definiteness");
  Kernel<1> cubic(KernelType::CubicSpline);
  const CriticalLoad ref =
      critical_tension_1d(tension_lattice_1d(cubic, 1.25, 30), cubic, 1.25, MomentumForm::Conservative);
  EXPECT_NEAR(std::stod(fields(pl[1])[col("tcrit")]) / ref.load, 1.0, 1e-11);

  // Mean polish (Powell 3.64): no T dependence for any form, T_crit = inf; Shepard conservative (3.59): finite,
  // well inside (0, 0.01).
  CliRun polish =
      run("tcrit --n 30 --kernel cubic --form uncorrected,plus,minus,conservative --h 1.3 "
          "--correction mean-polish");
  ASSERT_EQ(polish.status, 0);
  auto ml = lines(polish.out);
  ASSERT_EQ(ml.size(), 5u);
  for (size_t i = 1; i < ml.size(); ++i) {
    auto row = fields(ml[i]);
    EXPECT_EQ(row[col("tcrit")], "inf") << ml[i];
    EXPECT_EQ(row[col("criterion")], "definiteness") << ml[i];
    EXPECT_EQ(row[col("status")], "successful") << ml[i];
  }
  CliRun shep = run("tcrit --n 30 --kernel cubic --form conservative --h 1.3 --correction shepard");
  ASSERT_EQ(shep.status, 0);
  auto sl = lines(shep.out);
  ASSERT_EQ(sl.size(), 2u);
  const double t = std::stod(fields(sl[1])[col("tcrit")]);
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.01);
  EXPECT_NE(sl[1].find("shepard@strain"), std::string::npos);
  // Compression with the plain kernel: reported as a negative number or -inf.
  CliRun comp = run("tcrit --n 30 --kernel cubic --form conservative --h 1.3 --compression");
  ASSERT_EQ(comp.status, 0);
  EXPECT_EQ(fields(lines(comp.out)[1])[col("tcrit")], "-inf");
}

TEST(TcritCommand, BadInputIsOneErrorLineAndExitOne) {
  for (const char* args :
       {"tcrit --n 0", "tcrit --n abc", "tcrit --kernel nope", "tcrit --form sideways", "tcrit --h 1:0.5:0.1",
        "tcrit --h -1", "tcrit --dim 4", "tcrit --method fast", "tcrit --correction bogus", "tcrit --lattice square",
        "tcrit --correction shepard --periodic", "tcrit --corrected-operator strain",
        "tcrit --correction shepard --corrected-operator sideways", "tcrit --bogus 3", "tcrit --n 3 --h 3.0 --periodic",
        "tcrit --prestrain uniaxial", "tcrit --dim 2 --corrected-operator strain",
        "tcrit --dim 3 --n 4 --corrected-operator strain"}) {
    expect_one_error_line(args);
  }
}

TEST(TcritCommand, TwoDimensionalCriticalPreStrain) {
  CliRun r =
      run("tcrit --dim 2 --lattice hex --n 10 --kernel cubic,wendland-c4 --form conservative,plus --h 1.2:1.4:0.2 "
          "--prestrain uniaxial --compression");
  ASSERT_EQ(r.status, 0) << r.out;
  auto ls = lines(r.out);
  ASSERT_EQ(ls.size(), 1u + 2 * 2 * 2);
  auto header = fields(ls[0]);
  for (const char* c : {"kernel", "form", "N", "h_over_dx", "ecrit", "quantity", "ecrit_infinite", "mode_kx_over_pi",
                        "mode_ky_over_pi", "criterion", "mechanism", "reason"})
    EXPECT_NE(std::find(header.begin(), header.end(), c), header.end()) << c;
  auto col = [&](const char* name) { return std::find(header.begin(), header.end(), name) - header.begin(); };
  // Row: wendland-c4, h = 1.4, conservative (index 2 * 2 + 1 * 2 + 0 = 6).
  auto row = fields(ls[1 + 6]);
  ASSERT_EQ(row.size(), header.size());
  EXPECT_EQ(row[col("kernel")], "wendland-c4");
  EXPECT_EQ(row[col("form")], "conservative");
  EXPECT_EQ(row[col("h_over_dx")], "1.4");
  EXPECT_EQ(row[col("N")], "10");
  EXPECT_EQ(row[col("quantity")], "critical-prestrain");
  EXPECT_EQ(row[col("criterion")], "definiteness");
  Kernel<2> k(KernelType::WendlandC4);
  const ElasticMaterial nu03 = ElasticMaterial::from_lame(1.2115384615384615, 0.80769230769230769, 1.0);
  auto d = make_discretisation(strain_lattice_2d(LatticeType::Hexagonal, k, 1.4, 10), k, 1.4);
  const CriticalLoad ref =
      critical_load(analytic_jacobian_2d(*d, nu03, MomentumForm::Conservative, PreStrainKind::UniaxialX),
                    LoadDirection::Compression, CriticalLoadOptions::strain_2d());
  ASSERT_TRUE(std::isfinite(ref.load));
  EXPECT_NEAR(std::stod(row[col("ecrit")]) / ref.load, 1.0, 1e-11);  // 12 significant digits
  EXPECT_LT(std::stod(row[col("ecrit")]), 0.0);                      // compression: signed
  // The non-symmetric uniaxial plus form uses the dense eigenvalue criterion.
  auto plus = fields(ls[1 + 7]);
  EXPECT_EQ(plus[col("form")], "plus");
  EXPECT_EQ(plus[col("criterion")], "spectrum");
  // Periodic: exact symbol route; ecrit equals ecrit_symbol.
  CliRun p = run("tcrit --dim 2 --lattice square --n 9 --kernel cubic --h 1.3 --periodic");
  ASSERT_EQ(p.status, 0) << p.out;
  auto pl = lines(p.out);
  ASSERT_EQ(pl.size(), 2u);
  auto prow = fields(pl[1]);
  EXPECT_EQ(prow[col("method")], "symbol");
  EXPECT_EQ(prow[col("ecrit")], prow[col("ecrit_symbol")]);
  EXPECT_GT(std::stod(prow[col("ecrit")]), 0.0);
  // Minus form: inf.
  CliRun m = run("tcrit --dim 2 --n 6 --form minus --h 1.2");
  ASSERT_EQ(m.status, 0);
  EXPECT_EQ(fields(lines(m.out)[1])[col("ecrit")], "inf");
}

/// The value of column `name` in data row `row` of a CSV output.
std::string column(const std::string& out, const char* name, int row = 1) {
  const auto header = fields(lines(out)[0]);
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << name;
  return fields(lines(out)[row])[it - header.begin()];
}

/// Runs `common` with --method lobpcg and with --method eig (the assembled route): both succeed and e_crit agrees to
/// 1e-8 relative (or is the same infinity). Returns the lobpcg output.
std::string expect_lobpcg_matches_eig(const std::string& common) {
  CliRun a = run(common + "--method lobpcg");
  CliRun b = run(common + "--method eig");
  EXPECT_EQ(a.status, 0) << a.out;
  EXPECT_EQ(b.status, 0) << b.out;
  if (a.status != 0 || b.status != 0) return a.out;
  EXPECT_EQ(column(a.out, "method"), "lobpcg");
  EXPECT_EQ(column(a.out, "backend"), "matrix-free");
  EXPECT_EQ(column(a.out, "status"), "successful") << a.out;
  const double ea = std::stod(column(a.out, "ecrit")), eb = std::stod(column(b.out, "ecrit"));
  if (std::isfinite(eb))
    EXPECT_NEAR(ea / eb, 1.0, 1e-8) << a.out << b.out;
  else
    EXPECT_EQ(ea, eb) << a.out << b.out;
  return a.out;
}

TEST(TcritCommand, MatrixFreeLobpcgAgreesWithTheEigenRoute) {
  // --method lobpcg (matrix-free preconditioned block LOBPCG) against the default assembled eigen route, same block.
  const std::string out = expect_lobpcg_matches_eig("tcrit --dim 2 --n 14 --kernel cubic --form conservative --h 1.3 ");
  const double e = std::stod(column(out, "ecrit"));
  EXPECT_TRUE(std::isfinite(e) && e > 0) << out;
  for (const char* args :
       {"tcrit --dim 2 --n 14 --method lobpcg --periodic", "tcrit --dim 2 --n 14 --method lobpcg --lattice hex",
        "tcrit --dim 2 --n 14 --method lobpcg --backend dense",
        "tcrit --dim 2 --n 14 --method lobpcg --form plus --prestrain uniaxial"}) {
    expect_one_error_line(args);
  }
}

TEST(TcritCommand, LobpcgInCompressionFallsBackToNoPreconditioner) {
  // At h = 1.2 the square lattice has no interior instability in compression (no positive symbol ratio): the sine
  // preconditioner has no shift, so the block LOBPCG runs without it and must agree with the assembled eigen route.
  // (At h = 1.3 it has one, and the preconditioner is used.)
  const std::string out =
      expect_lobpcg_matches_eig("tcrit --dim 2 --n 12 --kernel cubic --form conservative --h 1.2 --compression ");
  EXPECT_NE(out.find("preconditioner none (symbol ratio"), std::string::npos) << out;
}

TEST(TcritCommand, ThreeDimensionalLobpcgAgreesWithTheUnpreconditionedIteration) {
  // --dim 3: cubic lattice, sine-preconditioned block LOBPCG; the reference is the same linearisation solved
  // in-process without a preconditioner and from a random start (another iteration path).
  CliRun a = run("tcrit --dim 3 --n 6 --kernel cubic --form conservative --h 1.3");
  ASSERT_EQ(a.status, 0) << a.out;
  EXPECT_EQ(column(a.out, "lattice"), "cubic");
  EXPECT_EQ(column(a.out, "method"), "lobpcg");
  EXPECT_EQ(column(a.out, "status"), "successful") << a.out;
  const Kernel<3> k(KernelType::CubicSpline);
  const auto disc =
      make_discretisation(make_lattice<3>(LatticeType::Cubic, 6, {.support_radius = k.support_radius(1.3)}), k, 1.3);
  const MatrixFreeLinearisation<3> lin(*disc, ElasticMaterial::from_lame(1.2115384615384615, 0.80769230769230769, 1),
                                       MomentumForm::Conservative, PreStrainKind::Isotropic);
  const MatrixFreeCriticalLoad ref = matrix_free_critical_load(lin, LoadDirection::Tension,
                                                               {.method = MatrixFreeEigenMethod::BlockLobpcg,
                                                                .residual_tol = 1e-9,
                                                                .max_iterations = 20000,
                                                                .preconditioner = MatrixFreePreconditioner::None,
                                                                .start = MatrixFreeStart::Random});
  ASSERT_EQ(ref.status, Status::Successful) << ref.reason;
  EXPECT_NEAR(std::stod(column(a.out, "ecrit")) / ref.load, 1.0, 1e-8);
  for (const char* args : {"tcrit --dim 3 --method eig", "tcrit --dim 3 --lattice square", "tcrit --dim 3 --periodic",
                           "tcrit --dim 3 --n 1", "tcrit --dim 3 --n 100000", "tcrit --dim 3 --h 0",
                           "tcrit --dim 3 --kernel nope", "tcrit --dim 4"}) {
    expect_one_error_line(args);
  }
}

TEST(TcritCommand, RouteNamesTheFrontDoorsRoute) {
  // --route matrix-free is --method lobpcg; --route assembled is the default route of a block with fixed layers.
  EXPECT_EQ(run("tcrit --dim 2 --n 14 --h 1.3 --route matrix-free").out,
            run("tcrit --dim 2 --n 14 --h 1.3 --method lobpcg").out);
  EXPECT_EQ(run("tcrit --dim 2 --n 10 --h 1.3 --route assembled").out, run("tcrit --dim 2 --n 10 --h 1.3").out);
  EXPECT_EQ(run("tcrit --dim 2 --n 9 --h 1.3 --periodic --route auto").out,
            run("tcrit --dim 2 --n 9 --h 1.3 --periodic").out);
  // auto: a block whose assembled route (~29 MB estimated) does not fit the limit goes matrix-free and says so; the
  // default (assembled) route refuses instead.
  CliRun a = run("--max-memory 30M tcrit --dim 2 --n 48 --h 1.3 --route auto");
  ASSERT_EQ(a.status, 0) << a.out;
  EXPECT_EQ(column(a.out, "method"), "lobpcg");
  EXPECT_EQ(column(a.out, "reason").rfind("\"fallback: the assembled route", 0), 0u) << a.out;
  expect_one_error_line("--max-memory 30M tcrit --dim 2 --n 48 --h 1.3");
  for (const char* args :
       {"tcrit --route assembled", "tcrit --dim 2 --method lobpcg --route assembled", "tcrit --dim 2 --route bogus",
        "tcrit --dim 2 --n 9 --periodic --route assembled", "tcrit --dim 2 --lattice hex --route matrix-free",
        "tcrit --dim 2 --route symbol", "tcrit --dim 3 --route symbol"})
    expect_one_error_line(args);
}

TEST(TcritCommand, PetscRouteAgreesWithTheAssembledEigenRoute) {
  CliRun p = run("tcrit --dim 2 --n 16 --h 1.3 --route petsc", true);
  if (p.status == 1 && p.out.find("SPHSTAB_WITH_PETSC") != std::string::npos)
    GTEST_SKIP() << "sphstab built without PETSc: " << p.out;
  ASSERT_EQ(p.status, 0) << p.out;
  CliRun e = run("tcrit --dim 2 --n 16 --h 1.3 --method eig");
  EXPECT_EQ(column(p.out, "backend"), "distributed");
  EXPECT_EQ(column(p.out, "status"), "successful") << p.out;
  // Shift-invert Krylov-Schur to a residual of 1e-10 (eigenvalue error ~1e-20) against Spectra's 1e-13; the
  // symmetrised matrices move e_crit by ~1e-11 (petsc_critical_load.hpp): 1e-9.
  EXPECT_NEAR(std::stod(column(p.out, "ecrit")) / std::stod(column(e.out, "ecrit")), 1.0, 1e-9);
}

TEST(TcritCommand, TwoDimensionalBadInput) {
  for (const char* args :
       {"tcrit --dim 2 --lattice line", "tcrit --dim 2 --prestrain shear", "tcrit --dim 2 --mu -1",
        "tcrit --dim 2 --lambda x", "tcrit --prestrain uniaxial", "tcrit --dim 2 --lattice hex --n 5 --periodic",
        "tcrit --dim 2 --n 3 --periodic --h 1.3", "tcrit --dim 2 --criterion nope", "tcrit --dim 2 --lattice cubic"}) {
    expect_one_error_line(args);
  }
}

}  // namespace
}  // namespace sphstab
