#include "sphstab/core/checked_arithmetic.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphstab {
namespace checked_arithmetic_test {

TEST(CheckedArithmetic, ExactResultsInsideTheRange) {
  EXPECT_EQ(checked_mul(3037000499L, 3037000499L, "x"), 9223372030926249001L);  // largest square below 2^63
  EXPECT_EQ(checked_add(LONG_MAX - 1, 1, "x"), LONG_MAX);
  EXPECT_EQ(checked_floor_count(7.99, 10, "x"), 7);
  EXPECT_EQ(checked_floor_count(10.0, 10, "x"), 10);
  EXPECT_EQ(checked_index_count(kMaxIndexCount, "x"), INT_MAX);
}

TEST(CheckedArithmetic, OverflowAndBadValuesThrowNamingTheQuantity) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::length_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { checked_mul(3037000500L, 3037000500L, "particles"); }).find("particles"), std::string::npos);
  EXPECT_NE(message([] { checked_add(LONG_MAX, 1, "layers"); }).find("overflows"), std::string::npos);
  EXPECT_NE(message([] { checked_floor_count(11.0, 10, "fixed layers"); }).find("exceeds the limit 10"),
            std::string::npos);
  // The float-to-integer casts that were undefined behaviour (issue: --h 1e308 corrupted the heap).
  for (double v : {double(INFINITY), 1e308, 3e10, 9.3e18})
    EXPECT_THROW(checked_floor_count(v, 1L << 29, "x"), std::length_error) << v;
  for (double v : {double(NAN), -1.0, -double(INFINITY)}) EXPECT_THROW(checked_floor_count(v, 100, "x"), std::length_error) << v;
  EXPECT_THROW(checked_index_count(2147483648L, "x"), std::length_error);
  EXPECT_THROW(checked_index_count(-1, "x"), std::length_error);
}

}  // namespace
}  // namespace sphstab
