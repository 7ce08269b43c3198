#pragma once
/// \file critical_tension_sweep.hpp
/// The critical tension of the 1D pre-stressed bar [Powell2012, ch. 3] over kernels x h/dx x momentum forms: what
/// `sphstab tcrit --dim 1` prints, one case per row.
///   - Plain kernel (correction None): critical_tension_1d (the analytic K - n T L [Powell2012, (3.40)], bracket in
///     units of n T) on tension_lattice_1d (fixed layers one support thick, or periodic), beside the closed-form
///     estimates (3.42), (3.49), (3.43), (3.51) and Swegle's, the infinite-lattice limit and, periodic, the lattice's
///     own Fourier symbol (tension only: NaN in compression).
///   - Corrected kernel: force_critical_loads of WaveForm1D with the corrected gradient (A(T) = A0 + T A1 by complex
///     step) on a lattice with fixed layers `corrected_layer_supports` supports thick, one case per applicable
///     criterion; the equilibrium residual is reported in `reason` (a WARNING when u = 0 is not an equilibrium).
///     No neighbour inside the support (2h <= dx): NaN with status NumericalIssue, as every other route.
/// The memory of every h is checked before anything is built (critical_tension_1d_memory_bytes).
///
/// \code{.cpp}
/// sphstab::CriticalTensionSweep s{.n = 30, .kernels = {sphstab::KernelType::CubicSpline}, .hs = {1.0, 1.3, 2.0}};
/// for (const auto& c : sphstab::critical_tension_sweep(s)) std::cout << c.h << " " << c.result.load << "\n";
/// \endcode
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/operators/correction.hpp"
#include "sphstab/spectral/tension_estimates.hpp"
#include "sphstab/stability/critical_load.hpp"

namespace sphstab {

struct CriticalTensionSweep {
  int n = 30;  ///< free particles (>= 1)
  bool periodic = false;
  LoadDirection direction = LoadDirection::Tension;
  std::vector<KernelType> kernels = {KernelType::CubicSpline};
  std::vector<double> hs = {1.3};  ///< h / dx
  std::vector<MomentumForm> forms = {MomentumForm::Conservative};
  Correction correction = Correction::None;
  CorrectedOperator corrected = CorrectedOperator::Auto;
  CriticalLoadMethod method = CriticalLoadMethod::Both;
  EigenBackend backend = EigenBackend::Auto;
  int corrected_layer_supports = 3;  ///< fixed layers of a corrected lattice, in supports (2h)
  /// The text before " needs ~X GB ..." in a memory refusal, per h; empty: "critical_tension_sweep: n = N, h/dx = H".
  std::function<std::string(double h)> memory_label;
  std::function<void()> on_case;  ///< called after each (kernel, h, form) computed
};

struct CriticalTensionCase {
  static constexpr double nan = CriticalLoad::nan;
  KernelType kernel = KernelType::CubicSpline;
  MomentumForm form = MomentumForm::Conservative;
  double h = nan;
  CriticalLoad result;
  std::string backend;    ///< the eigen route: "dense", "spectra", "dgeev" (spectrum criterion) or "none"
  std::string criterion;  ///< criterion_name(result.criterion), or "none" when nothing could be computed
  std::string reason;     ///< result.reason with the case's notes (compression, correction, fixed layers, residual)
  double mode_k_over_pi = nan;  ///< plain: the critical mode's k dx / pi; corrected: result.reported_wavenumber()
  std::optional<TensionEstimates1D> estimates;  ///< plain kernel in tension
  double infinite = nan;                        ///< plain, tension: critical_tension_infinite_1d
  double symbol = nan;                          ///< plain, periodic, tension: critical_tension_periodic_symbol_1d
};

/// Estimated peak bytes of one 1D case: the lattice, the neighbour list, G and H, the Jacobian (about 120 bytes per
/// entry of G, analytic_jacobian_1d.cpp), the Cholesky factor of the banded A0 (bandwidth 2 supports) and, for a dense
/// eigen route, five n x n copies.
double critical_tension_1d_memory_bytes(int n, double support, int layer_supports, bool periodic, bool dense);

/// Cases in the order kernel, h, form (form fastest; corrected: one case per criterion). Throws
/// std::invalid_argument for empty lists, a corrected periodic lattice, n < 1; MemoryLimitError before anything is
/// built; and as the engines do.
std::vector<CriticalTensionCase> critical_tension_sweep(const CriticalTensionSweep& sweep);

}  // namespace sphstab
