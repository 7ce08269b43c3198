#include "sphstab/stability/load_bracket.hpp"

#include <stdexcept>

namespace sphstab {

LoadBracket bracket_critical_load(const std::function<bool(double)>& stable, double start, double max, double min,
                                  double step) {
  if (!(step > 1) || !(start > 0) || !(min > 0) || !(max >= start) || !std::isfinite(max))
    throw std::invalid_argument("bracket_critical_load: need step > 1 and 0 < min, 0 < start <= max < inf");
  LoadBracket b;
  auto test = [&](double t) {
    ++b.tests;
    return stable(t);
  };
  double t = start;
  if (test(t)) {
    b.lo = t;
    while (true) {
      t *= step;
      if (t > max) {
        if (b.lo < max && !test(max)) {
          b.hi = max;
        } else {
          b.lo = max;
          b.outcome = LoadBracket::Outcome::StableToMax;
        }
        return b;
      }
      if (!test(t)) break;
      b.lo = t;
    }
    b.hi = t;
    return b;
  }
  b.hi = t;
  while (true) {
    t /= step;
    if (t < min) {
      b.outcome = LoadBracket::Outcome::UnstableToMin;
      return b;
    }
    if (test(t)) break;
    b.hi = t;
  }
  b.lo = t;
  return b;
}

void bisect_critical_load(LoadBracket& b, const std::function<bool(double)>& stable, double rtol) {
  if (b.outcome != LoadBracket::Outcome::Bracketed) return;
  while (b.hi / b.lo - 1 > rtol) {
    const double mid = std::sqrt(b.lo * b.hi);
    if (mid <= b.lo || mid >= b.hi) break;  // bracket at floating-point resolution
    ++b.tests;
    (stable(mid) ? b.lo : b.hi) = mid;
  }
}

}  // namespace sphstab
