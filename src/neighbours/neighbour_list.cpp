#include "sphstab/neighbours/neighbour_list.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

namespace {

template <int Dim>
void check_inputs(const ParticleSet<Dim>& p, double radius, const char* who) {
  p.validate(who);
  check_length(radius, std::string(who) + ": search radius");
  for (int a = 0; a < Dim; ++a)
    if (p.periodic[a] && p.box_hi[a] - p.box_lo[a] < 2.0 * radius)
      throw std::invalid_argument(std::string(who) + ": periodic box length " +
                                  format_number(p.box_hi[a] - p.box_lo[a]) + " in axis " + std::to_string(a) +
                                  " is shorter than 2 x search radius " + format_number(radius));
}

}  // namespace

template <int Dim>
double expected_neighbour_pairs(const ParticleSet<Dim>& p, double radius) {
  const double n = p.size();
  if (n == 0) return 0;
  // Ball of the radius over the mean particle volume, as a ratio of lengths so that nothing under/overflows.
  const double cell = std::pow(p.volume.mean(), 1.0 / Dim), ratio = radius / cell;
  const double ball =
      Dim == 1 ? 2 * ratio : (Dim == 2 ? M_PI * ratio * ratio : 4.0 / 3.0 * M_PI * ratio * ratio * ratio);
  return n * std::min(n, 1.0 + ball);
}

