// Zero-energy (hourglass) modes of the finite-strain total-Lagrangian form (forms/finite_strain_total_lagrangian.hpp)
// and the [Ganzenmueller2015] hourglass control term (FiniteStrainOptions::hourglass):
// (a) the spectrum of A = -da/du at u = 0 (mass-weighted: A already carries 1/m) on 1D lines and 2D square blocks,
//     periodic and with fixed layers, plain and NCSPH reference gradients, difference and direct strain sums: the
//     exact null space of the periodic lattices identified with the sawtooth / checkerboard patterns, the Fourier
//     symbol of the strain operator at k = pi/dx, the soft zigzag modes of the blocks and their shapes;
// (b) the lift of those eigenvalues against the coefficient c_HG, with the closed form of the periodic 1D sawtooth
//     and the 2 x 2 Bloch symbols of the 2D hourglass wavevectors, and the shift of the softest smooth mode;
// (c) the accuracy cost on Ismail's 1D validation bar (studies/tl-bar-wave-1d: Hooke 1D stress, clamped end) and
//     explicit leap-frog runs from a noisy initial velocity, with and without control.
// Writes to --out DIR: spectrum.csv, null_modes.csv, symbol.csv, modes.csv, lift.csv, bar.csv, bar_probes.csv,
// noise.csv, summary.json.
#include <CLI/CLI.hpp>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/integrate/leapfrog.hpp"
#include "sphstab/integrate/stable_time_step.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/models/hooke.hpp"
#include "sphstab/models/neo_hookean.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/spectral/zigzag_modes.hpp"

using namespace sphstab;
namespace fs = std::filesystem;

