#pragma once
/// \file random_vector.hpp
/// Reproducible random vectors (perturbed states of studies and tests): the same values on every run and machine.
#include <Eigen/Core>
#include <random>

namespace sphstab {

/// n values uniform in [-amplitude, amplitude] from std::mt19937(seed).
inline Eigen::VectorXd random_vector(int n, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = d(rng);
  return v;
}

}  // namespace sphstab
