// Study: critical stress of the rate-form scheme (continuity, equation of state, Jaumann rate) beside the critical
// tension of the §3.3 model (constant density, additive pre-stress), [Powell2012, Fig. 3.2] for the scheme people
// run. The engine is stability/rate_form_critical_stress.hpp (bisection on the full-state spectrum at rest); the §3.3
// values come from critical_tension_1d / critical_load on the analytic Jacobians in the same run.
//
// Writes to --out DIR: bar_1d.csv, block_2d.csv (square), block_2d_hex.csv (hexagonal), summary.json.
#include <CLI/CLI.hpp>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/study.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/stability/critical_load.hpp"
#include "sphstab/stability/rate_form_critical_stress.hpp"

using namespace sphstab;

namespace {

struct Formulation {
  std::string name;
  RateFormOptions options;
  bool corrected;  // needs neighbours of neighbours complete: more fixed layers
};

std::vector<Formulation> formulations() {
  return {{"sph", {}, false},
          {"sph-as", {.artificial_stress = 0.3}, false},
          {"ncsph", {.continuity = ContinuityForm::Divergence, .gradient = RateFormGradient::Ncsph}, true},
          {"ncsph-anti",
           {.continuity = ContinuityForm::Divergence,
            .gradient = RateFormGradient::Ncsph,
            .momentum = RateFormMomentum::Antisymmetric},
           true},
          {"cij", {.momentum = RateFormMomentum::Cij}, true},
          {"ssph", {.momentum = RateFormMomentum::StabilisedSph}, true},
          {"ssph-printed", {.momentum = RateFormMomentum::StabilisedSph, .switch_rule = SwitchRule::AsPrinted}, true}};
}

/// Largest |acceleration| of the free particles at the uniform state over the largest |J| entry scale: 0 iff the
/// lattice is an equilibrium of the formulation at this load.
template <int Dim>
double equilibrium_residual(const RateFormScheme<Dim>& s) {
  Eigen::VectorXd f;
  s.rate(s.uniform_state(), f);
  double r = 0;
  for (int i = 0; i < s.discretisation().size(); ++i)
    if (s.velocity_offset(i) >= 0) r = std::max(r, f.segment(s.velocity_offset(i), Dim).cwiseAbs().maxCoeff());
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  study::DriverCli cli{
      "Critical stress of the rate-form SPH scheme beside the §3.3 model (Powell Fig. 3.2)",
      "results/critical-stress-rate-form",
      "the study's test case: 1D cubic at h/dx 0.8, 1.3, ..., 2.8 with --n1 12; 2D square at h/dx 1.3 with "
      "--n2 3 (unless given), no hexagonal block"};
  int n1 = 30, n2 = 9;
  cli.add_quick_option("--n1", n1, 12, "free particles of the 1D bar")->check(CLI::Range(5, 400));
  cli.add_quick_option("--n2", n2, 3, "free particles per side of the 2D block")->check(CLI::Range(3, 41));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  const auto t0 = study::Clock::now();
  // rho0 = 1, K = 1, mu = 0.3 (GMS units, nu = 0.36): M = 1.4.
  const ElasticMaterial material = ElasticMaterial::from_bulk_shear(1.0, 0.3, 1.0);
  const double M = material.bulk_modulus() + 4 * material.mu() / 3;
  const std::vector<LoadDirection> dirs = {LoadDirection::Tension, LoadDirection::Compression};

  // 1D bar: kernels x h / dx as Fig. 3.2, both directions.
  std::ofstream bar(cli.out + "/bar_1d.csv");
  bar << "kernel,h_over_dx,direction,formulation,layer_supports,stress_over_modulus,xi,growth_above,evaluations,"
         "equilibrium_residual,t_plus_33,t_conservative_33,predicted_sph,status,reason\n";
  const std::vector<KernelType> kernels =
      cli.quick ? std::vector<KernelType>{KernelType::CubicSpline}
                : std::vector<KernelType>{KernelType::CubicSpline, KernelType::QuarticSpline, KernelType::QuinticSpline,
                                          KernelType::WendlandC2, KernelType::WendlandC4};
  double worst_prediction = 0;
  int bar_rows = 0;

  std::string cubic_table;
  for (KernelType type : kernels) {
    const Kernel<1> kernel(type);
    for (int hk = 0; hk <= 22; hk += cli.quick ? 5 : 1) {
      const double h = 0.8 + 0.1 * hk;
      const ParticleSet<1> plain_set = tension_lattice_1d(kernel, h, n1);
      const auto plain = make_discretisation(plain_set, kernel, h);
      const auto corrected = make_discretisation(tension_lattice_1d(kernel, h, n1, false, 3), kernel, h);
      for (LoadDirection dir : dirs) {
        const double t_plus =
            critical_tension_1d(plain_set, kernel, h, MomentumForm::Plus, CriticalLoadOptions::tension_1d(), dir).load;
        const double t_cons = critical_tension_1d(plain_set, kernel, h, MomentumForm::Conservative,
                                                  CriticalLoadOptions::tension_1d(), dir)
                                  .load;
        const double predicted = t_plus / (1 - t_plus);  // header note of rate_form_critical_stress.hpp
        std::vector<std::string> cells{study::fixed(h, 1), study::sig(t_plus, 4), study::sig(t_cons, 4)};
        for (const Formulation& f : formulations()) {
          const auto& disc = f.corrected ? corrected : plain;
          const RateFormCriticalStress r =
              rate_form_critical_stress<1>(disc, material, f.options, {.direction = dir, .max = 0.7});
          const double res = equilibrium_residual(
              RateFormScheme<1>(disc, material, f.options, material.density() / (1 + 0.01 * load_sign(dir))));
          if (f.name == "sph" && std::isfinite(predicted) && std::isfinite(r.stress_over_modulus))
            worst_prediction =
                std::max(worst_prediction, std::abs(r.stress_over_modulus - predicted) / std::abs(predicted));
          bar << csv_line({kernel_name(type), format_number(h, 4), load_direction_name(dir), f.name,
                           f.corrected ? "3" : "1", format_number(r.stress_over_modulus, 10), format_number(r.xi, 10),
                           format_number(r.growth_above, 6), std::to_string(r.evaluations), format_number(res, 3),
                           format_number(t_plus, 10), format_number(t_cons, 10), format_number(predicted, 10),
                           status_name(r.status), r.reason});
          ++bar_rows;
          cells.push_back(study::sig(r.stress_over_modulus, 4));
        }
        if (type == KernelType::CubicSpline && dir == LoadDirection::Tension && hk % 2 == 0)
          study::md_row(cubic_table, cells);
      }
    }
    std::printf("1D %s done (%.1f s)\n", kernel_name(type).c_str(), study::seconds_since(t0));
    std::fflush(stdout);
  }

  // 2D square and hexagonal blocks, cubic spline: the rate form beside the §3.3 plus and conservative forms at
  // isotropic pre-strain e (plane strain: sigma0 = 2 (lambda + mu) e in-plane, so sigma0 / M = 2 (lambda + mu) e / M).
  // The same material: its lambda is K - 2 mu / 3 (from_bulk_shear), as this study has always used.
  const ElasticMaterial& elastic = material;
  const double lambda = elastic.lambda(), mu = elastic.mu();
  const Kernel<2> k2(KernelType::CubicSpline);
  auto blocks = [&](LatticeType type, const std::string& file) {
    std::ofstream block(cli.out + "/" + file);
    block << "h_over_dx,direction,formulation,stress_over_modulus,xi,growth_above,evaluations,equilibrium_residual,"
             "plus_33,conservative_33,status,reason\n";
    std::string table;
    for (double h : cli.quick ? std::vector<double>{1.3} : std::vector<double>{1.0, 1.2, 1.3, 1.5, 2.0}) {
      const auto disc = make_discretisation(strain_lattice_2d(type, k2, h, n2), k2, h);
      for (LoadDirection dir : dirs) {
        double s33[2];
        int q = 0;
        for (MomentumForm form : {MomentumForm::Plus, MomentumForm::Conservative}) {
          const CriticalLoad e = critical_load(analytic_jacobian_2d(*disc, elastic, form, PreStrainKind::Isotropic),
                                               dir, CriticalLoadOptions::strain_2d());
          s33[q++] = 2 * (lambda + mu) * e.load / M;
        }
        std::vector<std::string> cells{study::fixed(h, 1), load_direction_name(dir), study::sig(s33[0], 4),
                                       study::sig(s33[1], 4)};
        for (const Formulation& f : formulations()) {
          if (f.name == "ncsph-anti" || f.name == "ssph-printed") continue;  // 1D shows them; keep 2D short
          const RateFormCriticalStress r =
              rate_form_critical_stress<2>(disc, material, f.options, {.direction = dir, .max = 0.7, .rtol = 1e-6});
          const double res = equilibrium_residual(
              RateFormScheme<2>(disc, material, f.options, material.density() / (1 + 0.01 * load_sign(dir))));
          block << csv_line({format_number(h, 4), load_direction_name(dir), f.name,
                             format_number(r.stress_over_modulus, 10), format_number(r.xi, 10),
                             format_number(r.growth_above, 6), std::to_string(r.evaluations), format_number(res, 3),
                             format_number(s33[0], 10), format_number(s33[1], 10), status_name(r.status), r.reason});
          cells.push_back(study::sig(r.stress_over_modulus, 4) + (res > 1e-12 ? " (r)" : ""));
        }
        study::md_row(table, cells);
        std::printf("2D %s h %.1f %s done (%.1f s)\n", lattice_name(type).c_str(), h, load_direction_name(dir).c_str(),
                    study::seconds_since(t0));
        std::fflush(stdout);
      }
    }
    return table;
  };
  const std::string block_table = blocks(LatticeType::Square, "block_2d.csv");
  const std::string hex_table = cli.quick ? "" : blocks(LatticeType::Hexagonal, "block_2d_hex.csv");

  study::Summary s;
  s.set("n1", n1);
  s.set("n2", n2);
  s.set("bar_rows", bar_rows);
  s.set("worst_prediction", worst_prediction, 2);
  s.set("cubic_table", cubic_table);
  s.set("block_table", block_table);
  s.set("hex_table", hex_table);
  study::write_summary(s, cli.out, t0, {.wall_key = "wall_total"});
  std::printf("1D sph against T_plus/(1 - T_plus): worst relative difference %.2g\n", worst_prediction);
  return 0;
}
