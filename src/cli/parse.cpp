#include "parse.hpp"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace sphstab::cli {

std::vector<std::string> split_list(const std::string& text, char sep, const std::string& what) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(sep, start);
    out.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (out.back().empty())
      throw std::invalid_argument(what + " has an empty item (got '" + text + "'; separate items by '" +
                                  std::string(1, sep) + "')");
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

double parse_double(const std::string& text, const std::string& what) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])))
    throw std::invalid_argument(what + " must be a finite number (got '" + text + "')");
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || std::isnan(v))
    throw std::invalid_argument(what + " must be a finite number (got '" + text + "')");
  if (std::isinf(v) || (errno == ERANGE && std::abs(v) > 1))
    throw std::invalid_argument(what + " must be a finite number ('" + text + "' overflows a double)");
  if (errno == ERANGE || (v != 0 && !std::isnormal(v)))
    throw std::invalid_argument(what + " = '" + text + "' underflows (below 2.2e-308, the smallest normal double)");
  return v;
}

long parse_integer(const std::string& text, long lo, long hi, const std::string& what) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  std::size_t k = (!text.empty() && text[0] == '-') ? 1 : 0;
  bool digits = text.size() > k;
  for (std::size_t i = k; i < text.size(); ++i) digits = digits && std::isdigit(static_cast<unsigned char>(text[i]));
  if (!digits) throw std::invalid_argument(what + " must be an integer in " + range + " (got '" + text + "')");
  errno = 0;
  const long v = std::strtol(text.c_str(), nullptr, 10);
  if (errno == ERANGE || v < lo || v > hi)
    throw std::invalid_argument(what + " must be an integer in " + range + " (got '" + text + "')");
  return v;
}

std::uint64_t parse_unsigned(const std::string& text, const std::string& what) {
  bool digits = !text.empty();
  for (char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  errno = 0;
  const unsigned long long v = digits ? std::strtoull(text.c_str(), nullptr, 10) : 0;
  if (!digits || errno == ERANGE)
    throw std::invalid_argument(what + " must be an integer in [0, 18446744073709551615] (got '" + text + "')");
  return v;
}

}  // namespace sphstab::cli
