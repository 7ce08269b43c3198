#include "sphstab/core/memory_budget.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace memory_budget_test {

/// Restores the process-wide limit when a test ends.
struct LimitGuard {
  ~LimitGuard() { set_memory_limit_bytes(0); }
};

TEST(MemoryBudget, MachineMemoryIsReadAndIsTheDefaultLimit) {
  LimitGuard guard;
  EXPECT_GT(machine_memory_bytes(), 1e8);
  EXPECT_EQ(memory_limit_bytes(), machine_memory_bytes());
  set_memory_limit_bytes(5e8);
  EXPECT_EQ(memory_limit_bytes(), 5e8);
  set_memory_limit_bytes(0);
  EXPECT_EQ(memory_limit_bytes(), machine_memory_bytes());
  EXPECT_THROW(set_memory_limit_bytes(NAN), std::invalid_argument);
  EXPECT_GT(resident_memory_bytes(), 1e5);
}

TEST(MemoryBudget, RefusesWithTheEstimateAndTheLimit) {
  LimitGuard guard;
  EXPECT_NO_THROW(require_memory(1e6, "small"));
  try {
    require_memory(4 * machine_memory_bytes(), "the case");
    ADD_FAILURE() << "no error";
  } catch (const MemoryLimitError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("the case needs ~", 0), 0u) << msg;
    EXPECT_NE(msg.find("this machine has " + format_bytes(machine_memory_bytes())), std::string::npos) << msg;
    EXPECT_NE(msg.find("use --max-memory to override"), std::string::npos) << msg;
  }
  set_memory_limit_bytes(1e9);
  try {
    require_memory(2e9, "x");
    ADD_FAILURE() << "no error";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("above the memory limit of 1 GB (--max-memory)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(require_memory(NAN, "x"), MemoryLimitError);
  EXPECT_THROW(require_memory(INFINITY, "x"), MemoryLimitError);
}

TEST(MemoryBudget, ParsesSizesAndFormatsBytes) {
  EXPECT_EQ(parse_memory_size("8G"), 8e9);
  EXPECT_EQ(parse_memory_size("512MB"), 512e6);
  EXPECT_EQ(parse_memory_size("1e9"), 1e9);
  EXPECT_EQ(parse_memory_size("3k"), 3e3);
  for (const char* bad : {"", "G", "-1G", "0", "8X", "nan", "1e999", "8 G"})
    EXPECT_THROW(parse_memory_size(bad), std::invalid_argument) << bad;
  EXPECT_EQ(format_bytes(512e6), "512 MB");
  EXPECT_EQ(format_bytes(3.7e9), "3.7 GB");
  EXPECT_EQ(format_bytes(999), "999 B");
}

TEST(MemoryBudget, LatticeNeighboursAndOperatorsAreCheckedBeforeAllocating) {
  LimitGuard guard;
  set_memory_limit_bytes(2e7 + resident_memory_bytes());  // 20 MB above what the test already uses
  // 2000^2 particles x 29 bytes = 116 MB: refused by the estimate, nothing allocated.
  EXPECT_THROW(make_lattice<2>(LatticeType::Square, 2000, {.spacing = 1.0, .fixed_layers = 0}), MemoryLimitError);
  // 1D, h = 1e5 dx: 4e5 particles are small, but 1.6e11 neighbour pairs are not.
  const Kernel<1> k(KernelType::CubicSpline);
  const auto line = make_lattice<1>(LatticeType::Line, 1, {.spacing = 1.0, .support_radius = k.support_radius(1e5)});
  EXPECT_EQ(line.size(), 400001);
  EXPECT_THROW(find_neighbours(line, k.support_radius(1e5)), MemoryLimitError);
  // The estimate matches the interior count of a lattice: 1 + 2 * 2.6 -> 5 neighbours + itself per particle.
  const auto small = make_lattice<1>(LatticeType::Line, 100, {.spacing = 1.0, .periodic = true});
  EXPECT_NEAR(expected_neighbour_pairs(small, 2.6), 100 * 6.2, 1e-9);
  EXPECT_EQ(find_neighbours(small, 2.6).nonzeros(), 100 * 5);
}

TEST(MemoryBudget, LatticeCountsAreCheckedNotWrapped) {
  // The cases: fixed layers from a huge support, and layer counts whose 2 x overflowed an int.
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .support_radius = 2e10}), std::length_error);
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = 2000000000}), std::length_error);
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = 1073741824}), std::length_error);
  EXPECT_THROW(make_lattice<3>(LatticeType::Cubic, 2000, {.spacing = 1.0, .fixed_layers = 0}), std::length_error);
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = -5}), std::invalid_argument);
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = 3, .periodic = true}),
               std::invalid_argument);
  EXPECT_EQ(make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .fixed_layers = 0, .periodic = true}).size(), 10);
}

}  // namespace
}  // namespace sphstab
