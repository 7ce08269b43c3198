#pragma once
/// \file format.hpp
/// Numbers in tables, summaries and reason strings: printf %.Ng with "nan", "inf", "-inf" spelled out, so a
/// missing or unbounded value is never printed as something that parses as a number it is not.
#include <cmath>
#include <cstdio>
#include <string>

namespace sphstab {

/// v with `digits` significant digits (%.*g); non-finite values as "nan", "inf", "-inf".
inline std::string format_number(double v, int digits = 6) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// Appends `part` to a "; "-separated reason string (empty parts are skipped).
inline void append_reason(std::string& reason, const std::string& part) {
  if (part.empty()) return;
  if (!reason.empty()) reason += "; ";
  reason += part;
}

}  // namespace sphstab
