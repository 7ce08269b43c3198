#pragma once
/// \file load_bracket.hpp
/// The critical load of a stability test that holds below it and fails above it (T_crit, e_crit): bracket by
/// geometric steps from a start value, then geometric bisection (Powell footnote g; the load spans many decades, so
/// steps and midpoints are geometric). One mechanism for every route: CHOLMOD definiteness (critical_tension,
/// critical_strain) and the eigenvalue criteria (critical_strain, affine_critical_tension).
///
/// \code{.cpp}
/// auto stable = [&](double t) { return check.is_positive_definite(pencil.evaluate(t)); };
/// sphstab::LoadBracket b = sphstab::bracket_critical_load(stable, 1e-3, 1e6, 1e-14, 2.0);
/// if (b.outcome == sphstab::LoadBracket::Outcome::Bracketed) sphstab::bisect_critical_load(b, stable, 1e-13);
/// double tcrit = b.critical();  // sqrt(lo hi); inf when stable up to max
/// \endcode
#include <cmath>
#include <functional>
#include <limits>

namespace sphstab {

/// lo: largest load found stable (0 if none); hi: smallest load found unstable (inf if none).
struct LoadBracket {
  enum class Outcome {
    Bracketed,     ///< 0 < lo < hi < inf
    StableToMax,   ///< stable at every tested load up to max (hi = inf)
    UnstableToMin  ///< unstable at every tested load down to min (lo = 0)
  };
  Outcome outcome = Outcome::Bracketed;
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  int tests = 0;  ///< evaluations of the stability test
  /// Geometric midpoint of the bracket: the critical load once bisected; inf for StableToMax, 0 for UnstableToMin.
  double critical() const { return std::isinf(hi) ? hi : std::sqrt(lo * hi); }
};

/// From `start`, multiply (stable) or divide (unstable) by `step` > 1 until the test changes. A load beyond `max` is
/// not tested; `max` itself is (so a critical load in (lo, max] is bracketed). Below `min`: UnstableToMin.
LoadBracket bracket_critical_load(const std::function<bool(double)>& stable, double start, double max, double min,
                                  double step);

/// Geometric bisection of a Bracketed bracket until hi/lo - 1 <= rtol or the floating-point resolution; other
/// outcomes are left unchanged.
void bisect_critical_load(LoadBracket& b, const std::function<bool(double)>& stable, double rtol);

}  // namespace sphstab
