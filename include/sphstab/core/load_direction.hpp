#pragma once
/// \file load_direction.hpp
/// The sign of a load parameter (1D pre-tension T, 2D pre-strain e): tension positive (docs/conventions.md).
#include <string>

namespace sphstab {

enum class LoadDirection { Tension, Compression };

/// "tension" / "compression".
std::string load_direction_name(LoadDirection direction);
/// Parses "tension" / "compression"; throws std::invalid_argument otherwise.
LoadDirection parse_load_direction(const std::string& name);
/// +1 for tension, -1 for compression.
inline double load_sign(LoadDirection direction) { return direction == LoadDirection::Tension ? 1.0 : -1.0; }

}  // namespace sphstab
