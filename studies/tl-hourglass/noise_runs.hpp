#pragma once
// Part (c) of the tl-hourglass study, the explicit runs from a noisy initial velocity: 1D periodic, 1D clamped,
// 2D periodic and 2D block (plain gradient, difference sum; hourglass_cases.hpp) with c_HG = 0, 0.1, 1, initial
// velocity uniform random in +-1e-3 c (fixed seed, mean removed on periodic lattices), leap-frog at half the limit
// for ten transit times n dx / c; the zigzag amplitude = RMS of D2 u / 4 (the sawtooth's amplitude for a sawtooth).
// Holds the zigzag fraction of a field, the runs of one lattice and the table noise.csv with its Markdown table.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "hourglass_cases.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/run.hpp"
#include "sphstab/integrate/run_observer.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/spectral/zigzag_modes.hpp"

namespace hourglass {

/// Zigzag fraction of a displacement field phi (dofs): max over axes a of ||D2_a phi||^2 / (16 ||phi||^2), D2_a the
/// second difference along a over the free block (zero outside it, wrapped when periodic). The sawtooth and every
/// pattern alternating along an axis give 1, smooth fields ~ 0, a wave of wavenumber k along a gives
/// (1 - cos k)^2 / 4 (0.5 at k = 0.64 pi).
template <int Dim>
double zigzag_fraction(const Eigen::VectorXd& phi, const std::vector<std::array<int, Dim>>& g, int n, bool periodic) {
  std::vector<int> slot(static_cast<std::size_t>(std::pow(n, Dim)), -1);
  auto key = [n](std::array<int, Dim> ix) {
    int k = 0;
    for (int a = Dim - 1; a >= 0; --a) k = k * n + ix[a];
    return k;
  };
  for (std::size_t f = 0; f < g.size(); ++f) slot[key(g[f])] = static_cast<int>(f);
  auto value = [&](std::array<int, Dim> ix, int c) {
    for (int a = 0; a < Dim; ++a) {
      if (periodic) ix[a] = (ix[a] + n) % n;
      if (ix[a] < 0 || ix[a] >= n) return 0.0;
    }
    return phi[Dim * slot[key(ix)] + c];
  };
  double best = 0;
  for (int a = 0; a < Dim; ++a) {
    double s = 0;
    for (std::size_t f = 0; f < g.size(); ++f)
      for (int c = 0; c < Dim; ++c) {
        auto p = g[f], m = g[f];
        ++p[a];
        --m[a];
        const double d2 = value(p, c) - 2 * phi[Dim * f + c] + value(m, c);
        s += d2 * d2;
      }
    best = std::max(best, s / (16 * phi.squaredNorm()));
  }
  return best;
}

/// noise.csv and the Markdown table of the noise runs.
struct NoiseTables {
  CsvWriter csv;
  std::string md_noise;
  explicit NoiseTables(const std::string& out)
      : csv(out + "/noise.csv", {"config", "hourglass", "time", "zigzag_amplitude", "rms_displacement"}) {}
};

/// The noise runs of one lattice.
template <int Dim>
void noise_run(const Config& cfg, NoiseTables& tables) {
  auto d = lattice<Dim>(cfg);
  const auto g = grid_indices<Dim>(*d, 1.0).index;
  for (double chg : {0.0, 0.1, 1.0}) {
    auto tl = form<Dim>(d, kVariants[0], chg);
    Eigen::VectorXd v0 = study::random_vector(tl.dofs(), 1e-3, 11);  // |v| <= 1e-3 c
    // no drift: remove the mean velocity per component
    if (cfg.periodic)
      for (int c = 0; c < Dim; ++c) {
        double mean = 0;
        for (int f = 0; f < d->free_count(); ++f) mean += v0[Dim * f + c];
        mean /= d->free_count();
        for (int f = 0; f < d->free_count(); ++f) v0[Dim * f + c] -= mean;
      }
    const double dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
    const double t_end = 10.0 * cfg.n;  // ten transit times n dx / c (c = 1 in lattice units)
    SecondOrderSystem sys;
    sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) { tl.acceleration(u, a); };
    sys.dofs_per_particle = Dim;
    LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), v0);
    const long steps = static_cast<long>(std::ceil(t_end / dt));
    const double step = t_end / steps;
    double zig_end = 0, zig_max = 0;
    SnapshotFunction zigzag([&](const StepView& s) {
      // zigzag amplitude: ||u|| sqrt(zigzag fraction) / sqrt(N), the RMS of the second difference / 4
      const double rms = s.u.norm() / std::sqrt(double(d->free_count()));
      const double zig = s.u.norm() > 0 ? rms * std::sqrt(zigzag_fraction<Dim>(s.u, g, cfg.n, cfg.periodic)) : 0;
      tables.csv.row({cfg.name, chg, s.time, zig, rms});
      zig_end = zig;
      zig_max = std::max(zig_max, zig);
    });
    RunOptions ro{.dt = step, .max_steps = steps, .snapshot_every = static_cast<int>(std::max(1L, steps / 200))};
    ro.observers = {&zigzag};
    if (const RunResult r = run(stepper, ro); !r.completed()) std::cerr << "noise run: " << r.message << "\n";
    study::md_row(tables.md_noise, {cfg.name, study::sig(chg, 2), study::sig(step, 3), std::to_string(steps),
                                    study::sig(zig_max, 3), study::sig(zig_end, 3)});
    std::cout << "noise " << cfg.name << " c_HG = " << chg << ": zigzag max " << zig_max << "\n";
  }
}

}  // namespace hourglass
