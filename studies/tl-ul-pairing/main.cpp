// Ismail (2009) §4.7: the tensile instability, total- against updated-Lagrangian SPH. A 1D bar, ends held, in uniform
// tension T = E eps (pre-stretched), the centre particle's displacement perturbed by 5 %. TL: the finite-strain TL
// form (forms/finite_strain_total_lagrangian.hpp, Hooke 1D stress, operators at the reference positions); UL: the
// 1D pre-tensioned wave form (forms/wave_1d.hpp, kernel at the CURRENT positions, the same Hooke law, Powell's
// pre-stress). Both with the plus divergence and the same kernel and h / dx.
// 1. critical tension: UL by the critical-load engine (stability/critical_load.hpp, Cholesky bisection and the
//    generalised eigenproblem); TL by the same engine on A(T) = A0 + T A1 from the complex-step Jacobian at the
//    pre-stretched states (A1 = 0 for Hooke: infinite), and by a Cholesky sweep of the Neo-Hookean TL stiffness over
//    stretches up to 6 (positive definite at every one: the largest tension tried is reported).
// 2. runs: both forms from the same perturbed pre-stretched state at T = factor x T_crit(UL); the pairing measure
//    min_i (x_{i+1} - x_i) / spacing over time and the middle 7 particles' displacements.
// 3. the rate-form scheme (GMS/Powell: continuity, equation of state, Jaumann rate, predictor-corrector) on the same
//    bar: its critical stress from the rate-form engine and the same runs (section_rate_form.hpp).
#include <CLI/CLI.hpp>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "section_2d.hpp"
#include "section_rate_form.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/cholmod_definiteness.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/stability/critical_load.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

constexpr double kNu = 0.3;  // E = rho = dx = 1

/// The free particles' positions (reference), the particle set and a discretisation with a neighbour margin.
struct Bar {
  ParticleSet<1> set;
  std::shared_ptr<const Discretisation<1>> disc;
  Eigen::VectorXd x_all;  ///< reference positions, all particles
};

Bar make_bar(int n, const Kernel<1>& kernel, double h) {
  Bar b;
  b.set = make_lattice<1>(LatticeType::Line, n, {.spacing = 1.0, .support_radius = 2 * kernel.support_radius(h)});
  b.disc = make_discretisation(b.set, kernel, h, kernel.support_radius(h) + 1.0);  // margin for the UL motion
  b.x_all = b.set.x.col(0);
  return b;
}

