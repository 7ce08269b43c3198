// Turek & Hron (2006) CSM3: the elastic beam clamped to a rigid cylinder, oscillating under gravity from rest, with
// finite-strain total-Lagrangian SPH (St Venant-Kirchhoff, plane strain) plus a constant body force
// (forms/body_force.hpp). Geometry and reference: problems/turek_hron_csm3.hpp. Forms (--gradient):
//   ncsph-variational  forms/variational_total_lagrangian.hpp with the NCSPH reference gradient (M a = -dU/du);
//   plain              forms/finite_strain_total_lagrangian.hpp, plain G, difference strain, plus divergence;
//   ncsph              the same with the NCSPH strain gradient (its divergence stays the plain G).
// Runs: the chosen form at the resolutions --across (the last three give the observed order), the two other forms
// and a 1 dx clamp at the coarsest one. Leap-frog at --cfl of the stability limit of the linearisation at rest.
// The displacement of A = (0.6, 0.2) is extrapolated linearly to x = 0.6 from the means of the two tip columns'
// particles nearest y = 0.2: u_A = 1.5 u(col 0) - 0.5 u(col 1). Mean = (max + min) / 2 and amplitude
// = (max - min) / 2 over the window t >= --t-measure, frequency = 1 / period from the zero crossings of u - mean.
// Writes to --out DIR: tip_<run>.csv, runs.csv, order.csv, rotation.csv, snapshot.csv (finest run, largest deflection
// of the last period), summary.json.
// The runs and their computation are in csm3_cases.hpp (the snapshot in deflection_snapshot.hpp), runs.csv and the
// tables against the reference in run_tables.hpp, the observed order in observed_order.hpp, the rigid-rotation check
// in rigid_rotation.hpp; the form builder, the gravity run and linear beam theory in studies/common/csm3.hpp.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/csm3.hpp"
#include "common/study.hpp"
#include "csm3_cases.hpp"
#include "deflection_snapshot.hpp"
#include "observed_order.hpp"
#include "rigid_rotation.hpp"
#include "run_tables.hpp"
#include "sphstab/models/st_venant_kirchhoff.hpp"

using namespace csm3_study;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  CLI::App app{"Turek & Hron CSM3: elastic beam under gravity, finite-strain TL SPH (St Venant-Kirchhoff)"};
  std::string out = "results/tl-csm3", gradient = "ncsph-variational", divergence = "plus";
  std::vector<int> across{4, 8, 12, 16};
  double t_end = 6, t_measure = 2, cfl = 0.8, h_over_dx = 1.5;
  int clamp_layers = 4, wide_clamp = 1;
  app.add_option("--out", out, "output directory");
  app.add_option("--across", across, "particles through the thickness, coarsest first (the last three give the order)");
  app.add_option(
         "--gradient", gradient,
         "strain gradient and form: ncsph-variational, plain or ncsph (the latter two: FiniteStrainTotalLagrangian)")
      ->check(CLI::IsMember({"ncsph", "plain", "ncsph-variational"}));
  app.add_option("--divergence", divergence, "stress divergence: plus, minus or plain")
      ->check(CLI::IsMember({"plus", "minus", "plain"}));
  app.add_option("--t-end", t_end, "physical time (s)")->check(CLI::PositiveNumber);
  app.add_option("--t-measure", t_measure, "start of the measuring window (s)")->check(CLI::NonNegativeNumber);
  app.add_option("--cfl", cfl, "fraction of the leap-frog limit")->check(CLI::Range(0.05, 0.9));
  app.add_option("--h", h_over_dx, "h / dx (Wendland C2, support 2h)")->check(CLI::Range(1.0, 3.0));
  app.add_option("--clamp", clamp_layers, "clamp width in dx")->check(CLI::Range(1, 20));
  app.add_option("--clamp-sensitivity", wide_clamp, "clamp width of the sensitivity run at the coarsest resolution")
      ->check(CLI::Range(1, 20));
  bool quick = false;
  app.add_flag("--quick", quick, "pipeline check: 2, 3 and 4 particles across, to t = 3 s, measured from t = 0.5 s");
  CLI11_PARSE(app, argc, argv);
  if (quick) across = {2, 3, 4}, t_end = 3, t_measure = 0.5;
  if (across.empty()) throw std::invalid_argument("tl-csm3: --across needs at least one resolution");
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  const std::vector<std::string> others = other_gradients(gradient);
  const std::string other = others[0] + " and " + others[1];

  // ---- 1. The runs: the chosen form at every resolution, the other forms and the clamp sensitivity. ----
  const ElasticMaterial lame = study::csm3::lame();
  auto svk = std::make_shared<StVenantKirchhoff<2>>(lame);
  const Kernel<2> kernel(KernelType::WendlandC2);
  const CaseSettings settings{
      .out = out, .divergence = divergence, .h_over_dx = h_over_dx, .t_end = t_end, .t_measure = t_measure, .cfl = cfl};
  std::vector<CaseResult> results;
  DeflectionSnapshot snapshot;
  for (const RunSpec& spec : case_specs(across, gradient, clamp_layers, wide_clamp)) {
    const bool finest = spec.across == across.back() && spec.gradient == gradient && spec.clamp_layers == clamp_layers;
    results.push_back(run_case(spec, settings, kernel, svk, finest ? &snapshot : nullptr));
  }

  // ---- 2. Tables: runs.csv, the measures against the reference, the observed order, the snapshot. ----
  const RunTables tables = run_tables(out, results);
  // observed order over the three resolutions of the chosen gradient
  const std::string md_order = order_table(out, results, across.size());
  snapshot.write(out, across.back(), clamp_layers);

  // ---- 3. Objectivity of the strain under a rigid rotation (plain and NCSPH gradient). ----
  const std::string md_rot = rigid_rotation(out, across, clamp_layers, kernel, h_over_dx, svk);

  // ---- 4. Key numbers for summary.md.in. ----
  study::Summary summary;
  summary.set("rotation", md_rot);
  summary.set("runs", tables.runs);
  summary.set("table", tables.table);
  summary.set("order", md_order);
  summary.set("gradient", gradient);
  summary.set("other_gradient", other);
  summary.set("h_over_dx", h_over_dx, 3);
  summary.set("cfl", cfl, 3);
  summary.set("t_end", t_end, 3);
  summary.set("t_measure", t_measure, 3);
  summary.set("clamp_layers", clamp_layers);
  summary.set("wide_clamp", wide_clamp);
  summary.set("lambda", lame.lambda(), 4);
  summary.set("snapshot_t", snapshot.t, 4);
  summary.set("snapshot_uy_mm", 1e3 * snapshot.uy, 4);
  summary.set("load", study::load_average());
  {  // linear beam theory for the 0.35 m cantilever (common/csm3.hpp)
    const study::csm3::BeamTheory b = study::csm3::beam_theory();
    summary.set("f_euler_bernoulli", b.f_euler_bernoulli, 4);
    summary.set("f_timoshenko", b.f_timoshenko, 4);
    summary.set("static_tip_mm", b.static_tip_mm, 4);
    summary.set("beam_length", b.length, 6);
  }
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
