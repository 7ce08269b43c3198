#pragma once
// The 2D critical-strain benchmark case shared by critical_strain_benchmark and matrix_free_benchmark: square lattices
// of n x n free particles plus fixed layers, cubic spline, h = 1.3 dx, Powell's steel in plane strain; and the
// process's peak resident memory (run one case per process for per-case memory).
#include <sys/resource.h>

#include <map>
#include <memory>

#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace bench {

constexpr double kH = 1.3;
const sphstab::ElasticMaterial kMaterial =
    sphstab::ElasticMaterial::from_lame(1.2115384615384615, 0.8076923076923077, 7.8);

inline double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux: kilobytes
}

/// The n x n lattice's discretisation, built once per n.
inline std::shared_ptr<const sphstab::Discretisation<2>> discretisation(int n) {
  static std::map<int, std::shared_ptr<const sphstab::Discretisation<2>>> cache;
  auto& d = cache[n];
  if (!d) {
    const sphstab::Kernel<2> k(sphstab::KernelType::CubicSpline);
    d = sphstab::make_discretisation(sphstab::strain_lattice_2d(sphstab::LatticeType::Square, k, kH, n), k, kH);
  }
  return d;
}

}  // namespace bench
