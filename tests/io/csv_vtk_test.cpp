#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/run_output.hpp"
#include "sphstab/io/vtk.hpp"

namespace sphstab {
namespace csv_vtk_test {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& name) : path(fs::temp_directory_path() / name) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string file(const std::string& f) const { return (path / f).string(); }
};

TEST(Csv, RoundTripIsExactForNumbersAndText) {
  TempDir dir("sphstab_csv_test");
  const std::vector<double> values = {0.1,
                                      1.0 / 3.0,
                                      -2.5e-300,
                                      6.02214076e23,
                                      std::numeric_limits<double>::max(),
                                      std::numeric_limits<double>::denorm_min(),
                                      0.0,
                                      -0.0};
  {
    CsvWriter w(dir.file("a.csv"), {"name", "index", "value"});
    for (std::size_t k = 0; k < values.size(); ++k)
      w.row({std::string(k % 2 ? "plain" : "with, comma \"quoted\""), static_cast<long>(k), values[k]});
    w.row({std::string("special"), 99L, std::nan("")});
    w.row({std::string("inf"), -1L, -std::numeric_limits<double>::infinity()});
    EXPECT_THROW(w.row({1.0, 2.0}), std::invalid_argument);
  }
  auto t = read_csv(dir.file("a.csv"));
  ASSERT_EQ(t.columns, (std::vector<std::string>{"name", "index", "value"}));
  ASSERT_EQ(t.rows.size(), values.size() + 2);
  auto v = t.numeric_column("value");
  for (std::size_t k = 0; k < values.size(); ++k) {
    EXPECT_EQ(v[k], values[k]) << k;  // bit-exact round trip
    EXPECT_EQ(std::signbit(v[k]), std::signbit(values[k])) << k;
  }
  EXPECT_TRUE(std::isnan(v[values.size()]));
  EXPECT_EQ(v.back(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(t.text_column("name")[0], "with, comma \"quoted\"");
  EXPECT_EQ(t.numeric_column("index")[3], 3.0);
  EXPECT_THROW(t.numeric_column("name"), std::invalid_argument);
  EXPECT_THROW(t.column_index("missing"), std::invalid_argument);
}

TEST(Vtk, PolyDataRoundTripIn1D2D3D) {
  TempDir dir("sphstab_vtk_test");
  for (int d = 1; d <= 3; ++d) {
    const int n = 7;
    Eigen::MatrixXd x(n, d);
    Eigen::VectorXd u(n * d), s(n);
    for (int i = 0; i < n; ++i) {
      s[i] = std::exp(-0.3 * i) / 3.0;
      for (int a = 0; a < d; ++a) {
        x(i, a) = 0.1 * i + 1.0 / (a + 3.0);
        u[i * d + a] = std::sin(1.0 + i + 10 * a) * 1e-7;
      }
    }
    const std::string path = dir.file("snap" + std::to_string(d) + ".vtp");
    write_vtp(path, x, {{"displacement", d, u}, {"pressure", 1, s}});
    auto back = read_vtp(path);
    ASSERT_EQ(back.points.rows(), n);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) EXPECT_EQ(back.points(i, a), a < d ? x(i, a) : 0.0);
    const auto& f = back.field("displacement");
    EXPECT_EQ(f.components, d == 1 ? 1 : 3);  // vectors padded to 3 components for ParaView
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) EXPECT_EQ(f.values[i * f.components + a], u[i * d + a]);
    if (d == 2)
      for (int i = 0; i < n; ++i) EXPECT_EQ(f.values[i * 3 + 2], 0.0);
    EXPECT_EQ(back.field("pressure").values, s);
  }
  // Malformed files are rejected with a reason.
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(3, 2);
  write_vtp(dir.file("ok.vtp"), x, {});
  std::ifstream in(dir.file("ok.vtp"));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir.file("truncated.vtp")) << text.substr(0, text.size() - 20);
  EXPECT_THROW(read_vtp(dir.file("truncated.vtp")), std::runtime_error);
  std::string swapped = text;
  swapped.replace(swapped.find("</Points>"), 9, "</Verts>");
  std::ofstream(dir.file("swapped.vtp")) << swapped;
  EXPECT_THROW(read_vtp(dir.file("swapped.vtp")), std::runtime_error);
  EXPECT_THROW(write_vtp(dir.file("bad.vtp"), x, {{"u", 2, Eigen::VectorXd::Zero(5)}}), std::invalid_argument);
}

TEST(Vtk, LeapfrogSnapshotsAndCsvMatchTheFinalState) {
  TempDir dir("sphstab_snap_test");
  // Two independent 2D oscillators (one particle, Dim = 2) with reference position (1, 2).
  SecondOrderSystem s;
  s.dofs_per_particle = 2;
  s.acceleration = [](const Eigen::VectorXd& u, Eigen::VectorXd& a) { a = -u; };
  s.strain_energy = [](const Eigen::VectorXd& u) { return u.squaredNorm(); };  // M a = -dU/du with M = 2
  s.mass = Eigen::VectorXd::Constant(1, 2.0);
  s.reference_positions = Eigen::Vector2d(1.0, 2.0);
  LeapfrogOptions opt;
  opt.dt = 0.01;
  opt.max_steps = 100;
  opt.record_every = 10;
  opt.snapshot_every = 50;
  VtkSeries vtk(dir.file("osc"), s);
  DiagnosticsCsv csv(dir.file("osc.csv"), 2);
  opt.observers = {&vtk, &csv};
  auto r = run_leapfrog(s, Eigen::Vector2d(0.1, -0.2), Eigen::Vector2d(0.0, 0.05), opt);
  ASSERT_TRUE(r.completed()) << r.message;
  auto snap = read_vtp(dir.file("osc_000100.vtp"));
  EXPECT_EQ(snap.points(0, 0), 1.0 + r.u[0]);
  EXPECT_EQ(snap.points(0, 1), 2.0 + r.u[1]);
  EXPECT_EQ(snap.field("velocity").values[1], r.v[1]);
  EXPECT_TRUE(fs::exists(dir.file("osc.pvd")));
  auto t = read_csv(dir.file("osc.csv"));
  EXPECT_EQ(t.rows.size(), 11u);
  const auto& last = r.history.back();
  EXPECT_EQ(t.numeric_column("total").back(), last.total);
  EXPECT_EQ(t.numeric_column("momentum_y").back(), 2.0 * r.v[1]);
  EXPECT_NEAR(last.total, r.history.front().total, 1e-4 * last.total);  // leap-frog energy error <= (w dt)² = 1e-4
}

}  // namespace
}  // namespace sphstab