template <int Dim>
NeighbourList find_neighbours(const ParticleSet<Dim>& p, double radius) {
  check_inputs(p, radius, "find_neighbours");
  const int n = p.size();
  const double pairs = expected_neighbour_pairs(p, radius);
  require_memory(pairs * sizeof(int) * 1.5, "find_neighbours: ~" + format_number(pairs, 3) + " neighbour pairs");
  const double r2 = radius * radius;

  // Cell grid over the bounding box (or the periodic box); cell edge >= radius, at most ~n cells.
  using Point = typename ParticleSet<Dim>::Point;
  Point lo = p.x.colwise().minCoeff(), hi = p.x.colwise().maxCoeff();
  std::array<int, Dim> cells;
  std::array<double, Dim> edge;
  long ncells = 1;
  for (int a = 0; a < Dim; ++a) {
    if (p.periodic[a]) {
      lo[a] = p.box_lo[a];
      hi[a] = p.box_hi[a];
    }
    double L = std::max(hi[a] - lo[a], 0.0);
    // Clamp in double before the cast (L / radius can exceed any int).
    cells[a] = static_cast<int>(std::clamp(std::floor(L / radius), 1.0, 4.0 * n + 4));
  }
  // Sparse sets spread far apart: coarsen so the grid never has more than ~4N cells.
  auto product = [&] {
    long c = 1;
    for (int a = 0; a < Dim; ++a) c *= cells[a];
    return c;
  };
  while (product() > 4L * n + 64) {
    int big = static_cast<int>(std::max_element(cells.begin(), cells.end()) - cells.begin());
    cells[big] = std::max(1, cells[big] / 2);
  }
  for (int a = 0; a < Dim; ++a) {
    double L = std::max(hi[a] - lo[a], 0.0);
    edge[a] = L > 0 ? L / cells[a] : 1.0;
    if (!p.periodic[a]) edge[a] = std::max(edge[a], radius);
    ncells *= cells[a];
  }
  auto cell_coord = [&](int i, int a) {
    return static_cast<int>(std::clamp(std::floor((p.x(i, a) - lo[a]) / edge[a]), 0.0, cells[a] - 1.0));
  };

  // Counting sort of particles into cells.
  std::vector<long> cell_start(ncells + 1, 0);
  std::vector<long> cell_of(n);
  for (int i = 0; i < n; ++i) {
    long c = 0;
    for (int a = Dim - 1; a >= 0; --a) c = c * cells[a] + cell_coord(i, a);
    cell_of[i] = c;
    ++cell_start[c + 1];
  }
  for (long c = 0; c < ncells; ++c) cell_start[c + 1] += cell_start[c];
  std::vector<int> sorted(n);
  {
    std::vector<long> fill(cell_start.begin(), cell_start.end() - 1);
    for (int i = 0; i < n; ++i) sorted[fill[cell_of[i]]++] = i;
  }

  // Positions in cell order, so that a cell's candidates are read contiguously.
  std::vector<Point> xs(n);
  for (int s = 0; s < n; ++s) xs[s] = p.x.row(sorted[s]);
  std::array<double, Dim> period;
  bool any_periodic = false;
  for (int a = 0; a < Dim; ++a) {
    period[a] = p.box_hi[a] - p.box_lo[a];
    any_periodic = any_periodic || p.periodic[a];
  }

  // One row: its neighbours in index order (appended to `out`), the same whichever thread finds it.
  const auto find_row = [&](int i, std::vector<int>& row, std::vector<int>& out) {
    row.clear();
    const Point xi = p.x.row(i);
    std::array<int, Dim> ci;
    for (int a = 0; a < Dim; ++a) ci[a] = cell_coord(i, a);
    // Visit the 3^Dim surrounding cells (fewer when an axis has < 3 cells, to avoid double visits).
    std::array<int, Dim> span;
    for (int a = 0; a < Dim; ++a) span[a] = std::min(3, cells[a]);
    int combos = 1;
    for (int a = 0; a < Dim; ++a) combos *= span[a];
    for (int k = 0; k < combos; ++k) {
      int rest = k;
      long c = 0;
      bool skip = false;
      std::array<int, Dim> cc;
      for (int a = 0; a < Dim; ++a) {
        int off = rest % span[a] - (span[a] == 3 ? 1 : 0);
        rest /= span[a];
        int v = span[a] == 3 ? ci[a] + off : off;  // fewer than 3 cells: visit all of them
        if (v < 0 || v >= cells[a]) {
          if (!p.periodic[a]) {
            skip = true;
            break;
          }
          v = (v + cells[a]) % cells[a];
        }
        cc[a] = v;
      }
      if (skip) continue;
      for (int a = Dim - 1; a >= 0; --a) c = c * cells[a] + cc[a];
      // ParticleSet::separation()'s arithmetic; appended without a branch (about a third of the candidates pass).
      const long s0 = cell_start[c], s1 = cell_start[c + 1];
      std::size_t len = row.size();
      row.resize(len + static_cast<std::size_t>(s1 - s0));
      for (long s = s0; s < s1; ++s) {
        const int j = sorted[s];
        Point d = xi - xs[s];
        if (any_periodic)
          for (int a = 0; a < Dim; ++a)
            if (p.periodic[a]) d[a] -= period[a] * std::round(d[a] / period[a]);
        row[len] = j;
        len += static_cast<std::size_t>((j == i) | (d.squaredNorm() < r2));
      }
      row.resize(len);
    }
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    out.insert(out.end(), row.begin(), row.end());
    return static_cast<long>(row.size());
  };

  // Rows in contiguous blocks, one per thread, each into its own buffer (reserved from the expected pair count: a
  // rebuild of the rings' Verlet list otherwise reallocates and page-faults its way up); the blocks are joined in
  // order, so the list is the same for any thread count (tests/neighbours: 1, 2 and 3 threads).
  NeighbourList list;
  list.radius = radius;
  list.offsets.assign(n + 1, 0);
  const int threads = threads_for(n);
  std::vector<std::vector<int>> block(threads);
  FirstException first;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int t = 0; t < threads; ++t)
    first.run([&] {
      const int i0 = static_cast<int>(static_cast<long>(n) * t / threads);
      const int i1 = static_cast<int>(static_cast<long>(n) * (t + 1) / threads);
      block[t].reserve(static_cast<std::size_t>(1.1 * pairs * (i1 - i0) / std::max(n, 1)) + 64);
      std::vector<int> row;
      for (int i = i0; i < i1; ++i) list.offsets[i + 1] = find_row(i, row, block[t]);
    });
  first.rethrow();
  for (int i = 0; i < n; ++i) list.offsets[i + 1] += list.offsets[i];
  if (threads == 1) {
    list.indices = std::move(block[0]);
  } else {
    list.indices.reserve(static_cast<std::size_t>(list.offsets[n]));
    for (const std::vector<int>& b : block) list.indices.insert(list.indices.end(), b.begin(), b.end());
  }
  return list;
}

template <int Dim>
NeighbourList find_neighbours_brute_force(const ParticleSet<Dim>& p, double radius) {
  check_inputs(p, radius, "find_neighbours_brute_force");
  const int n = p.size();
  NeighbourList list;
  list.radius = radius;
  list.offsets.assign(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j)
      if (j == i || p.separation(i, j).squaredNorm() < radius * radius) list.indices.push_back(j);
    list.offsets[i + 1] = static_cast<long>(list.indices.size());
  }
  return list;
}

#define SPHSTAB_INSTANTIATE(D)                                                \
  template double expected_neighbour_pairs<D>(const ParticleSet<D>&, double); \
  template NeighbourList find_neighbours<D>(const ParticleSet<D>&, double);   \
  template NeighbourList find_neighbours_brute_force<D>(const ParticleSet<D>&, double);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
