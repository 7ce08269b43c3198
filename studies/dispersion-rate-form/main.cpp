// Study: every dispersion branch of the rate-form scheme on infinite (periodic) lattices, from the Bloch symbol of
// its exact Jacobian (spectral/rate_form_symbol.hpp): the acoustic branches and the density/stress branches, the
// unstable wavevectors in tension and compression, and three checks against theory in the same run: GMS (5.8)/(5.9)
// (spectral/lattice_dispersion.hpp, derived independently), the continuum (4.9)/(4.10) at long wavelength, and in 1D
// the infinite-lattice critical stress against the closed form T/(1 - T) of fourier_symbol.hpp.
//
// Writes to --out DIR: branches_2d.csv, growth_2d.csv, long_wave_2d.csv, bar_1d.csv, summary.json.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "common/cli.hpp"
#include "common/driver.hpp"
#include "common/study.hpp"
#include "dispersion_cases.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"
#include "sphstab/spectral/lattice_dispersion.hpp"
#include "sphstab/spectral/rate_form_symbol.hpp"

using namespace sphstab;
using namespace dispersion_study;

namespace {}  // namespace

int main(int argc, char** argv) {
  study::DriverCli cli{
      "dispersion-rate-form: all dispersion branches of the rate-form scheme from its Bloch symbol",
      "results/dispersion-rate-form",
      "the study's test case: gms and ncsph at h/dx 1.3, --path-points 16, --grid 9 (unless given); 1D at "
      "h/dx 0.8, 1.9, 3.0"};
  int path_points = 48, grid = 33;
  cli.add_quick_option("--path-points", path_points, 16, "points per segment of Gamma-X-M-Gamma")
      ->check(CLI::Range(4, 2000));
  cli.add_quick_option("--grid", grid, 9, "k points per axis of the growth map over [0, pi]^2")
      ->check(CLI::Range(5, 400));
  if (const auto exit = cli.parse(argc, argv)) return *exit;
  const auto t0 = study::Clock::now();
  const double cp = kSteel.p_wave_speed();

  // --- 2D square lattice: branches along Gamma-X-M-Gamma, growth over the Brillouin zone ---------------------------
  const std::vector<double> hs = cli.quick ? std::vector<double>{1.3} : std::vector<double>{1.3, 1.5};
  const std::vector<double> xis{0.98, 1.0, 1.02};
  std::ofstream branches(cli.out + "/branches_2d.csv"), growth(cli.out + "/growth_2d.csv");
  branches << "formulation,h_over_dx,xi,s,kx_over_pi,ky_over_pi,omega_l,omega_t,growth_l,growth_t,"
              "longitudinality_l,growth_all,slaved_lambda,gms_rel_diff\n";
  growth << "formulation,h_over_dx,xi,box,growth_rate,kx_over_pi,ky_over_pi,longitudinality,max_slaved_lambda,"
            "invariance_residual,gms_rel_diff,status\n";
  std::string growth_table;
  double worst_slaved = 0, worst_invariance = 0, worst_gms = 0;
  const Kernel<2> kernel2(KernelType::CubicSpline);
  for (const Formulation& f : formulations(cli.quick))
    for (double h : hs)
      for (double xi : xis) {
        const int n = box_for(h);
        const RateFormSymbol<2> symbol = symbol_of<2>(f.options, h, xi, n);
        worst_invariance = std::max(worst_invariance, symbol.invariance_residual);
        const bool gms = f.name == "gms";
        const UniformState st = with_artificial_stress(gms_state(xi), 0.3);
        double gms_diff = 0, slaved = 0;
        // Path Gamma (0,0) -> X (pi,0) -> M (pi,pi) -> Gamma, arc length s in units of pi/dx.
        for (int seg = 0; seg < 3; ++seg)
          for (int q = (seg == 0 ? 0 : 1); q <= path_points; ++q) {
            const double t = static_cast<double>(q) / path_points;
            Eigen::Vector2d k = seg == 0   ? Eigen::Vector2d(t, 0)
                                : seg == 1 ? Eigen::Vector2d(1, t)
                                           : Eigen::Vector2d(1 - t, 1 - t);
            const double s = seg == 0 ? t : seg == 1 ? 1 + t : 2 + std::sqrt(2.0) * t;
            k *= M_PI;
            const RateFormDispersion d = rate_form_dispersion(symbol, k);
            slaved = std::max(slaved, d.slaved_lambda / cp);
            double rel = NAN;
            if (gms && k.norm() > 0) {
              const auto g = lattice_dispersion(LatticeType::Square, kernel2, h, k, st,
                                                {.exponent = 4, .perturbed_artificial_stress = true});
              std::array<double, 2> a{g.omega2[0].real(), g.omega2[1].real()};
              std::sort(a.begin(), a.end(), std::greater<>());
              // omega^2 vanishes at X and M without stress: measure against the continuum's c_P^2 |k|^2.
              const double scale = std::abs(a[0]) + std::abs(a[1]) + cp * cp * k.squaredNorm();
              rel = std::max(std::abs(d.omega2[0].real() - a[0]), std::abs(d.omega2[1].real() - a[1])) / scale;
              gms_diff = std::max(gms_diff, rel);
            }
            // omega = sqrt(omega^2) where real and positive; growth = sqrt(-omega^2) where negative.
            auto omega = [&](int b) { return std::sqrt(std::max(d.omega2[b].real(), 0.0)) / cp; };
            auto grow = [&](int b) { return std::sqrt(std::max(-d.omega2[b].real(), 0.0)) / cp; };
            const double longitudinality =
                k.norm() > 0 ? std::abs(d.polarisation.col(0).dot(k.normalized().cast<std::complex<double>>())) : NAN;
            branches << csv_line(
                {f.name, study::fixed(h, 1), study::fixed(xi, 2), format_number(s, 8), format_number(k[0] / M_PI, 8),
                 format_number(k[1] / M_PI, 8), format_number(omega(0), 10), format_number(omega(1), 10),
                 format_number(grow(0), 10), format_number(grow(1), 10), format_number(longitudinality, 6),
                 format_number(d.growth_rate / cp, 10), format_number(d.slaved_lambda / cp, 3), format_number(rel, 3)});
          }
        // Growth over the quarter zone [0, pi]^2 (the square lattice's mirror symmetry gives the rest).
        double best = 0, long_best = NAN;  // largest -omega^2 judged unstable; |v . k|/|k| of its mode
        Eigen::Vector2d kbest = Eigen::Vector2d::Zero();
        for (int a = 0; a < grid; ++a)
          for (int b = 0; b < grid; ++b) {
            const Eigen::Vector2d k(M_PI * a / (grid - 1), M_PI * b / (grid - 1));
            if (a == 0 && b == 0) continue;  // k = 0: translation
            const RateFormDispersion d = rate_form_dispersion(symbol, k);
            slaved = std::max(slaved, d.slaved_lambda / cp);
            // Unstable where -omega^2 exceeds rounding: 1e-10 of c_P^2 |k|^2 (both branches vanish at X and M for
            // some formulations, so not relative to the branches themselves).
            const int b_min = d.omega2[0].real() < d.omega2[1].real() ? 0 : 1;
            const double g2 = -d.omega2[b_min].real();
            if (g2 > 1e-10 * cp * cp * k.squaredNorm() && g2 > best)
              best = g2, kbest = k,
              long_best = std::abs(d.polarisation.col(b_min).dot(k.normalized().cast<std::complex<double>>()));
          }
        best = std::sqrt(best) / cp;
        const bool unstable = best > 0;
        worst_slaved = std::max(worst_slaved, slaved);
        if (gms) worst_gms = std::max(worst_gms, gms_diff);
        growth << csv_line(
            {f.name, study::fixed(h, 1), study::fixed(xi, 2), std::to_string(n), format_number(best, 10),
             unstable ? format_number(kbest[0] / M_PI, 6) : "nan", unstable ? format_number(kbest[1] / M_PI, 6) : "nan",
             unstable ? format_number(long_best, 4) : "nan", format_number(slaved, 3),
             format_number(symbol.invariance_residual, 3), gms ? format_number(gms_diff, 3) : "nan", "successful"});
        if (xi != 1.0)
          study::md_row(
              growth_table,
              {f.name, study::fixed(h, 1), study::fixed(xi, 2), unstable ? study::sig(best, 3) : "0",
               unstable ? "(" + study::fixed(kbest[0] / M_PI, 2) + ", " + study::fixed(kbest[1] / M_PI, 2) + ")" : "-",
               !unstable         ? "-"
               : long_best > 0.9 ? "longitudinal"
               : long_best < 0.1 ? "transverse"
                                 : "mixed"});
        std::printf("2D %s h %.1f xi %.2f: growth %.3g c_P/dx (%.0f s)\n", f.name.c_str(), h, xi, best,
                    study::seconds_since(t0));
        std::fflush(stdout);
      }

  // --- Long waves: omega^2 / k^2 against the continuum GMS (4.9)/(4.10) with a uniaxial prestress ---------------
  std::ofstream longwave(cli.out + "/long_wave_2d.csv");
  longwave << "formulation,h_over_dx,k_dx,direction,rel_error_l,rel_error_t\n";
  std::string long_table;
  double ncsph_order = NAN;
  for (const Formulation& f : formulations(cli.quick)) {
    if (f.name == "sph-as" || f.name == "gms") continue;  // R is ignored by the continuum relation
    for (double h : hs) {
      const int n = box_for(h);
      const Kernel<2> kernel(KernelType::CubicSpline);
      const ParticleSet<2> set = make_lattice<2>(
          LatticeType::Square, n, {.spacing = 1.0, .support_radius = kernel.support_radius(h), .periodic = true});
      Eigen::VectorXd dev(3);
      dev << 0.004, -0.002, 0.0;  // zeta = 0.003 (stress units of E = 2.1)
      const double xi = 1.01;
      const RateFormScheme<2> scheme(make_discretisation(set, kernel, h), kSteel, f.options, kSteel.density() / xi,
                                     dev);
      const RateFormSymbol<2> symbol = rate_form_symbol(scheme, scheme.uniform_state());
      UniformState st = gms_state(xi);
      st.sxx = dev[0];
      st.syy = dev[1];
      std::vector<double> ks, errs;
      for (double kdx : {0.16, 0.08, 0.04, 0.02, 0.01})
        for (int dir = 0; dir < 2; ++dir) {
          const Eigen::Vector2d k = kdx * (dir == 0 ? Eigen::Vector2d(1, 0) : Eigen::Vector2d(2, 1).normalized());
          const auto c = continuum_dispersion(k, st);
          std::array<double, 2> a{c.omega2[0].real(), c.omega2[1].real()};
          std::sort(a.begin(), a.end(), std::greater<>());
          const RateFormDispersion d = rate_form_dispersion(symbol, k);
          const double el = std::abs(d.omega2[0].real() - a[0]) / a[0], et = std::abs(d.omega2[1].real() - a[1]) / a[1];
          longwave << csv_line({f.name, study::fixed(h, 1), format_number(kdx, 4), dir == 0 ? "x" : "(2,1)",
                                format_number(el, 6), format_number(et, 6)});
          if (dir == 1) ks.push_back(kdx), errs.push_back(std::max(el, et));
        }
      const double order = study::loglog_slope({ks.end() - 3, ks.end()}, {errs.end() - 3, errs.end()});
      if (f.name == "ncsph" && h == 1.3) ncsph_order = order;
      study::md_row(long_table, {f.name, study::fixed(h, 1), study::sig(errs.back(), 3), study::fixed(order, 2)});
    }
  }

  // --- 1D: infinite-lattice critical stress from the symbol against the closed form --------------------------------
  // Plain SPH at rest: rho omega^2 = (M + sigma0)|g|^2 - 2 sigma0 L (rate_form_symbol.hpp), so at wavenumber k the
  // critical sigma0/M is |g|^2 / (2L - |g|^2) where 2L > |g|^2. The bisection on the symbol's spectrum and this closed
  // form are compared on the same k grid; the grid-free infimum (T/(1 - T), T of fourier_symbol.hpp with n = 2)
  // is reported beside them.
  std::ofstream bar(cli.out + "/bar_1d.csv");
  bar << "formulation,h_over_dx,sigma_crit_over_M_symbol,closed_form_grid,rel_diff,abs_diff,closed_form_infinite,"
         "k_over_pi\n";
  double worst_1d = 0, worst_1d_abs = 0;
  int bar_rows = 0;
  const Kernel<1> kernel1(KernelType::CubicSpline);
  const double M = kSteel.bulk_modulus() + 4 * kSteel.mu() / 3;
  const int kgrid = 400;
  for (int ih = 0; ih <= 22; ih += cli.quick ? 11 : 1) {
    const double h = 0.8 + 0.1 * ih;
    const int n = box_for(h);
    // Unstable at sigma0 = tau M if some grid k in (0, pi] has -omega^2 > 1e-14 c_P^2 k^2.
    auto unstable = [&](double tau) {
      const RateFormSymbol<1> s = symbol_of<1>({}, h, 1.0 / (1 - tau * M / kSteel.bulk_modulus()), n);
      for (int q = 1; q <= kgrid; ++q) {
        const double k = M_PI * q / kgrid;
        if (-rate_form_dispersion(s, Eigen::Matrix<double, 1, 1>(k)).omega2[0].real() > 1e-14 * cp * cp * k * k)
          return true;
      }
      return false;
    };
    // 2L - |g|^2 at rounding level (e.g. L(pi) = 0 exactly for the cubic spline at 1.5 <= h/dx <= 2.5) is not a
    // destabilising denominator: it must exceed 1e-12 of the largest |g|^2 + 2|L| over the grid.
    std::vector<FourierSymbol1D> f(kgrid + 1);
    double fscale = 0;
    for (int q = 1; q <= kgrid; ++q) {
      f[q] = fourier_symbol_1d(kernel1, h, 1.0, M_PI * q / kgrid);
      fscale = std::max(fscale, f[q].g_abs2 + 2 * std::abs(f[q].l_hat));
    }
    double closed = INFINITY, k_at = NAN;
    for (int q = 1; q <= kgrid; ++q) {
      const double d = 2 * f[q].l_hat - f[q].g_abs2;
      if (d > 1e-12 * fscale && f[q].g_abs2 / d < closed) closed = f[q].g_abs2 / d, k_at = M_PI * q / kgrid;
    }
    // sigma0 = -p = K (1 - rho/rho0) = K (1 - 1/xi) < K: search tau in (0, K/(2M)].
    double tau = INFINITY, lo = 1e-9, hi = 0.5 * kSteel.bulk_modulus() / M;
    if (unstable(lo)) {
      tau = 0;
    } else if (unstable(hi)) {
      while (hi - lo > 1e-10 * hi) {
        const double mid = 0.5 * (lo + hi);
        (unstable(mid) ? hi : lo) = mid;
      }
      tau = hi;
    }
    // The search range is (1e-9, K/(2M)]. Below ~1e-6 the instability threshold of the search dominates (growth
    // as sqrt(tau - tau_c) against a fixed omega^2 floor): compare absolutely there, relatively above 1e-4.
    const double cap = 0.5 * kSteel.bulk_modulus() / M;
    const double tc = closed > cap ? INFINITY : closed < 1e-9 ? 0.0 : closed;
    const double diff = tau == tc ? 0.0 : std::abs(tau - tc);
    const double rel = tc >= 1e-4 && std::isfinite(tc) ? diff / tc : NAN;
    if (!std::isnan(rel)) worst_1d = std::max(worst_1d, rel);
    if (tc < 1e-4) worst_1d_abs = std::max(worst_1d_abs, diff);
    const SymbolCriticalTension t = critical_tension_infinite_1d(kernel1, h, 1.0, 2);
    bar << csv_line({"sph", study::fixed(h, 1), format_number(tau, 10), format_number(closed, 10),
                     format_number(rel, 3), format_number(diff, 3),
                     format_number(std::isinf(t.tcrit) ? INFINITY : t.tcrit / (1 - t.tcrit), 10),
                     format_number(k_at / M_PI, 6)});
    ++bar_rows;
  }

  study::Summary s;
  s.set("growth_table", growth_table);
  s.set("long_table", long_table);
  s.set("worst_slaved", worst_slaved, 2);
  s.set("worst_invariance", worst_invariance, 2);
  s.set("worst_gms", worst_gms, 2);
  s.set("ncsph_order", ncsph_order, 3);
  s.set("worst_1d", worst_1d, 2);
  s.set("worst_1d_abs", worst_1d_abs, 2);
  s.set("bar_rows", bar_rows);
  s.set("path_points", path_points);
  s.set("grid", grid);
  study::write_summary(s, cli.out, t0, {.wall_key = "wall_total"});
  std::printf("GMS (5.8)/(5.9) worst %.2g, slaved |lambda| worst %.2g, 1D closed form worst %.2g\n", worst_gms,
              worst_slaved, worst_1d);
  return 0;
}
