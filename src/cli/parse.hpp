#pragma once
// Strict parsing of command-line values: every malformed, empty, out-of-range or non-finite value is a one-line
// std::invalid_argument naming the option and the text, never a silently dropped item or a wrapped integer.
#include <cstdint>
#include <string>
#include <vector>

#include "sphstab/operators/local_polish.hpp"

namespace sphstab::cli {

/// Items of a `sep`-separated list; an empty list or an empty item ("cubic,", "1,,2", ",") is an error naming
/// `what` and the text.
std::vector<std::string> split_list(const std::string& text, char sep, const std::string& what);
/// A finite double; overflow ("1e999") and underflow to a subnormal or zero ("1e-320") are errors that say so.
double parse_double(const std::string& text, const std::string& what);
/// An integer in [lo, hi] (no sign wrap: "-1" is not 2^64 - 1), decimal digits only with an optional leading '-'.
long parse_integer(const std::string& text, long lo, long hi, const std::string& what);
/// An unsigned 64-bit integer (seeds): digits only.
std::uint64_t parse_unsigned(const std::string& text, const std::string& what);

}  // namespace sphstab::cli