namespace {

// Lattice units for (a), (b) and the noise runs: dx = 1, E = 1, rho = 1 (eigenvalues in E / (rho dx^2)).
constexpr double kNu = 0.3;
const std::vector<double> kCoefficients{0, 0.01, 0.03, 0.1, 0.3, 1};
constexpr double kZigzag =
    0.5;  // a mode is "zigzag" when its hourglass_fraction (spectral/zigzag_modes.hpp) exceeds this

struct Config {
  std::string name;
  int dim;
  bool periodic;
  KernelType kernel;
  double h;  // h / dx
  int n;     // free particles per side
};
struct Variant {
  std::string name;
  bool ncsph;
  StrainSum sum;
  HourglassProjection projection = HourglassProjection::Bond;
};
const std::vector<Config> kConfigs{
    {"1d-periodic-cubic", 1, true, KernelType::CubicSpline, 1.3, 40},
    {"1d-clamped-cubic", 1, false, KernelType::CubicSpline, 1.3, 40},
    {"1d-clamped-mollifier", 1, false, KernelType::ModifiedMollifier, 2.75, 40},
    {"2d-periodic-cubic", 2, true, KernelType::CubicSpline, 1.3, 12},
    {"2d-block-cubic", 2, false, KernelType::CubicSpline, 1.3, 12},
};
const std::vector<Variant> kVariants{
    {"plain-difference", false, StrainSum::Difference},
    {"plain-direct", false, StrainSum::Direct},
    {"ncsph-difference", true, StrainSum::Difference},
    {"ncsph-direct", true, StrainSum::Direct},
    // the term's full-vector variant (not the paper's); at c_HG = 0 plain-difference
    {"plain-difference-full", false, StrainSum::Difference, HourglassProjection::Full}};

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> lattice(const Config& c) {
  const Kernel<Dim> k(c.kernel);
  const ParticleSet<Dim> set = make_lattice<Dim>(Dim == 1 ? LatticeType::Line : LatticeType::Square, c.n,
                                                 {.spacing = 1.0,
                                                  .fixed_layers = c.periodic ? 0 : -1,
                                                  .support_radius = c.periodic ? 0.0 : 2 * k.support_radius(c.h),
                                                  .periodic = c.periodic});
  return make_discretisation(set, k, c.h);
}

template <int Dim>
FiniteStrainTotalLagrangian<Dim> form(std::shared_ptr<const Discretisation<Dim>> d, const Variant& v, double chg,
                                      double E = 1.0, double rho = 1.0) {
  auto m = std::make_shared<NeoHookean<Dim>>(LameParameters::from_young_poisson(E, kNu));
  FiniteStrainOptions<Dim> o{.strain_sum = v.sum, .hourglass = chg, .hourglass_projection = v.projection};
  if (v.ncsph) o.gradient = make_gradient_provider<Dim>(Correction::Ncsph);
  return FiniteStrainTotalLagrangian<Dim>(d, m, rho, o);
}

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

/// The periodic hourglass patterns: translations and, per wavevector with components in {0, pi} (not all 0), each
/// displacement component. 1D: translation + sawtooth; 2D: 2 translations + 3 wavevectors x 2 components.
template <int Dim>
std::vector<std::pair<std::string, Eigen::VectorXd>> patterns(const std::vector<std::array<int, Dim>>& g) {
  std::vector<std::pair<std::string, Eigen::VectorXd>> out;
  const int nk = 1 << Dim;
  for (int kbits = 0; kbits < nk; ++kbits)
    for (int c = 0; c < Dim; ++c) {
      Eigen::VectorXd p = Eigen::VectorXd::Zero(Dim * static_cast<long>(g.size()));
      for (std::size_t f = 0; f < g.size(); ++f) {
        int parity = 0;
        for (int a = 0; a < Dim; ++a)
          if (kbits >> a & 1) parity += g[f][a];
        p[Dim * f + c] = parity % 2 ? -1.0 : 1.0;
      }
      std::string name = kbits == 0 ? "translation" : (Dim == 1 ? "sawtooth" : "k=(");
      if (Dim == 2 && kbits) name += std::string(kbits & 1 ? "pi," : "0,") + (kbits & 2 ? "pi)" : "0)");
      if (Dim == 2) name += c == 0 ? " u_x" : " u_y";
      out.push_back({name, p / p.norm()});
    }
  return out;
}

/// Symbol of the form's own strain operator along x at free particle f of a periodic lattice, wavevector k e_x:
/// S(k) = sum_j K^x_ij (e^{i k X_ij} - 1) (difference; sum_j K^x_ij e^{i k X_ij} for the direct sum), read from
/// F_i^{xx} - 1 of the real fields u_x = cos(k (X - X_i)) and sin(k (X - X_i)) (k a multiple of 2 pi / (n dx)).
template <int Dim>
double strain_symbol(const FiniteStrainTotalLagrangian<Dim>& tl, int f, double k) {
  const Discretisation<Dim>& d = tl.discretisation();
  const double xi = d.particles.x(d.free[f], 0);
  Eigen::VectorXd uc = Eigen::VectorXd::Zero(tl.dofs()), us = uc;
  for (int g = 0; g < d.free_count(); ++g) {
    uc[Dim * g] = std::cos(k * (d.particles.x(d.free[g], 0) - xi));
    us[Dim * g] = std::sin(k * (d.particles.x(d.free[g], 0) - xi));
  }
  const double re = tl.deformation_gradients(uc)(d.free[f], 0) - 1;
  const double im = tl.deformation_gradients(us)(d.free[f], 0) - 1;
  return std::hypot(re, im);
}

/// The Bloch symbol of A (Dim x Dim) at wavevector k from the Jacobian block rows of free particle f (periodic).
template <int Dim>
Eigen::Matrix<std::complex<double>, Dim, Dim> bloch_symbol(const Eigen::MatrixXd& A, const Discretisation<Dim>& d,
                                                           int f, const Eigen::Matrix<double, Dim, 1>& k) {
  Eigen::Matrix<std::complex<double>, Dim, Dim> S = Eigen::Matrix<std::complex<double>, Dim, Dim>::Zero();
  const int i = d.free[f];
  for (int g = 0; g < d.free_count(); ++g) {
    const Eigen::Matrix<double, Dim, 1> X = -d.particles.separation(i, d.free[g]).transpose();
    const std::complex<double> e = std::exp(std::complex<double>(0, k.dot(X)));
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) S(a, b) += A(Dim * f + a, Dim * g + b) * e;
  }
  return S;
}

