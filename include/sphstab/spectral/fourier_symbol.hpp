#pragma once
/// \file fourier_symbol.hpp
/// von Neumann (Fourier) analysis of A(T) = K - n T L on the infinite or periodic 1D lattice. On a lattice K and L
/// are Toeplitz (circulant when periodic); exp(i k x) is an eigenvector with eigenvalue
///
///   A(k) = |g^(k)|^2 - n T L^(k),   g^(k) = sum_j G_0j e^{i k (x_j - x_0)} = -2i sum_{m>=1} W'(m dx) dx sin(k m dx),
///                                   L^(k) = sum_{j!=0} H_0j (1 - cos k (x_j - x_0)) = 2 sum_{m>=1} W''(m dx) dx
///                                           (1 - cos(k m dx)),
///
/// so T_crit = inf over 0 < k <= pi/dx with L^(k) > 0 of |g^(k)|^2 / (n L^(k)).
/// g^(pi/dx) = 0 for every kernel (the sawtooth (-1)^i is invisible to the SPH gradient: terms m and -m cancel), so
/// T_crit,inf = 0 whenever L^(pi/dx) = 4 sum_{m odd} W''(m dx) dx > 0.
/// On a periodic lattice of N particles the admissible wavenumbers are k_m = 2 pi m / (N dx), m = 1..N/2 (m = 0 is
/// the translation, A(0) = 0 for every T).
#include <string>

#include "sphstab/kernel/kernel.hpp"

namespace sphstab {

struct FourierSymbol1D {
  double g_abs2 = 0;  ///< |g^(k)|^2
  double l_hat = 0;   ///< L^(k)
};

/// Symbols at wavenumber k (any real k) for kernel support 2h on spacing dx. Throws std::invalid_argument for
/// h <= 0 or dx <= 0.
FourierSymbol1D fourier_symbol_1d(const Kernel<1>& kernel, double h, double dx, double k);

struct SymbolCriticalTension {
  double tcrit = 0;           ///< inf if L^ <= 0 at every admissible k
  double k_over_pi = 0;       ///< k dx / pi of the minimiser (NaN if tcrit is inf)
  double l_hat_sawtooth = 0;  ///< L^(pi/dx)
  std::string reason;         ///< how the value arose (no commas)
};

/// Infinite lattice: minimum of |g^|^2/(n L^) over 0 < k <= pi/dx (grid of `grid` points, then golden-section
/// refinement to 1e-12 in k dx / pi); exactly 0 at the sawtooth when L^(pi/dx) > 1e-12 sum_m |H_m|.
/// n = initial_stress_multiplier > 0 (n = 0 returns inf). Throws std::invalid_argument for h, dx <= 0, n < 0, grid
/// < 16.
SymbolCriticalTension critical_tension_infinite_1d(const Kernel<1>& kernel, double h, double dx, int n,
                                                   int grid = 4096);

/// Periodic lattice of N particles: minimum over the discrete k_m, m = 1..N/2 (translation excluded). Exact
/// (no discretisation) as long as the box holds the whole support (N dx >= 2 * support). Throws
/// std::invalid_argument for N < 2, h, dx <= 0, n < 0.
SymbolCriticalTension critical_tension_periodic_symbol_1d(const Kernel<1>& kernel, double h, double dx, int particles,
                                                          int n);

}  // namespace sphstab
