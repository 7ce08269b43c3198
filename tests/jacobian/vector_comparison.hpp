#pragma once
/// \file vector_comparison.hpp
/// The two helpers the matrix-free tests compare operators with: a seeded random vector and the largest difference
/// relative to the reference's largest entry.
#include <Eigen/Core>
#include <cstdint>
#include <random>

namespace sphstab::test {

/// n entries uniform in [-1, 1] from a 64-bit Mersenne twister seeded with `seed`.
inline Eigen::VectorXd random_vector(long n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::VectorXd v(n);
  for (long i = 0; i < n; ++i) v[i] = uniform(rng);
  return v;
}

/// max |a - b| / max |b|.
inline double relative_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

}  // namespace sphstab::test
