#include "sphstab/spectral/fourier_symbol.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct KernelLatticeSums1D {
  std::vector<double> w1, w2;  // W'(m dx) dx, W''(m dx) dx for m = 1..M
  double h_scale = 0;          // sum |H_m|
};

KernelLatticeSums1D kernel_lattice_sums_1d(const Kernel<1>& kernel, double h, double dx, const char* who) {
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument(std::string(who) + ": h must be finite and > 0 (got " + format_number(h) + ")");
  if (!(dx > 0) || !std::isfinite(dx))
    throw std::invalid_argument(std::string(who) + ": dx must be finite and > 0 (got " + format_number(dx) + ")");
  KernelLatticeSums1D s;
  const double support = kernel.support_radius(h);
  checked_floor_count(support / dx, 1L << 29, std::string(who) + ": lattice terms (support / dx)");
  for (int m = 1; m * dx < support; ++m) {  // strict, like find_neighbours
    s.w1.push_back(kernel.d1(m * dx, h) * dx);
    s.w2.push_back(kernel.d2(m * dx, h) * dx);
    s.h_scale += 2 * std::abs(s.w2.back());
  }
  return s;
}

FourierSymbol1D symbol(const KernelLatticeSums1D& s, double kdx) {
  double g = 0, l = 0;
  for (size_t i = 0; i < s.w1.size(); ++i) {
    const double m = double(i + 1);
    g += s.w1[i] * std::sin(kdx * m);
    l += s.w2[i] * (1 - std::cos(kdx * m));
  }
  return {4 * g * g, 2 * l};
}

}  // namespace

FourierSymbol1D fourier_symbol_1d(const Kernel<1>& kernel, double h, double dx, double k) {
  return symbol(kernel_lattice_sums_1d(kernel, h, dx, "fourier_symbol_1d"), k * dx);
}

SymbolCriticalTension critical_tension_infinite_1d(const Kernel<1>& kernel, double h, double dx, int n, int grid) {
  const KernelLatticeSums1D s = kernel_lattice_sums_1d(kernel, h, dx, "critical_tension_infinite_1d");
  if (n < 0)
    throw std::invalid_argument("critical_tension_infinite_1d: n must be >= 0 (got " + std::to_string(n) + ")");
  if (grid < 16)
    throw std::invalid_argument("critical_tension_infinite_1d: grid must be >= 16 (got " + std::to_string(grid) + ")");
  SymbolCriticalTension r;
  r.l_hat_sawtooth = symbol(s, M_PI).l_hat;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (s.w1.empty()) {  // the symbol is identically 0: stability is undefined, not unconditional
    r.tcrit = nan;
    r.k_over_pi = nan;
    r.reason = "no lattice neighbour inside the kernel support (h too small)";
    return r;
  }
  if (n == 0) {
    r.tcrit = kInf;
    r.k_over_pi = nan;
    r.reason = "n = 0: no tension dependence";
    return r;
  }
  const double tol = 1e-12 * s.h_scale;
  if (r.l_hat_sawtooth > tol) {
    r.tcrit = 0;
    r.k_over_pi = 1;
    r.reason = "sawtooth k = pi/dx: g^ = 0 and L^ > 0";
    return r;
  }
  auto ratio = [&](double q) {  // q = k dx / pi
    const FourierSymbol1D f = symbol(s, q * M_PI);
    return f.l_hat > tol ? f.g_abs2 / (n * f.l_hat) : kInf;
  };
  double best = kInf;
  int best_j = -1;
  for (int j = 1; j <= grid; ++j) {
    const double v = ratio(double(j) / grid);
    if (v < best) {
      best = v;
      best_j = j;
    }
  }
  if (best_j < 0) {
    r.tcrit = kInf;
    r.k_over_pi = nan;
    r.reason = "L^(k) <= 0 for all k: A(T) positive definite for every T > 0";
    return r;
  }
  // Golden-section refinement on the bracketing grid cells (the ratio is smooth where L^ > 0).
  double a = double(best_j - 1) / grid, b = std::min(1.0, double(best_j + 1) / grid);
  const double phi = 0.5 * (std::sqrt(5.0) - 1);
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = ratio(c), fd = ratio(d);
  while (b - a > 1e-12) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - phi * (b - a);
      fc = ratio(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + phi * (b - a);
      fd = ratio(d);
    }
  }
  const double q = 0.5 * (a + b);
  const double refined = ratio(q);
  r.tcrit = std::min(best, refined);
  r.k_over_pi = refined <= best ? q : double(best_j) / grid;
  r.reason = "minimum of |g^|^2/(n L^) at interior k";
  return r;
}

SymbolCriticalTension critical_tension_periodic_symbol_1d(const Kernel<1>& kernel, double h, double dx, int particles,
                                                          int n) {
  const KernelLatticeSums1D s = kernel_lattice_sums_1d(kernel, h, dx, "critical_tension_periodic_symbol_1d");
  if (particles < 2)
    throw std::invalid_argument("critical_tension_periodic_symbol_1d: need N >= 2 particles (got " +
                                std::to_string(particles) + ")");
  if (n < 0)
    throw std::invalid_argument("critical_tension_periodic_symbol_1d: n must be >= 0 (got " + std::to_string(n) + ")");
  SymbolCriticalTension r;
  r.l_hat_sawtooth = symbol(s, M_PI).l_hat;
  r.tcrit = kInf;
  r.k_over_pi = std::numeric_limits<double>::quiet_NaN();
  r.reason = n == 0 ? "n = 0: no tension dependence" : "L^(k_m) <= 0 for all m: A(T) positive definite for every T > 0";
  if (s.w1.empty()) {  // as critical_tension_infinite_1d: undefined, not unconditionally stable
    r.tcrit = r.k_over_pi;
    r.reason = "no lattice neighbour inside the kernel support (h too small)";
    return r;
  }
  if (n == 0) return r;
  const double tol = 1e-12 * s.h_scale;
  for (int m = 1; 2 * m <= particles; ++m) {
    const double q = 2.0 * m / particles;
    const FourierSymbol1D f = symbol(s, q * M_PI);
    if (!(f.l_hat > tol)) continue;
    // At the sawtooth (2m = N) g^ vanishes exactly; the rounding residue is dropped.
    const double g2 = (2 * m == particles) ? 0.0 : f.g_abs2;
    const double t = g2 / (n * f.l_hat);
    if (t < r.tcrit) {
      r.tcrit = t;
      r.k_over_pi = q;
      r.reason =
          (2 * m == particles) ? "sawtooth k = pi/dx (N even): g^ = 0 and L^ > 0" : "minimum over k_m = 2 pi m/(N dx)";
    }
  }
  return r;
}

}  // namespace sphstab
