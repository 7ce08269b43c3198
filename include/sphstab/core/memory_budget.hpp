#pragma once
/// \file memory_budget.hpp
/// A size check before every large allocation. Each routine that allocates in proportion to its input (lattices,
/// neighbour lists, operator matrices, Jacobians, dense copies, Cholesky factors) first estimates its bytes and calls
/// require_memory(), which refuses with "needs ~X GB, this machine has Y GB (use --max-memory to override)" instead
/// of running into std::bad_alloc, swap or the kernel's OOM killer.
///
/// The limit is process-wide (like Eigen::setNbThreads): by default the machine's physical memory (or the cgroup
/// limit, if smaller); the command line's --max-memory and tests set it with set_memory_limit_bytes().
#include <stdexcept>
#include <string>

namespace sphstab {

/// Thrown by require_memory(): an estimated allocation exceeds the memory limit.
class MemoryLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Physical memory of this machine in bytes: sysconf(_SC_PHYS_PAGES) x page size, or the cgroup v2 memory.max if
/// that is smaller.
double machine_memory_bytes();
/// The current limit in bytes (the machine's memory unless set).
double memory_limit_bytes();
/// Sets the process-wide limit; bytes <= 0 restores the default (the machine's memory). Throws
/// std::invalid_argument for NaN.
void set_memory_limit_bytes(double bytes);
/// Resident set size of this process (/proc/self/statm), 0 if unknown.
double resident_memory_bytes();
/// Throws MemoryLimitError("<what> needs ~X GB, this machine has Y GB (use --max-memory to override)") when
/// bytes + the resident set exceed memory_limit_bytes() (the resident set is read only for requests above 16 MB);
/// bytes that are NaN or inf are refused too.
void require_memory(double bytes, const std::string& what);
/// require_memory() for `copies` dense n x n double matrices: "<what>: 3 dense 30000 x 30000 matrices needs ~..."
void require_dense_memory(long n, int copies, const std::string& what);
/// "512 MB", "3.7 GB", "1.2e+04 GB": bytes for messages (decimal units).
std::string format_bytes(double bytes);
/// Parses a size for --max-memory: a number of bytes with an optional suffix K, M, G, T (decimal, case-insensitive,
/// optional trailing B), e.g. "8G", "512MB", "1e9". Throws std::invalid_argument naming the text otherwise.
double parse_memory_size(const std::string& text);

}  // namespace sphstab
