#pragma once
// The 1D version of the Swegle test: WaveForm1D (u_tt = (u_x + T)_x, c = E = rho = 1, dx = 1), pre-strain
// T = xi - 1, 21 free particles, centre particle kicked; the four momentum forms with the analytic Jacobian
// [Powell2012, (3.40)] next to the complex-step one, NCSPH [Powell2012, (1.19)] and C_ij [Powell2012, (4.9), Fig. 4.3,
// (4.18)]; growth rate of the excited (mirror-antisymmetric) class against the run's; writes onedim_ke.csv and
// onedim_runs.csv.

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "linear_theory.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/growth/growth_run.hpp"
#include "sphstab/growth/linear_growth.hpp"
#include "sphstab/growth/stability_verdict.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/analytic_jacobian_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/dominant_wavenumber.hpp"
#include "swegle_options.hpp"

namespace swegle_study {

using namespace sphstab;
using study::sig;

struct Row1D {
  std::string form;
  double T = 0;
  double gamma_cs = kNaN, gamma_analytic = kNaN, gamma_exc = kNaN;
  GrowthRun run;
  double ratio = kNaN;
  std::string lin_verdict, run_verdict;
  WavenumberEstimate k_mode;
};

/// The 1D version: every momentum form and the corrected kernels of the 2D study, 21 free particles, T = xi - 1;
/// writes onedim_ke.csv and onedim_runs.csv.
inline std::vector<Row1D> run_1d(const Config& c) {
  std::cout << "1D: WaveForm1D, 21 free particles, T = xi - 1\n";
  std::vector<Row1D> rows1;
  Kernel<1> k(KernelType::CubicSpline);
  const double h = 1.3;
  auto set = make_lattice<1>(LatticeType::Line, 21, {.spacing = 1.0, .support_radius = k.support_radius(h)});
  auto disc = make_discretisation(set, k, h);
  const int centre = 10;
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(disc->dofs());
  v0[centre] = 1e-10;
  // Excited class: reflection about the centre, (T f)_i = -f_{20 - i}; the kick has T v0 = -v0.
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(21, 11);
  for (int i = 0; i <= 10; ++i) {
    Q(i, i) = 1;
    Q(20 - i, i) = 1;  // T f = -f  <=>  f_{20-i} = f_i
    Q.col(i).normalize();
  }
  const Eigen::VectorXd x1 = disc->free_positions().col(0);
  CsvWriter ke1(c.out + "/onedim_ke.csv", {"form", "T", "t", "kinetic"});
  const double detect1 = detection_floor(c.t_end_1d, c.onset);  // log(onset) / (2 t_end_1d)
  // The four momentum forms (analytic Jacobian of Powell 3.40 available) and the corrected kernels of the 2D study.
  struct Form1D {
    std::string name;
    MomentumForm form;
    std::shared_ptr<const GradientProvider<1>> provider;
    CorrectedOperator corrected;
  };
  std::vector<Form1D> forms1;
  for (MomentumForm form : all_momentum_forms())
    forms1.push_back({momentum_form_name(form), form, nullptr, CorrectedOperator::Auto});
  forms1.push_back(
      {"ncsph", MomentumForm::Plus, make_gradient_provider<1>(Correction::Ncsph), CorrectedOperator::Both});
  forms1.push_back({"cij", MomentumForm::Uncorrected,
                    make_gradient_provider<1>(Correction::LocalPolish, {.counting = NeighbourCounting::BoundaryLevel,
                                                                        .first_step_shepard = true}),
                    CorrectedOperator::Divergence});
  for (const Form1D& f1 : forms1)
    for (double xi : c.xis) {
      Row1D r{.form = f1.name, .T = xi - 1};
      auto force =
          std::make_shared<WaveForm1D>(disc, f1.form, r.T, f1.provider, WaveForm1DOptions{.corrected = f1.corrected});
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(force->dofs());
      const Eigen::MatrixXd A(jacobian(*force, zero));
      r.gamma_cs = matrix_growth(A).gamma;
      if (!f1.provider)
        r.gamma_analytic = matrix_growth(Eigen::MatrixXd(analytic_jacobian_1d(set, k, h, f1.form).at(r.T))).gamma;
      const LinearGrowth ge = matrix_growth(Q.transpose() * A * Q, true);
      r.gamma_exc = ge.gamma;
      if (ge.mode.size()) r.k_mode = dominant_wavenumber(Q * ge.mode, x1, false);
      GrowthRunOptions o;
      o.dt = 0.3 * h;  // c = 1
      o.t_end = c.t_end_1d;
      o.displacement_limit = 0.1;
      o.linear_limit = 1e-3;
      o.record_every = 2;
      r.run = run_growth_test<1>(disc, force, Eigen::VectorXd(), v0, o);
      if (r.run.fit.grew && r.gamma_exc > 0) r.ratio = r.run.fit.gamma / r.gamma_exc;
      r.lin_verdict = linear_verdict(r.gamma_exc, detect1);
      r.run_verdict = r.run.blew_up() ? "blow-up" : (r.run.fit.grew ? "growth" : "bounded");
      for (std::size_t q = 0; q < r.run.t.size(); q += 4) ke1.row({r.form, r.T, r.run.t[q], r.run.kinetic[q]});
      std::printf("  1D %-12s T = %+.2f: %-8s gamma meas %-8s pred %-8s (cs %s, analytic %s) ratio %s\n",
                  r.form.c_str(), r.T, r.run_verdict.c_str(), sig(r.run.fit.gamma, 4).c_str(),
                  sig(r.gamma_exc, 4).c_str(), sig(r.gamma_cs, 4).c_str(), sig(r.gamma_analytic, 4).c_str(),
                  sig(r.ratio, 3).c_str());
      rows1.push_back(std::move(r));
    }
  CsvWriter csv(c.out + "/onedim_runs.csv", {"form", "T", "status", "t_stop", "grew", "gamma_measured", "fit_r2",
                                             "gamma_linear_all_cs", "gamma_linear_all_analytic", "gamma_linear_excited",
                                             "ratio", "linear_verdict", "run_verdict", "mode_k_dx_over_pi"});
  for (const Row1D& r : rows1)
    csv.row({r.form, r.T, run_status_name(r.run.status), r.run.t_stop, r.run.fit.grew ? 1 : 0, r.run.fit.gamma,
             r.run.fit.fit.r2, r.gamma_cs, r.gamma_analytic, r.gamma_exc, r.ratio, r.lin_verdict, r.run_verdict,
             r.k_mode.k_projection});
  return rows1;
}

}  // namespace swegle_study
