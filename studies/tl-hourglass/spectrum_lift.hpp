#pragma once
// Parts (a) and (b) of the tl-hourglass study: the spectrum of A = -da/du at u = 0 (mass-weighted: A already carries
// 1/m) of each lattice and variant of hourglass_cases.hpp against the [Ganzenmueller2015] coefficient c_HG.
// (a) At c_HG = 0: the exact null space of the periodic lattices against the sawtooth / checkerboard patterns, the
//     symbol of the strain operator up to k = pi/dx, the soft zigzag modes of the blocks and the six softest shapes.
// (b) Per c_HG: the softest zigzag and smooth eigenvalues, the closed form of the periodic 1D sawtooth lift
//     mu = 4 c_HG (E/rho) sum_{m odd} W(m dx) dx / (m dx)^2 and the 2 x 2 Bloch symbols of the 2D hourglass
//     wavevectors (lattice_symbols.hpp), and the shift of the softest smooth mode (the fundamental).
// Zigzag: the hourglass_fraction of spectral/zigzag_modes.hpp above kZigzag.
// Holds the computation of one lattice and the tables spectrum.csv, null_modes.csv, symbol.csv, modes.csv, lift.csv
// with their Markdown tables and summary numbers.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "common/study.hpp"
#include "hourglass_cases.hpp"
#include "lattice_symbols.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/spectral/zigzag_modes.hpp"

