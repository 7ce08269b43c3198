#pragma once
/// \file length_scale.hpp
/// The range of lengths (lattice spacing, smoothing length, support radius) the geometry and kernel code supports.
///
/// SPH is scale-invariant, floating point is not: a 3D second-derivative operator forms W''(r, h) = sigma h^-3
/// (kappa/h)^2 f''(q), i.e. h^-5, and volumes dx^3. Inside [kMinLength, kMaxLength] = [1e-60, 1e60] every such power
/// (|exponent| <= 5) is a normal double, so operators at spacing s dx are the exact rescalings of those at dx (bitwise
/// for s a power of two; tests/operators/scale_invariance_test.cpp checks it over the whole range in 1D, 2D and 3D).
/// Outside it, check_length() refuses with a one-line error naming the range: rescale the problem to units nearer 1.
#include <string>

namespace sphstab {

inline constexpr double kMinLength = 1e-60;
inline constexpr double kMaxLength = 1e60;

/// Throws std::invalid_argument("<what> = 1e-300 is outside the supported length range [1e-60, 1e60] ...") unless
/// value is finite and kMinLength <= value <= kMaxLength.
void check_length(double value, const std::string& what);

}  // namespace sphstab