// ---- (c) the validation bar of studies/tl-bar-wave-1d (Hooke 1D stress, clamped right end) ----
constexpr double kBarE = 200e9, kBarRho = 8000, kBarLength = 0.15, kBarStress = -100e3;
constexpr double kBarHOverDx = 2.75, kRise = 2e-6, kDuration = 10e-6;
double shape(double t) {
  if (t <= 0 || t >= kDuration) return 0;
  auto s2 = [](double x) { return std::pow(std::sin(0.5 * std::numbers::pi * x), 2); };
  if (t < kRise) return s2(t / kRise);
  if (t > kDuration - kRise) return s2((kDuration - t) / kRise);
  return 1;
}
double shape_integral(double t) {
  if (t <= 0) return 0;
  const double r = kRise;
  auto ramp_int = [r](double x) { return 0.5 * x - r / (2 * std::numbers::pi) * std::sin(std::numbers::pi * x / r); };
  if (t < r) return ramp_int(t);
  const double rise = ramp_int(r);
  if (t < kDuration - r) return rise + (t - r);
  const double plateau = kDuration - 2 * r;
  if (t < kDuration) return rise + plateau + (rise - ramp_int(kDuration - t));
  return 2 * rise + plateau;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Hourglass modes of the finite-strain TL form and the Ganzenmueller (2015) control term"};
  std::string out = "results/tl-hourglass";
  int bar_n = 300;
  app.add_option("--out", out, "output directory");
  app.add_option("--bar-n", bar_n, "free particles of the validation bar")->check(CLI::Range(50, 5000));
  CLI11_PARSE(app, argc, argv);
  fs::create_directories(out);
  const auto t0 = study::Clock::now();
  study::Summary summary;
  CsvWriter spec_csv(out + "/spectrum.csv", {"config", "variant", "hourglass", "rank", "mu", "abs_imag", "zigzag"});
  CsvWriter null_csv(out + "/null_modes.csv",
                     {"config", "variant", "zero_eigenvalues", "pattern", "residual_rel", "zero_tol"});
  CsvWriter sym_csv(out + "/symbol.csv", {"config", "variant", "k_over_pi", "abs_K_symbol", "max_abs_K_symbol"});
  CsvWriter mode_csv(out + "/modes.csv", {"config", "variant", "rank", "mu", "zigzag", "x", "y", "phi_x", "phi_y"});
  CsvWriter lift_csv(
      out + "/lift.csv",
      {"config", "variant", "hourglass", "mu_zigzag_min", "mu_smooth_min", "zigzag_below_smooth", "mu_closed_form",
       "closed_form_residual_rel", "mu_fundamental", "fundamental_overlap", "fundamental_shift_rel", "max_abs_imag"});
  std::string md_null, md_block, md_lift, md_bloch;
  double closed_worst = 0;  // largest closed-form / Bloch residual over every periodic case and coefficient

  // ---------------- (a) + (b): spectra at u = 0 against the coefficient ----------------
  auto run_config = [&]<int Dim>(const Config& cfg) {
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
          spec_csv.row({cfg.name, v.name, chg, static_cast<long>(r), modes[r].mu, modes[r].imag, modes[r].zigzag});
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
        // closed form of the periodic 1D sawtooth lift: mu = 4 c E/rho sum_{m odd} W(m) V / m^2 (plain gradient: the
        // TL part vanishes); 2D: the smallest eigenvalue of the Bloch symbols at the three hourglass wavevectors
        double closed = std::nan(""), closed_res = std::nan("");
        if (cfg.periodic && Dim == 1) {
          double s = 0;
          for (int m = 1; m < cfg.n / 2; m += 2) s += d->kernel.value(double(m), d->h) / (m * m);
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
            const auto S = bloch_symbol<Dim>(A, *d, f0, k);
            Eigen::ComplexEigenSolver<Eigen::Matrix<std::complex<double>, Dim, Dim>> ce(S);
            for (int e = 0; e < Dim; ++e) {
              const double lam = ce.eigenvalues()[e].real();
              closed = std::min(closed, lam);
              // is it in the spectrum of A? distance to the nearest eigenvalue
              double dist = std::numeric_limits<double>::infinity();
              for (const ZigzagMode& m : modes) dist = std::min(dist, std::abs(m.mu - lam));
              closed_res = std::max(closed_res, dist / mu_max);  // each symbol eigenvalue is in the spectrum
              if (chg == 1 && v.sum == StrainSum::Difference)
                study::md_row(md_bloch, {cfg.name, v.name, study::sig(chg, 2),
                                         "(" + study::sig(kk[0], 1) + "," + study::sig(kk[1], 1) + ") pi",
                                         study::sig(lam, 6), study::sig(dist / mu_max, 2)});
            }
          }
        }
        if (!std::isnan(closed_res)) closed_worst = std::max(closed_worst, closed_res);
        if (cfg.periodic && Dim == 1 && chg == 1 && v.name == "plain-difference")
          summary.set("sawtooth_lift_per_coefficient", closed, 6);
        lift_csv.row({cfg.name, v.name, chg, mu_zig, mu_smooth, static_cast<long>(zig_below), closed, closed_res,
                      mu_fund, overlap, mu_fund / mu_fund0 - 1, max_imag});
        if (v.sum == StrainSum::Difference && (chg == 0 || chg == 0.1 || chg == 1))
          study::md_row(md_lift, {cfg.name, v.name, study::sig(chg, 2), study::sig(mu_zig, 4),
                                  std::isnan(closed) ? "-" : study::sig(closed, 4), study::sig(mu_smooth, 4),
                                  study::sig(mu_fund, 4), study::fixed(100 * (mu_fund / mu_fund0 - 1), 3, true) + " %",
                                  study::fixed(overlap, 3), std::to_string(zig_below)});
        if (chg != 0 || v.projection == HourglassProjection::Full) continue;
        // ---- at c_HG = 0: null modes, symbols, shapes ----
        if (cfg.periodic) {
          for (const auto& [name, p] : patterns<Dim>(g)) {
            const double res = (A * p).norm() / mu_max;
            null_csv.row({cfg.name, v.name, static_cast<long>(zeros), name, res, zero_tol});
          }
          double worst = 0;
          for (const auto& [name, p] : patterns<Dim>(g)) worst = std::max(worst, (A * p).norm() / mu_max);
          study::md_row(md_null, {cfg.name, v.name, std::to_string(zeros),
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
            for (auto [kq, s] : line) sym_csv.row({cfg.name, v.name, kq, s, kmax});
            summary.set("symbol_at_pi_" + cfg.name + "_" + v.name, line.back().second / kmax, 2);
          }
        } else {
          double mu_zig_first = mu_zig;
          study::md_row(md_block,
                        {cfg.name, v.name, std::to_string(zig_below), study::sig(mu_zig_first, 4),
                         study::sig(mu_smooth, 4), study::sig(mu_zig_first / mu_smooth, 3), study::sig(max_imag, 2)});
        }
        if (v.sum == StrainSum::Difference) {  // shapes: the 6 softest modes
          for (int r = 0; r < 6; ++r)
            for (int f = 0; f < d->free_count(); ++f)
              mode_csv.row({cfg.name, v.name, static_cast<long>(r), modes[r].mu, modes[r].zigzag,
                            d->particles.x(d->free[f], 0), Dim == 2 ? d->particles.x(d->free[f], 1) : 0.0,
                            modes[r].phi[Dim * f], Dim == 2 ? modes[r].phi[Dim * f + 1] : 0.0});
        }
      }
      std::cout << cfg.name << " " << v.name << " done (" << study::fixed(study::seconds_since(t0), 1) << " s)\n";
    }
  };
  for (const Config& cfg : kConfigs) {
    if (cfg.dim == 1)
      run_config.template operator()<1>(cfg);
    else
      run_config.template operator()<2>(cfg);
  }
  summary.set("null_modes", md_null);
  summary.set("block_modes", md_block);
  summary.set("lift", md_lift);
  summary.set("bloch", md_bloch);
  summary.set("zigzag_threshold", kZigzag, 2);
  summary.set("closed_form_worst_residual", closed_worst, 2);

  // ---------------- (c) the validation bar against the coefficient ----------------
  {
    const LameParameters lame = LameParameters::from_young_poisson(kBarE, kNu);
    const double c = std::sqrt(kBarE / kBarRho), dx = kBarLength / bar_n, h = kBarHOverDx * dx;
    const Kernel<1> kernel(KernelType::ModifiedMollifier);
    const ParticleSet<1> set =
        make_lattice<1>(LatticeType::Line, bar_n, {.spacing = dx, .support_radius = 2 * kernel.support_radius(h)});
    const auto disc = make_discretisation(set, kernel, h);
    std::vector<double> x_fixed;
    for (int i = 0; i < disc->size(); ++i)
      if (disc->free_slot[i] < 0) x_fixed.push_back(disc->particles.x(i, 0));
    const std::vector<double> probes{0.05, 0.10, 0.15};
    std::vector<int> slot;
    for (double xp : probes) {
      int best = 0;
      for (int f = 0; f < disc->free_count(); ++f)
        if (std::abs(disc->particles.x(disc->free[f], 0) - xp) < std::abs(disc->particles.x(disc->free[best], 0) - xp))
          best = f;
      slot.push_back(best);
    }
    CsvWriter bar_csv(out + "/bar.csv", {"hourglass", "dt_ns", "steps", "max_error_kpa_x0.05", "max_error_kpa_x0.1",
                                         "max_error_kpa_x0.15", "plateau_error_kpa_x0.1", "arrival_error_ns_x0.1",
                                         "speed_rel_error", "zigzag_rms_end"});
    CsvWriter probe_csv(out + "/bar_probes.csv", {"hourglass", "t_us", "sigma_sph_kpa_x0.1", "sigma_exact_kpa_x0.1"});
    std::string md_bar;
    for (double chg : kCoefficients) {
      auto hooke = std::make_shared<Hooke<1>>(lame, UniaxialState::Stress);
      FiniteStrainTotalLagrangian<1> tl(disc, hooke, kBarRho, {.hourglass = chg});
      const double v0 = -kBarStress / (kBarRho * c);
      Eigen::VectorXd dfix(x_fixed.size());
      double t_now = 0;
      auto set_fixed = [&] {
        for (std::size_t k = 0; k < x_fixed.size(); ++k)
          dfix[k] = x_fixed[k] < 0 ? v0 * shape_integral(t_now - x_fixed[k] / c) : 0.0;
        tl.set_fixed_displacement(dfix);
      };
      set_fixed();
      const double dt = 0.5 * stable_time_step(tl, Eigen::VectorXd::Zero(tl.dofs())).dt;
      const double t_end = 1.9 * kBarLength / c;
      SecondOrderSystem sys;
      sys.acceleration = [&](const Eigen::VectorXd& u, Eigen::VectorXd& a) {
        set_fixed();
        tl.acceleration(u, a);
      };
      sys.set_time = [&](double t) { t_now = t; };
      sys.mass = tl.dof_mass();
      LeapfrogStepper stepper(sys, Eigen::VectorXd::Zero(tl.dofs()), Eigen::VectorXd::Zero(tl.dofs()));
      std::vector<double> worst(probes.size(), 0.0), arrival(probes.size(), std::nan("")), prev(probes.size(), 0.0);
      double t_prev = 0, plateau_sum = 0;
      long plateau_count = 0;
      SnapshotFunction probe_run([&](const StepView& view) {
        const double t = view.time;
        t_now = t;
        const Eigen::MatrixXd P = tl.stresses(view.u);
        for (std::size_t p = 0; p < probes.size(); ++p) {
          const double xp = disc->particles.x(disc->free[slot[p]], 0);
          const double s = P(disc->free[slot[p]], 0);
          const double exact = kBarStress * (shape(t - xp / c) + shape(t - (2 * kBarLength - xp) / c));
          worst[p] = std::max(worst[p], std::abs(s - exact) / 1e3);
          const double threshold = 0.5 * kBarStress * (p == 2 ? 2 : 1);
          if (std::isnan(arrival[p]) && s <= threshold)
            arrival[p] = t_prev + (t - t_prev) * (threshold - prev[p]) / (s - prev[p]);
          prev[p] = s;
          if (p == 1) {
            // plateau: the incident wave's flat top at x = 0.10 (reflection not yet there), middle 80 %
            const double tau = t - xp / c;
            if (tau > kRise + 0.1 * (kDuration - 2 * kRise) &&
                tau < kDuration - kRise - 0.1 * (kDuration - 2 * kRise)) {
              plateau_sum += s - exact;
              ++plateau_count;
            }
            if (view.step % 2 == 0) probe_csv.row({chg, t * 1e6, s / 1e3, exact / 1e3});
          }
        }
        t_prev = t;
      });
      study::run_probed(stepper, dt, t_end, probe_run);
      // zigzag content at the end: RMS of the second difference / 4 of u over the free particles, relative to RMS u
      const Eigen::VectorXd& u = stepper.u();
      double z = 0;
      for (int f = 1; f + 1 < u.size(); ++f) z += std::pow((u[f + 1] - 2 * u[f] + u[f - 1]) / 4, 2);
      const double zig = std::sqrt(z / (u.size() - 2)) / std::sqrt(u.squaredNorm() / u.size());
      const double xa = disc->particles.x(disc->free[slot[0]], 0), xb = disc->particles.x(disc->free[slot[1]], 0);
      const double speed_err = (xb - xa) / (arrival[1] - arrival[0]) / c - 1;
      const double t_half = kRise / 2;
      const double arr_err = (arrival[1] - (t_half + xb / c)) * 1e9;
      const double plateau = plateau_sum / std::max(1L, plateau_count) / 1e3;
      bar_csv.row({chg, dt * 1e9, stepper.steps(), worst[0], worst[1], worst[2], plateau, arr_err, speed_err, zig});
      study::md_row(md_bar,
                    {study::sig(chg, 2), study::sig(dt * 1e9, 4), study::sig(worst[0], 3), study::sig(worst[1], 3),
                     study::sig(worst[2], 3), study::fixed(plateau, 3, true), study::fixed(arr_err, 2, true),
                     study::fixed(100 * speed_err, 3, true) + " %", study::sig(zig, 3)});
      std::cout << "bar c_HG = " << chg << ": dt " << dt * 1e9 << " ns, max err " << worst[1] << " kPa\n";
    }
    summary.set("bar", md_bar);
    summary.set("bar_n", bar_n);
    summary.set("bar_dx_mm", dx * 1e3, 4);
  }

  // ---------------- (c) explicit runs from a noisy initial velocity ----------------
  {
    CsvWriter noise_csv(out + "/noise.csv", {"config", "hourglass", "time", "zigzag_amplitude", "rms_displacement"});
    std::string md_noise;
    auto noise_run = [&]<int Dim>(const Config& cfg) {
      auto d = lattice<Dim>(cfg);
      const auto g = grid_indices<Dim>(*d, 1.0).index;
      for (double chg : {0.0, 0.1, 1.0}) {
        auto tl = form<Dim>(d, kVariants[0], chg);
        Eigen::VectorXd v0 = study::random_vector(tl.dofs(), 1e-3, 11);  // |v| <= 1e-3 c
        if (cfg.periodic)  // no drift: remove the mean velocity per component
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
          noise_csv.row({cfg.name, chg, s.time, zig, rms});
          zig_end = zig;
          zig_max = std::max(zig_max, zig);
        });
        RunOptions ro{.dt = step, .max_steps = steps, .snapshot_every = static_cast<int>(std::max(1L, steps / 200))};
        ro.observers = {&zigzag};
        if (const RunResult r = run(stepper, ro); !r.completed()) std::cerr << "noise run: " << r.message << "\n";
        study::md_row(md_noise, {cfg.name, study::sig(chg, 2), study::sig(step, 3), std::to_string(steps),
                                 study::sig(zig_max, 3), study::sig(zig_end, 3)});
        std::cout << "noise " << cfg.name << " c_HG = " << chg << ": zigzag max " << zig_max << "\n";
      }
    };
    noise_run.template operator()<1>(kConfigs[0]);
    noise_run.template operator()<1>(kConfigs[1]);
    noise_run.template operator()<2>(kConfigs[3]);
    noise_run.template operator()<2>(kConfigs[4]);
    summary.set("noise", md_noise);
  }
  summary.set("wall_seconds", study::seconds_since(t0), 3);
  summary.write(out);
  return 0;
}