namespace hourglass {

/// The CSV files and Markdown tables of (a) and (b).
struct SpectrumTables {
  CsvWriter spectrum, null_modes, symbol, modes, lift;
  std::string md_null, md_block, md_lift, md_bloch;
  double closed_worst = 0;  // largest closed-form / Bloch residual over every periodic case and coefficient
  explicit SpectrumTables(const std::string& out)
      : spectrum(out + "/spectrum.csv", {"config", "variant", "hourglass", "rank", "mu", "abs_imag", "zigzag"}),
        null_modes(out + "/null_modes.csv",
                   {"config", "variant", "zero_eigenvalues", "pattern", "residual_rel", "zero_tol"}),
        symbol(out + "/symbol.csv", {"config", "variant", "k_over_pi", "abs_K_symbol", "max_abs_K_symbol"}),
        modes(out + "/modes.csv", {"config", "variant", "rank", "mu", "zigzag", "x", "y", "phi_x", "phi_y"}),
        lift(out + "/lift.csv", {"config", "variant", "hourglass", "mu_zigzag_min", "mu_smooth_min",
                                 "zigzag_below_smooth", "mu_closed_form", "closed_form_residual_rel", "mu_fundamental",
                                 "fundamental_overlap", "fundamental_shift_rel", "max_abs_imag"}) {}
  void summarise(study::Summary& summary) const {
    summary.set("null_modes", md_null);
    summary.set("block_modes", md_block);
    summary.set("lift", md_lift);
    summary.set("bloch", md_bloch);
    summary.set("zigzag_threshold", kZigzag, 2);
    summary.set("closed_form_worst_residual", closed_worst, 2);
  }
};

/// The closed form of a periodic lattice at c_HG = chg and its residual against the spectrum (NaN, NaN for a lattice
/// with fixed layers); the 2D Bloch eigenvalues at c_HG = 1 (difference sum) go to tables.md_bloch.
template <int Dim>
std::pair<double, double> closed_form(const Config& cfg, const Variant& v, double chg, const Discretisation<Dim>& d,
                                      const std::vector<std::array<int, Dim>>& g, const Eigen::MatrixXd& A,
                                      const std::vector<ZigzagMode>& modes, double mu_max, SpectrumTables& tables) {
  // closed form of the periodic 1D sawtooth lift: mu = 4 c E/rho sum_{m odd} W(m) V / m^2 (plain gradient: the
  // TL part vanishes); 2D: the smallest eigenvalue of the Bloch symbols at the three hourglass wavevectors
  double closed = std::nan(""), closed_res = std::nan("");
  if (cfg.periodic && Dim == 1) {
    double s = 0;
    for (int m = 1; m < cfg.n / 2; m += 2) s += d.kernel.value(double(m), d.h) / (m * m);
    closed = 4 * chg * 1.0 * s;  // E / rho = 1, V = dx = 1
    const Eigen::VectorXd saw = patterns<Dim>(g)[1].second;
    closed_res = (A * saw - closed * saw).norm() / mu_max;  // sawtooth: an exact eigenvector, residual 0
  }
  if (cfg.periodic && Dim == 2) {
    closed = std::numeric_limits<double>::infinity();
    closed_res = 0;
    const int f0 = 0;
    for (const auto& kk : std::vector<std::array<double, 2>>{{1, 0}, {0, 1}, {1, 1}}) {
      Eigen::Matrix<double, Dim, 1> k;
      for (int a = 0; a < Dim; ++a) k[a] = std::numbers::pi * kk[a];
      const auto S = bloch_symbol<Dim>(A, d, f0, k);
      Eigen::ComplexEigenSolver<Eigen::Matrix<std::complex<double>, Dim, Dim>> ce(S);
      for (int e = 0; e < Dim; ++e) {
        const double lam = ce.eigenvalues()[e].real();
        closed = std::min(closed, lam);
        // is it in the spectrum of A? distance to the nearest eigenvalue
        double dist = std::numeric_limits<double>::infinity();
        for (const ZigzagMode& m : modes) dist = std::min(dist, std::abs(m.mu - lam));
        closed_res = std::max(closed_res, dist / mu_max);  // each symbol eigenvalue is in the spectrum
        if (chg == 1 && v.sum == StrainSum::Difference)
          study::md_row(tables.md_bloch, {cfg.name, v.name, study::sig(chg, 2),
                                          "(" + study::sig(kk[0], 1) + "," + study::sig(kk[1], 1) + ") pi",
                                          study::sig(lam, 6), study::sig(dist / mu_max, 2)});
      }
    }
  }
  return {closed, closed_res};
}

/// (a) + (b) for one lattice: every variant and coefficient.
template <int Dim>
void spectra(const Config& cfg, SpectrumTables& tables, study::Summary& summary, study::Clock::time_point t0) {
  auto d = lattice<Dim>(cfg);
  const GridIndices<Dim> grid = grid_indices<Dim>(*d, 1.0);
  const auto& g = grid.index;
  for (const Variant& v : kVariants) {
    // the fundamental: the softest smooth mode at c_HG = 0, followed to c_HG > 0 by the largest overlap |phi . phi0|
    double mu_fund0 = std::nan("");
    Eigen::VectorXd phi_fund0;
    for (double chg : kCoefficients) {
      auto tl = form<Dim>(d, v, chg);
      const Eigen::MatrixXd A(jacobian(tl, Eigen::VectorXd::Zero(tl.dofs())));
      const std::vector<ZigzagMode> modes = zigzag_spectrum<Dim>(A, grid);
      const double mu_max = modes.back().mu;
      double max_imag = 0;
      for (const ZigzagMode& m : modes) max_imag = std::max(max_imag, m.imag);
      for (std::size_t r = 0; r < std::min<std::size_t>(modes.size(), 30); ++r)
        tables.spectrum.row({cfg.name, v.name, chg, static_cast<long>(r), modes[r].mu, modes[r].imag, modes[r].zigzag});
      // zero modes (periodic): |mu| < 1e-10 mu_max; the patterns' residuals ||A p|| / ||A||
      const double zero_tol = 1e-10 * mu_max;
      int zeros = 0;
      for (const ZigzagMode& m : modes) zeros += std::abs(m.mu) < zero_tol;
      // the softest smooth mode (not zigzag, not a zero mode) and the softest zigzag mode that is not a rigid
      // translation (zero modes whose zigzag fraction is small)
      double mu_smooth = std::nan(""), mu_zig = std::nan("");
      int zig_below = 0;
      for (const ZigzagMode& m : modes)
        if (m.zigzag < kZigzag && std::abs(m.mu) >= zero_tol && std::isnan(mu_smooth)) mu_smooth = m.mu;
      for (const ZigzagMode& m : modes)
        if (m.zigzag >= kZigzag && std::isnan(mu_zig)) mu_zig = m.mu;
      for (const ZigzagMode& m : modes) zig_below += m.zigzag >= kZigzag && m.mu < mu_smooth;
      if (chg == 0)
        for (const ZigzagMode& m : modes)
          if (m.zigzag < kZigzag && std::abs(m.mu) >= zero_tol) {
            mu_fund0 = m.mu;
            phi_fund0 = m.phi;
            break;
          }
      double mu_fund = std::nan(""), overlap = 0;
      for (const ZigzagMode& m : modes)
        if (std::abs(m.phi.dot(phi_fund0)) > overlap) {
          overlap = std::abs(m.phi.dot(phi_fund0));
          mu_fund = m.mu;
        }
      const auto [closed, closed_res] = closed_form<Dim>(cfg, v, chg, *d, g, A, modes, mu_max, tables);
      if (!std::isnan(closed_res)) tables.closed_worst = std::max(tables.closed_worst, closed_res);
      if (cfg.periodic && Dim == 1 && chg == 1 && v.name == "plain-difference")
        summary.set("sawtooth_lift_per_coefficient", closed, 6);
      tables.lift.row({cfg.name, v.name, chg, mu_zig, mu_smooth, static_cast<long>(zig_below), closed, closed_res,
                       mu_fund, overlap, mu_fund / mu_fund0 - 1, max_imag});
      if (v.sum == StrainSum::Difference && (chg == 0 || chg == 0.1 || chg == 1))
        study::md_row(tables.md_lift,
                      {cfg.name, v.name, study::sig(chg, 2), study::sig(mu_zig, 4),
                       std::isnan(closed) ? "-" : study::sig(closed, 4), study::sig(mu_smooth, 4),
                       study::sig(mu_fund, 4), study::fixed(100 * (mu_fund / mu_fund0 - 1), 3, true) + " %",
                       study::fixed(overlap, 3), std::to_string(zig_below)});
      if (chg != 0 || v.projection == HourglassProjection::Full) continue;
      // ---- at c_HG = 0: null modes, symbols, shapes ----
      if (cfg.periodic) {
        for (const auto& [name, p] : patterns<Dim>(g)) {
          const double res = (A * p).norm() / mu_max;
          tables.null_modes.row({cfg.name, v.name, static_cast<long>(zeros), name, res, zero_tol});
        }
        double worst = 0;
        for (const auto& [name, p] : patterns<Dim>(g)) worst = std::max(worst, (A * p).norm() / mu_max);
        study::md_row(tables.md_null,
                      {cfg.name, v.name, std::to_string(zeros),
                       std::to_string(static_cast<int>(patterns<Dim>(g).size())), study::sig(worst, 2)});
        // symbol of the strain operator along x, k = 2 pi q / n from 0 to pi (particle in the middle)
        {
          const int f = d->free_count() / 2;
          double kmax = 0;
          std::vector<std::pair<double, double>> line;
          for (int q = 0; q <= cfg.n / 2; ++q) {
            const double s = strain_symbol<Dim>(tl, f, 2 * std::numbers::pi * q / cfg.n);
            kmax = std::max(kmax, s);
            line.push_back({2.0 * q / cfg.n, s});
          }
          for (auto [kq, s] : line) tables.symbol.row({cfg.name, v.name, kq, s, kmax});
          summary.set("symbol_at_pi_" + cfg.name + "_" + v.name, line.back().second / kmax, 2);
        }
      } else {
        double mu_zig_first = mu_zig;
        study::md_row(tables.md_block,
                      {cfg.name, v.name, std::to_string(zig_below), study::sig(mu_zig_first, 4),
                       study::sig(mu_smooth, 4), study::sig(mu_zig_first / mu_smooth, 3), study::sig(max_imag, 2)});
      }
      if (v.sum == StrainSum::Difference) {  // shapes: the 6 softest modes
        for (int r = 0; r < 6; ++r)
          for (int f = 0; f < d->free_count(); ++f)
            tables.modes.row({cfg.name, v.name, static_cast<long>(r), modes[r].mu, modes[r].zigzag,
                              d->particles.x(d->free[f], 0), Dim == 2 ? d->particles.x(d->free[f], 1) : 0.0,
                              modes[r].phi[Dim * f], Dim == 2 ? modes[r].phi[Dim * f + 1] : 0.0});
      }
    }
    std::cout << cfg.name << " " << v.name << " done (" << study::fixed(study::seconds_since(t0), 1) << " s)\n";
  }
}

}  // namespace hourglass
