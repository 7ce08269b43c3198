#pragma once
// The tensile (and compressive) instability of the updated-Lagrangian minus/plus pair of the speed-vs-error study
// [Swegle1995; Powell2012, ch. 3], by two routes:
//   - linearised: A = -da/du about a uniform strain of ±2 % by finite differences, min Re of its eigenvalues and the
//     growth rate sqrt(-min Re μ) (ul_linearised.csv);
//   - seeded: the growth of a sawtooth of amplitude 1e-8 dx on the bar stretched by 2 % (ul_tensile_seed.csv).
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bar_formulations.hpp"
#include "common/study.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/time_step.hpp"
#include "sphstab/io/csv.hpp"

namespace speed_error {

/// One row of ul_linearised.csv.
struct LinRow {
  std::string kernel;
  double hr, strain, minre, growth;
};

/// The linearised UL minus/plus bar per kernel, h/dx and strain +2 %, 0, -2 %, written to <out>/ul_linearised.csv.
inline std::vector<LinRow> ul_linearised(const std::string& out, const std::vector<KernelType>& kernels,
                                         const std::vector<double>& ratios) {
  // UL (minus gradient + plus divergence, the consistent pair) linearised about a uniform strain of ±2 % (the strain
  // scale v0/c of this problem), n = 100, no ghosts (a uniformly strained free bar is consistent there):
  // A = -da/du by finite differences (dense), min Re of its eigenvalues. Negative = exponentially growing mode of
  // ü = -A u for every dt (tensile / compressive instability, Swegle; Powell ch. 3). TL has no such term.
  CsvWriter lin_csv(out + "/ul_linearised.csv",
                    {"kernel", "h_over_dx", "strain", "min_re_mu", "growth_rate_per_us", "max_abs_mu"});
  std::vector<LinRow> lin_rows;
  for (KernelType kt : kernels)
    for (double hr : ratios)
      for (double strain : {0.02, 0.0, -0.02}) {
        // skin 5 dx: no neighbour rebuilds between the probes
        ElasticBar1D ul({.particles = 100,
                         .kernel = kt,
                         .h_over_dx = hr,
                         .gradient = StrainGradient::Minus,
                         .divergence = StressDivergence::Plus,
                         .boundary = BarBoundary::None,
                         .frame = LagrangianFrame::Updated,
                         .skin_over_dx = 5.0});
        const int n = ul.size();
        Eigen::VectorXd u0 = strain * (ul.positions().array() - 0.5).matrix(), a0(n), a1(n);
        ul.acceleration(u0, a0);
        Eigen::MatrixXd A(n, n);
        const double eps = 1e-7 * ul.spacing();
        for (int j = 0; j < n; ++j) {
          Eigen::VectorXd u = u0;
          u[j] += eps;
          ul.acceleration(u, a1);
          A.col(j) = -(a1 - a0) / eps;
        }
        Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(A, false).eigenvalues();
        const double minre = mu.real().minCoeff(), maxab = mu.cwiseAbs().maxCoeff();
        // Below 1e-9 |mu|max the sign is finite-difference noise.
        const double growth = minre < -1e-9 * maxab ? std::sqrt(-minre) : 0.0;
        lin_csv.row({kernel_name(kt), hr, strain, minre, growth, maxab});
        lin_rows.push_back({kernel_name(kt), hr, strain, minre, growth});
      }
  return lin_rows;
}

/// The seeded sawtooth: its growth rate between amplitudes 1e-7 and 1e-5 dx and the largest amplitude reached.
struct SeededGrowth {
  double rate = NAN, saturation = 0;
};

inline SeededGrowth seeded_sawtooth(const std::string& out, double courant, double c) {
  // Second route to the same growth rate: seed the sawtooth mode (amplitude 1e-8 dx) on the uniformly stretched
  // (+2 %) bar, cubic, h/dx = 1, n = 100, UL minus/plus, and measure the growth of its interior amplitude.
  SeededGrowth g;
  CsvWriter seed_csv(out + "/ul_tensile_seed.csv", {"t", "sawtooth_amplitude_over_dx"});
  ElasticBar1D ul({.particles = 100,
                   .h_over_dx = 1.0,
                   .gradient = StrainGradient::Minus,
                   .divergence = StressDivergence::Plus,
                   .boundary = BarBoundary::None,
                   .frame = LagrangianFrame::Updated});
  const int n = ul.size();
  Eigen::VectorXd base = 0.02 * (ul.positions().array() - 0.5).matrix(), saw(n);
  for (int i = 0; i < n; ++i) saw[i] = (i % 2) ? 1.0 : -1.0;
  LeapfrogStepper st(ul.system(), base + 1e-8 * ul.spacing() * saw, Eigen::VectorXd::Zero(n));
  const double dt = cfl_time_step(courant, ul.h(), c);
  double t_a = NAN, t_b = NAN;
  SnapshotFunction seed([&](const StepView& s) {
    if (s.time >= 0.9) return;  // the state the last step reached is not part of the record
    const Eigen::VectorXd d = s.u - base;
    const double amp = std::abs(d.segment(30, 40).dot(saw.segment(30, 40))) / 40.0 / ul.spacing();
    seed_csv.row({s.time, amp});
    if (std::isnan(t_a) && amp > 1e-7) t_a = s.time;
    if (std::isnan(t_b) && amp > 1e-5) t_b = s.time;
    g.saturation = std::max(g.saturation, amp);
  });
  study::run_probed(st, dt, 0.9, seed);
  g.rate = std::log(1e-5 / 1e-7) / (t_b - t_a);
  return g;
}

}  // namespace speed_error
