#include "sphstab/core/checked_arithmetic.hpp"

#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

long checked_mul(long a, long b, const std::string& what) {
  long r = 0;
  if (__builtin_mul_overflow(a, b, &r))
    throw std::length_error(what + ": " + std::to_string(a) + " x " + std::to_string(b) + " overflows a 64-bit count");
  return r;
}

long checked_add(long a, long b, const std::string& what) {
  long r = 0;
  if (__builtin_add_overflow(a, b, &r))
    throw std::length_error(what + ": " + std::to_string(a) + " + " + std::to_string(b) + " overflows a 64-bit count");
  return r;
}

long checked_floor_count(double value, long limit, const std::string& what) {
  if (std::isnan(value) || value < 0)
    throw std::length_error(what + " is not a count (got " + format_number(value) + ")");
  const double f = std::floor(value);
  // Compare in double before converting: static_cast of a double above LONG_MAX is undefined.
  if (!(f <= static_cast<double>(limit)))
    throw std::length_error(what + " = " + format_number(f) + " exceeds the limit " + std::to_string(limit));
  return static_cast<long>(f);
}

int checked_index_count(long v, const std::string& what) {
  if (v < 0 || v > kMaxIndexCount)
    throw std::length_error(what + " = " + std::to_string(v) + " is outside [0, " + std::to_string(kMaxIndexCount) +
                            "] (particle and DOF indices are 32-bit)");
  return static_cast<int>(v);
}

}  // namespace sphstab
