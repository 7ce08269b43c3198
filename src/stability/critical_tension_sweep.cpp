#include "sphstab/stability/critical_tension_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/particles/lattice_presets.hpp"
#include "sphstab/spectral/fourier_symbol.hpp"

namespace sphstab {

namespace {

CriticalTensionCase make_case(KernelType kernel, MomentumForm form, double h) {
  CriticalTensionCase c;
  c.kernel = kernel;
  c.form = form;
  c.h = h;
  return c;
}
}  // namespace

double critical_tension_1d_memory_bytes(int n, double support, int layer_supports, bool periodic, bool dense) {
  const double particles = n + (periodic ? 0.0 : 2.0 * std::floor(layer_supports * support + 1));
  const double pairs = particles * std::min(particles, 1 + 2 * support);
  return 21 * particles + 150 * pairs + 18 * n * std::min<double>(n, 4 * support + 1) + (dense ? 40.0 * n * n : 0.0);
}

std::vector<CriticalTensionCase> critical_tension_sweep(const CriticalTensionSweep& s) {
  if (s.kernels.empty() || s.hs.empty() || s.forms.empty())
    throw std::invalid_argument("critical_tension_sweep: kernels, hs and forms must not be empty");
  if (s.n < 1) throw std::invalid_argument("critical_tension_sweep: n = " + std::to_string(s.n) + " (need >= 1)");
  const bool plain = s.correction == Correction::None;
  if (!plain && s.periodic)
    throw std::invalid_argument(
        "critical_tension_sweep: a corrected form needs fixed layers (the general route does not deflate the "
        "translation null mode of a periodic lattice)");
  for (double h : s.hs)  // before the memory estimates, which a NaN would turn into "needs ~nan bytes"
    if (!(h > 0) || !std::isfinite(h))
      throw std::invalid_argument("critical_tension_sweep: h/dx must be finite and > 0 (got " + format_number(h, 12) +
                                  ")");
  for (double h : s.hs) {
    const double support = Kernel<1>(s.kernels[0]).support_radius(h);
    const bool dense = s.method != CriticalLoadMethod::Bisection &&
                       (s.backend == EigenBackend::Dense ||
                        s.n <= (plain ? CriticalLoadOptions{}.dense_max : CriticalLoadOptions{}.spectrum_dense_max));
    require_memory(
        critical_tension_1d_memory_bytes(s.n, support, plain ? 1 : s.corrected_layer_supports, s.periodic, dense),
        s.memory_label ? s.memory_label(h)
                       : "critical_tension_sweep: n = " + std::to_string(s.n) + ", h/dx = " + format_number(h, 12));
  }
  auto with_routes = [&](CriticalLoadOptions o) {
    o.method = s.method;
    o.backend = s.backend;
    o.want_mode = s.method != CriticalLoadMethod::Bisection;
    return o;
  };
  const bool tension = s.direction == LoadDirection::Tension;  // the estimates are tension formulas
  std::vector<CriticalTensionCase> cases;
  for (KernelType type : s.kernels) {
    const Kernel<1> kernel(type);
    for (double h : s.hs) {
      if (plain) {
        // The analytic Jacobian K - n T L (Powell 3.40) and the closed-form estimates.
        const ParticleSet<1> set = tension_lattice_1d(kernel, h, s.n, s.periodic);
        for (MomentumForm form : s.forms) {
          const int n = initial_stress_multiplier(form);
          CriticalTensionCase c = make_case(type, form, h);
          c.result =
              critical_tension_1d(set, kernel, h, form, with_routes(CriticalLoadOptions::tension_1d()), s.direction);
          const TensionEstimates1D e = tension_estimates_1d(kernel, h, 1.0, n);
          const SymbolCriticalTension inf = critical_tension_infinite_1d(kernel, h, 1.0, n);
          if (s.periodic && tension) c.symbol = critical_tension_periodic_symbol_1d(kernel, h, 1.0, s.n, n).tcrit;
          if (tension) {
            c.estimates = e;
            c.infinite = inf.tcrit;
          }
          c.backend = c.result.eigen_backend.empty() ? "none" : c.result.eigen_backend;
          c.criterion = criterion_name(c.result.criterion);
          c.reason = tension ? c.result.reason : "compression: T < 0 searched as K + |T| n L; " + c.result.reason;
          c.mode_k_over_pi = c.result.mode_wavenumber.k_projection;
          cases.push_back(std::move(c));
          if (s.on_case) s.on_case();
        }
        continue;
      }
      // Corrected kernel: complex-step A(T) = A0 + T A1 of the force function, then the general criteria.
      if (kernel.support_radius(h) <= 1.0) {
        // One rule with the plain routes: no neighbour inside the support -> NaN and numerical-issue (a correction
        // such as NCSPH is not even defined there).
        for (MomentumForm form : s.forms) {
          CriticalTensionCase c = make_case(type, form, h);
          c.result.status = Status::NumericalIssue;
          c.backend = "none";
          c.criterion = "none";
          c.reason = "no neighbour inside the kernel support (2h = " + format_number(kernel.support_radius(h), 12) +
                     " <= dx): every operator is diagonal";
          c.mode_k_over_pi = c.result.reported_wavenumber().k_projection;
          cases.push_back(std::move(c));
        }
        continue;
      }
      const ParticleSet<1> set = tension_lattice_1d(kernel, h, s.n, false, s.corrected_layer_supports);
      auto disc = make_discretisation(set, kernel, h);
      const Eigen::MatrixXd x = disc->free_positions();
      const auto provider = make_gradient_provider<1>(s.correction);
      const CriticalLoadOptions fopt = with_routes(CriticalLoadOptions::force_function());
      for (MomentumForm form : s.forms) {
        WaveForm1D force(disc, form, 0.0, provider, {.corrected = s.corrected});
        const ForceCriticalLoad load = force_critical_loads(force, s.direction, x, fopt);
        std::string note = "corrected " + force.name().substr(force.name().rfind('/') + 1) + "; fixed layers " +
                           std::to_string(s.corrected_layer_supports) + " supports";
        if (load.residual_relative > 1e-10)
          note += "; WARNING u = 0 is not an equilibrium (max|a(0)|/max|A0| = " +
                  format_number(load.residual_relative, 12) + ")";
        for (const CriticalLoad& r : load.results) {
          CriticalTensionCase c = make_case(type, form, h);
          c.result = r;
          const bool pd = r.criterion != Criterion::Spectrum;
          c.backend = pd ? (r.eigen_backend.empty() ? "none" : r.eigen_backend) : std::string("dgeev");
          c.criterion = criterion_name(r.criterion);
          c.reason = note + "; " + r.reason;
          c.mode_k_over_pi = r.reported_wavenumber().k_projection;
          cases.push_back(std::move(c));
        }
        if (s.on_case) s.on_case();
      }
    }
  }
  return cases;
}

}  // namespace sphstab
