#include "sphstab/particles/block_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sphstab {

ParticleSet<2> make_block_lattice_2d(int nx, int ny, const LatticeOptions& options) {
  if (nx < 1 || ny < 1)
    throw std::invalid_argument("make_block_lattice_2d: nx and ny must be >= 1 (got " + std::to_string(nx) + " x " +
                                std::to_string(ny) + ")");
  if (options.periodic) throw std::invalid_argument("make_block_lattice_2d: a block is not periodic (periodic = true)");
  if (options.perturbation != 0)
    throw std::invalid_argument("make_block_lattice_2d: a block is regular (perturbation must be 0)");
  // The square lattice of side max(nx, ny) with the same layers, cut to the rectangle [-k, nx + k) x [-k, ny + k) in
  // lattice indices (k layers), free where i < nx and j < ny. make_lattice's free-first, x-fastest order is kept.
  const int n = std::max(nx, ny);
  const ParticleSet<2> square = make_lattice<2>(LatticeType::Square, n, options);
  const double dx = square.spacing;
  const long k = std::lround(0.5 - square.x.col(0).minCoeff() / dx);  // layers: the first column sits at (1/2 - k) dx
  std::vector<int> free, fixed;
  for (int p = 0; p < square.size(); ++p) {
    const long i = std::lround(square.x(p, 0) / dx - 0.5), j = std::lround(square.x(p, 1) / dx - 0.5);
    if (i >= nx + k || j >= ny + k) continue;
    (i >= 0 && i < nx && j >= 0 && j < ny ? free : fixed).push_back(p);
  }
  std::vector<int> order = free;
  order.insert(order.end(), fixed.begin(), fixed.end());
  // make_lattice lists the free block first: a particle free in the square but outside the block becomes fixed and
  // must follow every block particle; sort each part by the square's lexicographic (y, x) order, as make_lattice.
  auto lexicographic = [&](int a, int b) {
    return std::pair(square.x(a, 1), square.x(a, 0)) < std::pair(square.x(b, 1), square.x(b, 0));
  };
  std::sort(order.begin(), order.begin() + static_cast<long>(free.size()), lexicographic);
  std::sort(order.begin() + static_cast<long>(free.size()), order.end(), lexicographic);
  ParticleSet<2> block;
  const int total = static_cast<int>(order.size());
  block.x.resize(total, 2);
  block.volume.resize(total);
  block.role.resize(total);
  block.depth.resize(total);
  for (int r = 0; r < total; ++r) {
    const int p = order[r];
    block.x.row(r) = square.x.row(p);
    block.volume[r] = square.volume[p];
    block.role[r] = r < static_cast<int>(free.size()) ? Role::Free : Role::Fixed;
    // depth: lattice distance to the outside of the block (fixed layers included), as make_lattice
    const long i = std::lround(square.x(p, 0) / dx - 0.5), j = std::lround(square.x(p, 1) / dx - 0.5);
    block.depth[r] = static_cast<int>(std::min({i + k, nx + k - 1 - i, j + k, ny + k - 1 - j}));
  }
  block.spacing = dx;
  return block;
}

}  // namespace sphstab
