#include "sphstab/core/memory_budget.hpp"

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

std::atomic<double> g_limit{0.0};  // <= 0: the machine's memory

double cgroup_limit_bytes() {
  std::ifstream f("/sys/fs/cgroup/memory.max");
  std::string s;
  if (!(f >> s) || s == "max") return 0;
  try {
    return std::stod(s);
  } catch (const std::exception&) {
    return 0;
  }
}

}  // namespace

double machine_memory_bytes() {
  static const double bytes = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    double b = (pages > 0 && page > 0) ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
    const double cg = cgroup_limit_bytes();
    if (cg > 0 && (b <= 0 || cg < b)) b = cg;
    return b > 0 ? b : 4e9;  // unknown: assume a small machine
  }();
  return bytes;
}

double memory_limit_bytes() {
  const double l = g_limit.load();
  return l > 0 ? l : machine_memory_bytes();
}

void set_memory_limit_bytes(double bytes) {
  if (std::isnan(bytes)) throw std::invalid_argument("memory limit must be a number of bytes (got nan)");
  g_limit.store(bytes > 0 ? bytes : 0.0);
}

double resident_memory_bytes() {
  std::ifstream f("/proc/self/statm");
  double pages_total = 0, pages_resident = 0;
  if (!(f >> pages_total >> pages_resident)) return 0;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGE_SIZE));
}

void require_memory(double bytes, const std::string& what) {
  const double limit = memory_limit_bytes();
  // Small requests are not worth reading /proc for (re-assembly loops call this every step).
  const double in_use = (bytes > 16e6 || !(bytes >= 0)) ? resident_memory_bytes() : 0.0;
  if (bytes + in_use <= limit) return;  // false for NaN: refused below
  const bool set = g_limit.load() > 0;
  const std::string used = in_use > 0.01 * limit ? " (with " + format_bytes(in_use) + " already in use)" : "";
  throw MemoryLimitError(what + " needs ~" + format_bytes(bytes) + used +
                         (set ? ", above the memory limit of " + format_bytes(limit) + " (--max-memory)"
                              : ", this machine has " + format_bytes(limit) + " (use --max-memory to override)"));
}

void require_dense_memory(long n, int copies, const std::string& what) {
  require_memory(
      8.0 * static_cast<double>(n) * static_cast<double>(n) * copies,
      what + ": " + std::to_string(copies) + " dense " + std::to_string(n) + " x " + std::to_string(n) + " matrices");
}

std::string format_bytes(double bytes) {
  if (!std::isfinite(bytes)) return format_number(bytes) + " bytes";
  const char* unit[] = {"B", "kB", "MB", "GB"};
  int u = 0;
  double v = bytes;
  while (u < 3 && v >= 1000) {
    v /= 1000;
    ++u;
  }
  char buf[64];
  if (v >= 1e4)
    std::snprintf(buf, sizeof buf, "%.2g %s", v, unit[u]);
  else
    std::snprintf(buf, sizeof buf, "%.3g %s", v, unit[u]);
  return buf;
}

double parse_memory_size(const std::string& text) {
  std::size_t used = 0;
  double v = NAN;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string suffix = used ? text.substr(used) : "";
  for (char& c : suffix) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (suffix.size() == 2 && suffix[1] == 'B') suffix.pop_back();
  double scale = 0;
  if (suffix.empty() || suffix == "B")
    scale = 1;
  else if (suffix == "K")
    scale = 1e3;
  else if (suffix == "M")
    scale = 1e6;
  else if (suffix == "G")
    scale = 1e9;
  else if (suffix == "T")
    scale = 1e12;
  if (used == 0 || scale == 0 || !std::isfinite(v) || !(v > 0) || !std::isfinite(v * scale))
    throw std::invalid_argument(
        "memory size must be a positive number of bytes with an optional K, M, G or T suffix "
        "(got '" +
        text + "')");
  return v * scale;
}

}  // namespace sphstab