bool positive_definite(const SparseMatrix<>& a) {
  const ColSparseMatrix s = ColSparseMatrix(SparseMatrix<>(0.5 * (a + SparseMatrix<>(a.transpose()))));
  CholmodDefiniteness check;
  check.analyze_pattern(s);
  return check.is_positive_definite(s);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Ismail 2009 §4.7: TL stays in phase, UL pairs; critical tension of each"};
  std::string out = "results/tl-ul-pairing";
  std::string kernel_arg = "mollifier";
  int n = 41;
  double h_over_dx = 2.75, tension = 0.05, t_end = 100, perturbation = 0.05;
  app.add_option("--out", out, "output directory");
  app.add_option("--kernel", kernel_arg, "kernel (Ismail: mollifier)");
  app.add_option("--h", h_over_dx, "h / dx (support 2h; Ismail's 5.5 dx is 2.75)");
  app.add_option("--n", n, "free particles (odd: a centre particle)")->check(CLI::Range(11, 2001));
  app.add_option("--tension", tension, "run tension T = E eps (E = 1: the pre-strain)");
  app.add_option("--t-end", t_end, "run length (dx / c)");
  app.add_option("--perturbation", perturbation, "relative perturbation of the centre particle's displacement");
  std::string section = "both";
  pairing2d::Options o2;
  app.add_option("--section", section, "1d, 2d or both")->check(CLI::IsMember({"1d", "2d", "both"}));
  app.add_option("--kernel-2d", o2.kernel, "2D kernel (default cubic; see README)");
  app.add_option("--h-2d", o2.h, "2D h / dx");
  app.add_option("--nx-2d", o2.nx, "2D free particles along x (odd)")->check(CLI::Range(5, 401));
  app.add_option("--ny-2d", o2.ny, "2D free particles along y (odd)")->check(CLI::Range(1, 401));
  app.add_option("--strain-2d", o2.strain, "2D run pre-strain e (E = 1)");
  app.add_option("--t-end-2d", o2.t_end, "2D run length (dx / c with c^2 = E / rho)");
  bool quick = false;
  app.add_flag("--quick", quick,
               "pipeline check: 1D bar of 15 free particles to t = 75, 2D block of 9 x 3 to t = 20 (both sections)");
  CLI11_PARSE(app, argc, argv);
  if (quick) n = 15, t_end = 75, section = "both", o2.nx = 9, o2.ny = 3, o2.t_end = 20;
  o2.perturbation = perturbation;
  if (n % 2 == 0) throw std::invalid_argument("tl-ul-pairing: --n must be odd (a centre particle)");
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  if (section == "2d") {  // the 2D section alone (the 1D keys of summary.json are then absent)
    study::Summary summary;
    pairing2d::run(o2, out, summary);
    summary.set("wall_seconds", study::seconds_since(t0), 3);
    summary.write(out);
    return 0;
  }
  const Kernel<1> kernel(parse_kernel_type(kernel_arg));
  const double h = h_over_dx;
  const Bar bar = make_bar(n, kernel, h);
  const int n_all = bar.set.size();
  const auto& disc = bar.disc;
  study::Summary summary;
  summary.set("kernel", kernel_name(kernel.type()));
  summary.set("h_over_dx", h, 4);
  summary.set("n", n);
  summary.set("fixed_per_end", (n_all - n) / 2);

  // 1. critical tensions
  CsvWriter ccsv(out + "/critical.csv", {"form", "route", "t_crit", "note"});
  CriticalLoadOptions copt = CriticalLoadOptions::tension_1d();
  copt.want_mode = true;
  const CriticalLoad ul_plus = critical_tension_1d(bar.set, kernel, h, MomentumForm::Plus, copt);
  const CriticalLoad ul_unc = critical_tension_1d(bar.set, kernel, h, MomentumForm::Uncorrected, copt);
  for (const auto& [name, r] : {std::pair{"UL plus", &ul_plus}, std::pair{"UL uncorrected", &ul_unc}}) {
    ccsv.row({name, "eigen", r->load_eigen, r->reason});
    ccsv.row({name, "bisection", r->load_bisection, status_name(r->status)});
  }
  const double t_ul = ul_plus.load;
  summary.set("t_crit_ul_plus", ul_plus.load, 6);
  summary.set("t_crit_ul_plus_bisection", ul_plus.load_bisection, 6);
  summary.set("t_crit_ul_plus_routes", ul_plus.relative_difference, 2);
  summary.set("t_crit_ul_uncorrected", ul_unc.load, 6);
  summary.set("ul_mode_k", ul_plus.mode_wavenumber.k_sign_changes, 3);
  summary.set("ul_mode_k_projection", ul_plus.mode_wavenumber.k_projection, 3);
  if (!(t_ul > 0) || !std::isfinite(t_ul)) throw std::runtime_error("tl-ul-pairing: T_crit(UL) not finite");

  // TL, Hooke: A(T) from the complex-step Jacobian at the pre-stretched states u = eps X, eps = T / E.
  const ElasticMaterial lame = ElasticMaterial::from_young_poisson(1.0, kNu, 1.0);
  auto hooke = std::make_shared<Hooke<1>>(lame, UniaxialState::Stress);
  const Eigen::VectorXd x_free = disc->free_positions().col(0);
  const double x_end = x_free.minCoeff() - 0.5;          // the bar's left end, between the free and the fixed particles
  const Eigen::VectorXd x_rel = x_free.array() - x_end;  // pre-stretch u = eps (X - x_end): the left end held
  auto fixed_u = [&](double eps) {
    Eigen::VectorXd d(n_all - n);
    for (int i = 0, k = 0; i < n_all; ++i)
      if (disc->free_slot[i] < 0) d[k++] = eps * (bar.x_all[i] - x_end);
    return d;
  };
  FiniteStrainTotalLagrangian<1> tl(disc, hooke, 1.0);
  Linearisation lin;
  {
    tl.set_fixed_displacement(fixed_u(0));
    lin.A0 = jacobian(tl, Eigen::VectorXd::Zero(n));
    const double t1 = 0.5;
    tl.set_fixed_displacement(fixed_u(t1));
    lin.A1 = (jacobian(tl, t1 * x_rel) - lin.A0) / t1;
    lin.symmetric = true;
    lin.dofs_per_particle = 1;
  }
  const CriticalLoad tl_hooke = critical_load(lin, LoadDirection::Tension, CriticalLoadOptions::tension_1d());
  ccsv.row({"TL Hooke", "engine", tl_hooke.load, tl_hooke.reason});
  summary.set("t_crit_tl_hooke", std::isinf(tl_hooke.load) ? std::string("inf") : study::sig(tl_hooke.load, 6));
  summary.set("tl_hooke_a1_norm", lin.A1.norm() / lin.A0.norm(), 2);

  // TL, Neo-Hookean (1D strain, Ismail's algorithm 5.1): Cholesky sweep over stretches; UL: the same sweep of
  // A(T) = A0 + T A1 over the same tensions (an independent bracket of the engine's T_crit)
  auto nh = std::make_shared<NeoHookean<1>>(lame, UniaxialState::Strain);
  FiniteStrainTotalLagrangian<1> tl_nh(disc, nh, 1.0);
  const Linearisation ul_lin = analytic_jacobian_1d(bar.set, kernel, h, MomentumForm::Plus);
  CsvWriter scsv(out + "/sweep.csv", {"stretch", "tension", "tl_neo_hookean_pd", "ul_plus_pd", "tl_dt_limit"});
  double t_max_tl = 0, ul_last_pd = 0, ul_first_fail = std::nan("");
  bool tl_all_pd = true;
  for (int k = 0; k <= 60; ++k) {
    const double stretch = std::pow(6.0, k / 60.0) + (k == 0 ? 1e-3 : 0.0);
    Deformation<double, 1> f;
    f(0, 0) = stretch;
    const double tension = nh->stress(f)(0, 0);
    tl_nh.set_fixed_displacement(fixed_u(stretch - 1));
    const Eigen::VectorXd u = (stretch - 1) * x_rel;
    const SparseMatrix<> a = jacobian(tl_nh, u);
    const bool tl_pd = positive_definite(a);
    const bool ul_pd = positive_definite(ul_lin.at(tension));
    const StableTimeStep dt = stable_time_step(a, tl_nh.dof_mass());
    scsv.row({stretch, tension, tl_pd ? 1 : 0, ul_pd ? 1 : 0, dt.dt});
    tl_all_pd = tl_all_pd && tl_pd;
    if (tl_pd) t_max_tl = std::max(t_max_tl, tension);
    if (ul_pd && std::isnan(ul_first_fail)) ul_last_pd = tension;
    if (!ul_pd && std::isnan(ul_first_fail)) ul_first_fail = tension;
  }
  summary.set("tl_nh_all_pd", tl_all_pd ? "yes" : "no");
  summary.set("tl_nh_max_tension", t_max_tl, 4);
  summary.set("ul_sweep_last_pd", ul_last_pd, 4);
  summary.set("ul_sweep_first_fail", ul_first_fail, 4);
  std::cout << "T_crit(UL plus) = " << ul_plus.load << ", uncorrected " << ul_unc.load << "; TL Hooke engine "
            << tl_hooke.load << "; TL Neo-Hookean PD up to T = " << t_max_tl << (tl_all_pd ? " (all)" : "") << "\n";

  // 2. the runs at the tension T (E = 1: eps = T)
  const double eps = tension;
  const int centre = n / 2;
  const double delta = perturbation * eps * x_rel[centre];
  summary.set("tension", tension, 4);
  summary.set("tension_over_t_crit_ul", tension / t_ul, 3);
  summary.set("delta_over_dx", delta, 4);
  summary.set("t_end", t_end, 3);
  summary.set("t_arrival", x_rel[centre], 3);
  CsvWriter pcsv(out + "/pairing.csv",
                 {"run", "t", "min_gap_over_spacing", "max_gap_over_spacing", "gap_deviation_over_initial"}, false);
  std::vector<std::string> tcols{"run", "t"};
  for (int k = -3; k <= 3; ++k) tcols.push_back("d" + std::to_string(k) + "_over_dx");
  CsvWriter tcsv(out + "/middle7.csv", tcols, false);
  std::string md_runs;
  for (const std::string run : {"TL", "UL"}) {
    const bool is_tl = run == "TL";
    std::shared_ptr<ForceFunction> force;
    Eigen::VectorXd u_eq;
    double spacing = 1;
    if (is_tl) {
      auto f = std::make_shared<FiniteStrainTotalLagrangian<1>>(disc, hooke, 1.0);
      f->set_fixed_displacement(fixed_u(eps));
      u_eq = eps * x_rel;
      spacing = 1 + eps;
      force = f;
    } else {
      force = std::make_shared<WaveForm1D>(disc, MomentumForm::Plus, tension);
      u_eq = Eigen::VectorXd::Zero(n);
    }
    Eigen::VectorXd a_eq;
    force->acceleration(u_eq, a_eq);
    Eigen::VectorXd u0 = u_eq;
    u0[centre] += delta;
    const double dt = 0.05;
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { force->acceleration(u, a); };
    sys.mass = force->dof_mass();
    LeapfrogStepper stepper(sys, u0, Eigen::VectorXd::Zero(n));
    double t_pair = std::nan(""), gap_min_all = 1e300, amp_max = 0, amp_at_arrival = std::nan("");
    const double t_arrival = x_rel[centre];  // the perturbation's wave reaches the ends (c = 1): Ismail's run length
    SnapshotFunction gaps([&](const StepView& s) {
      const double t = s.time;
      const Eigen::VectorXd pos = x_free + s.u;
      double gmin = 1e300, gmax = 0;
      for (int i = 0; i + 1 < n; ++i) {
        const double g = (pos[i + 1] - pos[i]) / spacing;
        gmin = std::min(gmin, g);
        gmax = std::max(gmax, g);
      }
      gap_min_all = std::min(gap_min_all, gmin);
      // the largest gap deviation over the initial one (delta / spacing at the centre particle)
      const double amp = std::max(1 - gmin, gmax - 1) / (delta / spacing);
      amp_max = std::max(amp_max, amp);
      if (std::isnan(amp_at_arrival) && t >= t_arrival) amp_at_arrival = amp;
      if (std::isnan(t_pair) && gmin < 0.5) t_pair = t;
      if (s.step % 4 == 0) {
        pcsv.row({run, t, gmin, gmax, amp});
        std::vector<CsvCell> row{run, t};
        for (int k = -3; k <= 3; ++k) row.push_back((s.u[centre + k] - u_eq[centre + k]) / spacing);
        tcsv.row(row);
      }
      if (gmin < 0.05) gaps.stop("particles within 0.05 spacing");
    });
    RunOptions ro{.dt = dt, .t_end = t_end, .land_on_t_end = false, .snapshot_every = 1};
    ro.observers = {&gaps};
    const RunResult result = sphstab::run(stepper, ro);
    const std::string status = result.completed()                       ? "completed"
                               : result.status == RunStatus::Stopped ? "particles within 0.05 spacing (stopped)"
                                                                     : run_status_name(result.status);
    summary.set("t_pair_" + run, std::isnan(t_pair) ? std::string("never") : study::sig(t_pair, 4));
    summary.set("amp_max_" + run, amp_max, 3);
    summary.set("amp_arrival_" + run, amp_at_arrival, 3);
    study::md_row(md_runs,
                  {run, force->name(), study::sig(a_eq.cwiseAbs().maxCoeff(), 2), study::sig(amp_at_arrival, 3),
                   study::sig(amp_max, 3), study::sig(gap_min_all, 4),
                   std::isnan(t_pair) ? "never" : study::sig(t_pair, 4), study::sig(stepper.time(), 4), status});
    std::cout << run << ": min gap " << gap_min_all << ", t_pair " << t_pair << ", " << status << "\n";
  }
  // 3. the rate-form scheme (finite-strain UL as practitioners run it) on the same bar: section_rate_form.hpp
  pairing_rf::run_section({.disc = disc,
                           .t_plus = t_ul,
                           .tension = tension,
                           .delta = delta,
                           .centre = centre,
                           .t_end = t_end,
                           .t_arrival = x_rel[centre],
                           .nu = kNu},
                          out, summary, md_runs);
  summary.set("runs", md_runs);
  if (section == "both") pairing2d::run(o2, out, summary);
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
