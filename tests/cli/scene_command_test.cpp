// `sphstab scene` in-process (cli_harness.hpp): the printed series is the library's run of the same GMS scene set up
// independently here, a run that stops keeps its rows and VTK frames and ends with its status and particle (exit 0),
// and out-of-range scene parameters are one error line naming the option (exit 1).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_harness.hpp"
#include "sphstab/analysis/fragments.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/vtk.hpp"
#include "sphstab/problems/cantilever_plate.hpp"
#include "sphstab/problems/colliding_rings.hpp"
#include "sphstab/problems/powell_impact.hpp"

namespace sphstab {
namespace scene_command_test {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("sphstab_scene_test_" + std::to_string(getpid())) / name;
}

test::CliOutcome run(const std::vector<std::string>& args, const std::string& tag = "case") {
  return test::run_cli_in_child(args, scratch(tag), 2e9, 120);
}

const RateFormOptions kGms{.continuity = ContinuityForm::Divergence,
                           .xsph = 0.5,
                           .viscosity = ViscositySwitch::Compression,
                           .viscosity_alpha = 1,
                           .viscosity_beta = 2,
                           .artificial_stress = 0.3,
                           .pair_loop = PairLoop::Pairs};  // the command's default (auto: pairs for GMS's scheme)

TEST(SceneCommand, PlateSeriesIsTheLibrarysRun) {
  // GMS §7.1 at 4 across (dp = 0.5, h = 0.75), mu = 0.3, V_f = 0.02, dt = 0.5 h / c_P, skin 0.5 dp.
  const double L = 20, H = 2, vf = 0.02, dp = 0.5, h = 1.5 * dp;
  const ElasticMaterial mat = ElasticMaterial::from_bulk_shear(1, 0.3, 1);
  const RateFormScheme<2> scheme(make_discretisation(make_cantilever_plate({.length = L, .thickness = H, .across = 4}),
                                                     Kernel<2>(KernelType::CubicSpline), h),
                                 mat, kGms);
  Eigen::VectorXd y0 = scheme.uniform_state();
  const ParticleSet<2>& p = scheme.discretisation().particles;
  std::vector<int> tip;
  for (int i = 0; i < p.size(); ++i) {
    if (p.role[i] == Role::Free)
      scheme.set_velocity(y0, i, Eigen::Vector2d(0, cantilever_mode_velocity(p.x(i, 0), L, vf)));
    if (p.x(i, 0) > L - dp) tip.push_back(i);
  }
  std::vector<double> deflection;
  const RateFormRunResult direct = run_rate_form(scheme, y0,
                                                 {.dt = 0.5 * h / mat.p_wave_speed(),
                                                  .t_end = 150,
                                                  .record_every = 40,
                                                  .observer =
                                                      [&](long, double, const Eigen::VectorXd& y) {
                                                        const Eigen::Matrix2Xd x = rate_form_positions(scheme, y);
                                                        double u = 0;
                                                        for (int i : tip) u += x(1, i) - p.x(i, 1);
                                                        deflection.push_back(u / static_cast<double>(tip.size()));
                                                      },
                                                  .reuse_corrector_rate = true,  // the plate's default: pc1
                                                  .neighbour_skin = 0.5 * dp});
  ASSERT_TRUE(direct.completed());
  const test::CliOutcome r = run({"scene", "plate", "--across", "4", "--mu", "0.3", "--tip-speed", "0.02", "--t-end",
                                  "150", "--record-every", "40"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  {  // no blank line anywhere (issue 36: a blank second line after the header)
    std::ifstream raw(r.out_path);
    std::string line;
    int count = 0;
    while (std::getline(raw, line)) EXPECT_FALSE(line.empty()) << "line " << ++count;
  }
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), direct.times.size() + 1);  // + the status row
  const std::vector<std::string> status = t.text_column("status");
  EXPECT_EQ(status.back(), "completed");
  for (std::size_t k = 0; k < direct.times.size(); ++k) {
    EXPECT_EQ(std::stod(t.rows[k][1]), direct.times[k]) << k;
    EXPECT_EQ(std::stod(t.rows[k][2]), direct.kinetic_energy[k]) << k;
    EXPECT_EQ(std::stod(t.rows[k][4]), deflection[k]) << k;  // tip_deflection, shortest round-trip text
    EXPECT_EQ(t.rows[k][3], "1") << k;                       // one fragment: the plate bends, it does not break
  }
  EXPECT_GT(std::abs(deflection.back()), 0.1);  // it has moved: V_f T / (2 pi) ~ 4 over the first quarter period
}

TEST(SceneCommand, ImpactSeriesIsPowellsRun) {
  // Powell's bar impact [Powell2012, ch. 4 §4.2] with basic SPH at dx = 0.1 cm to 4 us: MCM's leap-frog with the
  // velocity smoothing (2.71), eps 0.1, at dt = 0.8 h / c_P, skin 0.5 dx; the measure is the bar's length.
  const PowellImpactOptions po{
      .problem = ImpactProblem::Bar, .spacing = 0.1, .t_end = 4, .scheme = powell_formulation_options("sph")};
  const Scene<2> sc = powell_impact_scene(po);
  std::vector<double> value;
  const SceneMeasure<2>& m = sc.measures.front();
  const RateFormRunResult direct = run_rate_form(
      *sc.scheme, sc.y0,
      {.dt = sc.time_step(0.8),
       .t_end = 4,
       .record_every = 3,
       .observer = [&](long, double,
                       const Eigen::VectorXd& y) { value.push_back(m.value(rate_form_positions(*sc.scheme, y), y)); },
       .integrator = RateFormIntegrator::Leapfrog,
       .leapfrog_xsph = 0.1,
       .neighbour_skin = 0.05});
  ASSERT_TRUE(direct.completed()) << direct.message;
  const test::CliOutcome r =
      run({"scene", "bar-impact", "--formulation", "sph", "--dp", "0.1", "--t-end", "4", "--record-every", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_EQ(t.rows.size(), direct.times.size() + 1);
  EXPECT_EQ(t.columns[4], m.name);
  EXPECT_EQ(t.text_column("status").back(), "completed");
  for (std::size_t k = 0; k < direct.times.size(); ++k) {
    EXPECT_EQ(std::stod(t.rows[k][1]), direct.times[k]) << k;
    EXPECT_EQ(std::stod(t.rows[k][2]), direct.kinetic_energy[k]) << k;
    EXPECT_EQ(std::stod(t.rows[k][4]), value[k]) << k;
  }
  EXPECT_NE(value.back(), value.front());  // the impact has changed the bar's length
}

TEST(SceneCommand, RunThatStopsKeepsRowsAndFrames) {
  // dt = 4 h / c_P is far beyond the step limit: the rings' densities collapse within a few steps. With GMS's two-rate
  // step the corrected state has the first density <= 0 (with the rings' default pc1 the evaluation at a predicted
  // state refuses it first, and the run stops as an exception: checked at the end).
  const std::filesystem::path dir = scratch("frames");
  const test::CliOutcome r = run({"scene", "rings", "--dp", "0.3", "--cfl", "4", "--t-end", "50", "--record-every", "1",
                                  "--integrator", "pc", "--out", dir.string()},
                                 "stops");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const CsvTable t = read_csv(r.out_path);
  ASSERT_GE(t.rows.size(), 2u);
  const std::vector<std::string> status = t.text_column("status");
  EXPECT_TRUE(status.back() == "non-positive-density" || status.back() == "non-finite") << status.back();
  EXPECT_GE(std::stoi(t.rows.back()[6]), 0);  // the particle
  EXPECT_LT(std::stod(t.rows.back()[1]), 50.0);
  EXPECT_NE(r.err.find("scene: stopped:"), std::string::npos);
  // Every printed row has its frame, and the collection lists them all.
  const long frames = static_cast<long>(t.rows.size()) - 1;
  for (long k = 0; k < frames; ++k) EXPECT_TRUE(std::filesystem::exists(dir / ("scene_" + t.rows[k][0] + ".vtp"))) << k;
  const VtpData last = read_vtp((dir / ("scene_" + t.rows[frames - 1][0] + ".vtp")).string());
  EXPECT_EQ(last.points.rows(), make_colliding_rings({.spacing = 0.3}).size());
  EXPECT_TRUE(std::filesystem::exists(dir / "scene.pvd"));
  const test::CliOutcome d =
      run({"scene", "rings", "--dp", "0.3", "--cfl", "4", "--t-end", "50", "--record-every", "1"}, "stops-pc1");
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const CsvTable td = read_csv(d.out_path);
  EXPECT_EQ(td.text_column("status").back(), "exception");
  EXPECT_NE(d.err.find("density must be finite and > 0"), std::string::npos) << d.err;
}

TEST(SceneCommand, StopMessageQuotesValuesInShortForm) {
  // Issue 36: an artificial stress of 1e308 drives a density to about -1e170, which the stop message used to print
  // with std::to_string as a 170-digit fixed-point number.
  const test::CliOutcome r =
      run({"scene", "plate", "--t-end", "1", "--eps", "1e308", "--integrator", "pc"}, "huge");  // GMS's two-rate step
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string::size_type at = r.err.find("scene: stopped:");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string line = r.err.substr(at, r.err.find('\n', at) - at);
  EXPECT_LT(line.size(), 200u) << line;
  EXPECT_NE(line.find("e+"), std::string::npos) << line;  // the value in exponent form
}

TEST(SceneCommand, LargeSceneIsAnnouncedBeforeItIsBuilt) {
  // Issue 36: a scene of millions of particles spent minutes building with nothing on the screen. 2 pi 7 / 0.02^2 =
  // 1.1e5 rings particles, at 2 kB each.
  const test::CliOutcome r = run({"scene", "rings", "--dp", "0.02", "--t-end", "0.001"}, "announce");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("scene: building rings (about 1.1e+05 particles, ~220 MB)"), std::string::npos) << r.err;
  const test::CliOutcome small = run({"scene", "rings", "--dp", "0.3", "--t-end", "0.001"}, "quiet");
  ASSERT_EQ(small.exit_code, 0) << small.err;
  EXPECT_EQ(small.err.find("scene: building"), std::string::npos) << small.err;
}

TEST(SceneCommand, BadInputIsOneLine) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"scene", "plate", "--thickness", "0"}, "--thickness"},
      {{"scene", "plate", "--thickness", "-2"}, "--thickness"},
      {{"scene", "rings", "--dp", "0"}, "--dp"},
      {{"scene", "slab", "--dp", "nan"}, "--dp"},
      {{"scene", "slab", "--nu", "0.5"}, "--nu"},
      {{"scene", "rings", "--nu", "-1"}, "--nu"},
      {{"scene", "slab", "--yield", "0"}, "--yield"},
      {{"scene", "plate", "--eps", "-0.1"}, "--eps"},
      {{"scene", "plate", "--mu", "-1"}, "--mu"},
      {{"scene", "disc"}, "unknown scene"},
      {{"scene", "rings", "--integrator", "euler"}, "unknown integrator 'euler'"},
      {{"scene", "slab", "--integrator", "pc1", "--dp", "0.25"}, "reuse_corrector_rate with a yield stress"},
      {{"scene", "rings", "--mu", "0.2", "--nu", "0.3"}, "--mu or --nu"},
      {{"scene", "plate", "--dp", "0.1"}, "--across"},
      {{"scene", "plate", "--across", "1"}, "--across"},
      {{"scene", "slab", "--t-end", "0"}, "--t-end"},
      {{"scene", "rings", "--dp", "0.6"}, "spacing"},
      {{"scene", "plate", "--length", "1e9", "--across", "100"}, "GB"},  // refused before anything is built
      // More particles than any run may step, even one step: refused before anything is built (issue 36)
      {{"scene", "rings", "--dp", "1e-5"}, "particle-steps"},
      {{"scene", "slab", "--dp", "1e-4"}, "particle-steps"},
      // Memory estimated before the scene is built (issue 36: --dp 0.003 took ~7 GB unannounced); short runs, so the
      // step count passes
      {{"scene", "rings", "--dp", "0.003", "--t-end", "0.01"}, "GB"},
      {{"--max-memory", "20M", "scene", "rings", "--dp", "0.03"}, "--max-memory"},
      {{"scene", "slab", "--dp", "1e-3", "--t-end", "0.01"}, "GB"},
      // options of another scene (issue 36: they used to be accepted and ignored)
      {{"scene", "rings", "--across", "5"}, "--across applies to the plate only"},
      {{"scene", "slab", "--thickness", "1"}, "--thickness applies to the plate only"},
      {{"scene", "rings", "--length", "5"}, "--length applies to the plate only"},
      {{"scene", "rings", "--tip-speed", "0.1"}, "--tip-speed applies to the plate only"},
      {{"scene", "plate", "--speed", "0.1"}, "--speed applies to the rings and the impacts only"},
      {{"scene", "slab", "--speed", "0.1"}, "--speed applies to the rings and the impacts only"},
      // Powell's impact problems
      {{"scene", "bar-impact", "--formulation", "tl"}, "formulation"},
      {{"scene", "rings", "--formulation", "sph"}, "--formulation applies to the impact problems only"},
      {{"scene", "bar-impact", "--mu", "0.3"}, "--mu applies to the GMS scenes only"},
      {{"scene", "symmetric-impact", "--eps", "0.3"}, "--eps applies to the GMS scenes only"},
      {{"scene", "clamped-beam", "--dp", "0.03"}, "clamp"},
      {{"scene", "symmetric-impact", "--dp", "0"}, "spacing"},
      {{"scene", "bar-impact", "--speed", "nan"}, "speed"},
      {{"scene", "bar-impact", "--across", "4"}, "--across applies to the plate only"},
  };
  test::expect_one_line_errors(cases, [](const std::vector<std::string>& args) { return run(args, "bad"); });
}

}  // namespace scene_command_test
}  // namespace sphstab
