#pragma once
/// \file checked_arithmetic.hpp
/// Counts that come from user input (lattice sizes, fixed layers, particle and matrix sizes) in checked integer
/// arithmetic: an overflow or an out-of-range conversion is a one-line std::length_error naming the quantity, never
/// a wrapped value or undefined behaviour (a float-to-int cast of inf or 3e10 is undefined in C++).
#include <limits>
#include <string>

namespace sphstab {

/// Particle and DOF indices are int: the largest count of particles (and of DOFs) any routine accepts.
inline constexpr long kMaxIndexCount = std::numeric_limits<int>::max();

/// Largest number of lattice rows a lattice sum visits on each side ((2 x 16384)^2 = 1.1e9 terms, minutes).
inline constexpr long kMaxLatticeReach = 1L << 14;

/// a * b; throws std::length_error("<what>: a x b overflows") when the product does not fit a long.
long checked_mul(long a, long b, const std::string& what);
/// a + b; throws std::length_error on overflow.
long checked_add(long a, long b, const std::string& what);
/// floor(value) as a count in [0, limit]; throws std::length_error naming `what`, the value and the limit when value
/// is NaN, negative or floor(value) > limit.
long checked_floor_count(double value, long limit, const std::string& what);
/// v as an int; throws std::length_error when v is outside [0, kMaxIndexCount].
int checked_index_count(long v, const std::string& what);

}  // namespace sphstab
