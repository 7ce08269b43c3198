#include "sphstab/neighbours/neighbour_list.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/core/huge_page_allocator.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/numerics/instantiation.hpp"

#if SPHSTAB_HAS_AVX2_CLONES
#include <immintrin.h>
#endif

namespace sphstab {

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

namespace detail {

#if SPHSTAB_HAS_AVX2_CLONES
namespace {

/// For each 4-bit mask, the byte shuffle that moves the 32-bit lanes it selects to the front, in order.
struct CompressTable {
  alignas(16) std::uint8_t shuffle[16][16];
  constexpr CompressTable() : shuffle{} {
    for (int m = 0; m < 16; ++m) {
      int to = 0;
      for (int lane = 0; lane < 4; ++lane)
        if (m >> lane & 1) {
          for (int b = 0; b < 4; ++b) shuffle[m][4 * to + b] = static_cast<std::uint8_t>(4 * lane + b);
          ++to;
        }
      for (int b = 4 * to; b < 16; ++b) shuffle[m][b] = 0x80;  // zero: written past the kept ones, overwritten later
    }
  }
};
constexpr CompressTable kCompress{};

/// The 2D scan of find_neighbours (no periodic axis) four candidates at a time: per candidate the scalar scan's
/// operations (d = x_i - x_j, d_x d_x + d_y d_y < r^2, or j == i), so the same rows; the kept indices moved to the
/// front by a shuffle and stored four at a time (the caller has room for the whole range).
SPHSTAB_TARGET_AVX2 std::size_t scan_2d_avx2(const double* xs, const int* sorted, long s0, long s1, double xi,
                                             double yi, int i, double r2, int* out, std::size_t used) {
  const __m256d vxi = _mm256_set1_pd(xi), vyi = _mm256_set1_pd(yi), vr2 = _mm256_set1_pd(r2);
  const __m128i vi = _mm_set1_epi32(i);
  long s = s0;
  for (; s + 4 <= s1; s += 4) {
    const __m256d a = _mm256_loadu_pd(xs + 2 * s), b = _mm256_loadu_pd(xs + 2 * s + 4);  // x0 y0 x1 y1, x2 y2 x3 y3
    const __m256d lo = _mm256_permute2f128_pd(a, b, 0x20), hi = _mm256_permute2f128_pd(a, b, 0x31);
    const __m256d dx = _mm256_sub_pd(vxi, _mm256_unpacklo_pd(lo, hi)),
                  dy = _mm256_sub_pd(vyi, _mm256_unpackhi_pd(lo, hi));
    const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const __m128i js = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sorted + s));
    const int keep = _mm256_movemask_pd(_mm256_cmp_pd(d2, vr2, _CMP_LT_OQ)) |
                     _mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(js, vi)));
    const __m128i shuffle = _mm_load_si128(reinterpret_cast<const __m128i*>(kCompress.shuffle[keep]));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + used), _mm_shuffle_epi8(js, shuffle));
    used += static_cast<std::size_t>(std::popcount(static_cast<unsigned>(keep)));
  }
  for (; s < s1; ++s) {
    const int j = sorted[s];
    const double dx = xi - xs[2 * s], dy = yi - xs[2 * s + 1];
    out[used] = j;
    used += static_cast<std::size_t>((j == i) | (dx * dx + dy * dy < r2));
  }
  return used;
}

}  // namespace
#endif

/// Cells of edge >= radius / kCellsPerRadius over the bounding box (or the periodic box), the particles counting-sorted
/// into them, and their positions in that order, so that a row's candidates are read contiguously. Cells of half the
/// radius: the candidates of a row cover (2.5 r)^Dim instead of (3 r)^Dim, about 30 % fewer in 2D (the SI rings'
/// search 1.1x faster with the contiguous runs below than with radius-sized cells, measured).
template <int Dim>
struct CellGrid {
  static constexpr double kCellsPerRadius = 2;
  using Point = typename ParticleSet<Dim>::Point;

  const ParticleSet<Dim>& p;
  Point lo;
  std::array<int, Dim> cells, reach;  ///< cells per axis; cells a neighbour can be away along the axis
  std::array<double, Dim> edge, period;
  bool any_periodic = false;
  std::vector<long> cell_start;  ///< the particles of cell c at sorted positions [cell_start[c], cell_start[c + 1])
  std::vector<int> sorted;       ///< particle indices, by cell and within a cell ascending
  std::vector<Point> xs;         ///< their positions

  CellGrid(const ParticleSet<Dim>& set, double radius) : p(set) {
    const int n = p.size();
    lo = p.x.colwise().minCoeff();
    Point hi = p.x.colwise().maxCoeff();
    for (int a = 0; a < Dim; ++a) {
      if (p.periodic[a]) {
        lo[a] = p.box_lo[a];
        hi[a] = p.box_hi[a];
      }
      // Clamp in double before the cast (L / radius can exceed any int).
      const double L = std::max(hi[a] - lo[a], 0.0);
      cells[a] = static_cast<int>(std::clamp(std::floor(kCellsPerRadius * L / radius), 1.0, 4.0 * n + 4));
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
      const double L = std::max(hi[a] - lo[a], 0.0);
      edge[a] = L > 0 ? L / cells[a] : 1.0;
      if (!p.periodic[a]) edge[a] = std::max(edge[a], radius / kCellsPerRadius);
      // |x_j - x_i| < r along a puts j at most ceil(r / edge) cells from i.
      reach[a] = static_cast<int>(std::min<double>(std::ceil(radius / edge[a]), cells[a]));
      period[a] = p.box_hi[a] - p.box_lo[a];
      any_periodic = any_periodic || p.periodic[a];
    }
    // Counting sort of the particles into cells (stable: ascending within a cell).
    cell_start.assign(product() + 1, 0);
    std::vector<long> cell_of(n);
    for (int i = 0; i < n; ++i) {
      cell_of[i] = cell_index(i);
      ++cell_start[cell_of[i] + 1];
    }
    for (std::size_t c = 0; c + 1 < cell_start.size(); ++c) cell_start[c + 1] += cell_start[c];
    sorted.resize(n);
    std::vector<long> fill(cell_start.begin(), cell_start.end() - 1);
    for (int i = 0; i < n; ++i) sorted[fill[cell_of[i]]++] = i;
    xs.resize(n);
    for (int s = 0; s < n; ++s) xs[s] = p.x.row(sorted[s]);
  }

  int coord(int i, int a) const {
    return static_cast<int>(std::clamp(std::floor((p.x(i, a) - lo[a]) / edge[a]), 0.0, cells[a] - 1.0));
  }
  long cell_index(int i) const {
    long c = 0;
    for (int a = Dim - 1; a >= 0; --a) c = c * cells[a] + coord(i, a);
    return c;
  }

  /// The runs of cells particle i's row visits along axis a (one, or two where a periodic axis wraps): ci - reach ..
  /// ci + reach, clipped in a bounded axis; every cell once when the axis has at most 2 reach + 1 cells.
  int axis_runs(int i, int a, std::array<int, 2>& from, std::array<int, 2>& to) const {
    const int ci = coord(i, a), c0 = ci - reach[a], c1 = ci + reach[a];
    if (2 * reach[a] + 1 >= cells[a]) {
      from[0] = 0, to[0] = cells[a] - 1;
      return 1;
    }
    if (!p.periodic[a] || (c0 >= 0 && c1 < cells[a])) {
      from[0] = std::max(c0, 0), to[0] = std::min(c1, cells[a] - 1);
      return 1;
    }
    if (c0 < 0) {
      from = {0, c0 + cells[a]}, to = {c1, cells[a] - 1};
    } else {
      from = {c0, 0}, to = {cells[a] - 1, c1 - cells[a]};
    }
    return 2;
  }

  /// Calls scan(s0, s1) for the ranges of sorted positions holding row i's candidates, each candidate once. Axis 0
  /// varies fastest in the cell index, so a run of cells along it is one range.
  template <class Scan>
  void for_each_candidate_range(int i, const Scan& scan) const {
    std::array<std::array<int, 2>, Dim> from, to;
    std::array<int, Dim> runs, cc, run{};
    for (int a = 0; a < Dim; ++a) {
      runs[a] = axis_runs(i, a, from[a], to[a]);
      cc[a] = from[a][0];
    }
    while (true) {
      long base = 0;
      for (int a = Dim - 1; a >= 1; --a) base = base * cells[a] + cc[a];
      base *= cells[0];
      for (int r = 0; r < runs[0]; ++r) scan(cell_start[base + from[0][r]], cell_start[base + to[0][r] + 1]);
      // The next cell of axes 1 .. Dim-1, odometer-style.
      int a = 1;
      for (; a < Dim; ++a) {
        if (cc[a] < to[a][run[a]]) {
          ++cc[a];
          break;
        }
        if (run[a] + 1 < runs[a]) {
          cc[a] = from[a][++run[a]];
          break;
        }
        run[a] = 0;
        cc[a] = from[a][0];
      }
      if (a == Dim) return;
    }
  }
};

/// The rows bound[t] .. bound[t + 1] into block[t], one block per thread (sized from the expected pairs per row);
/// count[i] = row i's length. A function, not a generic lambda: clang 14 refuses an OpenMP region inside one.
template <class Block, class FindRow>
void search_row_blocks(std::vector<Block>& block, const std::vector<int>& bound, double pairs_per_row,
                       const FindRow& find_row, std::vector<long>& count) {
  const int threads = static_cast<int>(block.size());
  FirstException first;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int t = 0; t < threads; ++t)
    first.run([&] {
      block[t].resize(static_cast<std::size_t>(1.1 * pairs_per_row * (bound[t + 1] - bound[t])) + 64);
      std::size_t used = 0;
      for (int i = bound[t]; i < bound[t + 1]; ++i) count[i] = find_row(i, block[t], used);
      block[t].resize(used);
    });
  first.rethrow();
}

template <int Dim>
NeighbourList find_neighbours(const ParticleSet<Dim>& p, double radius, RowOrder order) {
  check_inputs(p, radius, "find_neighbours");
  const int n = p.size();
  const double pairs = expected_neighbour_pairs(p, radius);
  // The transpose holds the unsorted rows beside the list: two copies of the pairs.
  require_memory(pairs * sizeof(int) * (order == RowOrder::Transpose ? 2.5 : 1.5),
                 "find_neighbours: ~" + format_number(pairs, 3) + " neighbour pairs");
  const double r2 = radius * radius;
  const CellGrid<Dim> grid(p, radius);
  const bool avx2 = Dim == 2 && !grid.any_periodic && avx2_enabled();  // scan_2d_avx2 reads xs as x, y pairs
  static_assert(sizeof(typename CellGrid<Dim>::Point) == Dim * sizeof(double));
  (void)avx2;

  // Row i's neighbours in cell order, appended at out[used..] without a branch (about half the candidates pass), by
  // ParticleSet::separation()'s arithmetic. Exactly symmetric: x_j - x_i = -(x_i - x_j) and round(-t) = -round(t).
  // `out` grows geometrically and is cut to `used` at the end (a resize per cell run would zero-fill every time).
  const auto find_row = [&](int i, auto& out, std::size_t& used) {
    using Point = typename ParticleSet<Dim>::Point;
    const Point xi = p.x.row(i);
    const std::size_t start = used;
    grid.for_each_candidate_range(i, [&](long s0, long s1) {
      if (out.size() < used + static_cast<std::size_t>(s1 - s0))
        out.resize(std::max(2 * out.size(), used + static_cast<std::size_t>(s1 - s0)));
      int* const o = out.data();
#if SPHSTAB_HAS_AVX2_CLONES
      if constexpr (Dim == 2)
        if (avx2) {
          used = scan_2d_avx2(grid.xs.data()->data(), grid.sorted.data(), s0, s1, xi[0], xi[1], i, r2, o, used);
          return;
        }
#endif
      for (long s = s0; s < s1; ++s) {
        const int j = grid.sorted[s];
        Point d = xi - grid.xs[s];
        if (grid.any_periodic)
          for (int a = 0; a < Dim; ++a)
            if (p.periodic[a]) d[a] -= grid.period[a] * std::round(d[a] / grid.period[a]);
        o[used] = j;
        used += static_cast<std::size_t>((j == i) | (d.squaredNorm() < r2));
      }
    });
    if (order == RowOrder::Sort)
      std::sort(out.begin() + static_cast<long>(start), out.begin() + static_cast<long>(used));
    return static_cast<long>(used - start);
  };

  // Rows in contiguous blocks, one per thread, each into its own buffer (sized from the expected pair count: a
  // rebuild of the rings' Verlet list otherwise reallocates and page-faults its way up).
  const int threads = threads_for(n);
  std::vector<int> bound(threads + 1);
  for (int t = 0; t <= threads; ++t) bound[t] = static_cast<int>(static_cast<long>(n) * t / threads);
  std::vector<long> count(n);
  const double pairs_per_row = pairs / std::max(n, 1);

  NeighbourList list;
  list.radius = radius;
  const auto set_offsets = [&] {
    list.offsets.assign(n + 1, 0);
    for (int i = 0; i < n; ++i) list.offsets[i + 1] = list.offsets[i] + count[i];
  };
  if (order == RowOrder::Sort) {  // the blocks joined in order (one block becomes the list: no copy)
    std::vector<std::vector<int>> block(threads);
    search_row_blocks(block, bound, pairs_per_row, find_row, count);
    set_offsets();
    if (threads == 1) {
      list.indices = std::move(block[0]);
    } else {
      list.indices.reserve(static_cast<std::size_t>(list.offsets[n]));
      for (const std::vector<int>& b : block) list.indices.insert(list.indices.end(), b.begin(), b.end());
    }
    return list;
  }
  // The transpose's blocks are scratch, dropped at the end: huge-page work arrays (core/huge_page_allocator.hpp),
  // which a rebuild into fresh memory faults in 2 MiB at a time.
  std::vector<HugePageVector<int>> block(threads);
  search_row_blocks(block, bound, pairs_per_row, find_row, count);
  set_offsets();
  // The pattern is symmetric, so row j holds count[j] entries, the i whose rows hold j, and visiting i in ascending
  // order writes them sorted. Thread t writes the rows of its own block.
  list.indices.resize(static_cast<std::size_t>(list.offsets[n]));
  std::vector<long> next(list.offsets.begin(), list.offsets.end() - 1);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    const int j0 = bound[t], j1 = bound[t + 1];
    for (int u = 0; u < threads; ++u) {
      const int* q = block[u].data();
      for (int i = bound[u]; i < bound[u + 1]; ++i)
        for (const int* const end = q + count[i]; q < end; ++q)
          if (*q >= j0 && *q < j1) list.indices[next[*q]++] = i;
    }
  }
  return list;
}

}  // namespace detail

template <int Dim>
NeighbourList find_neighbours(const ParticleSet<Dim>& p, double radius) {
  // Sorted rows by a transpose rather than a sort per row for lists up to 16 MB: the size of the Verlet lists a run
  // rebuilds again and again, whose buffers come back from the heap (the SI rings' 0.6 M pairs: the sort per row took
  // 2.8 of the search's 6.3 ms with radius-sized cells; the search is 2.8 ms with half-radius cells and the transpose).
  // A larger list is mostly a single search into fresh memory, where touching the transpose's second copy costs more
  // than the sort saves (a 3D lattice of 85 k particles, 6.5 M pairs, one search in a fresh process: 0.17 s sorting,
  // 0.22 s by the transpose; page faults are slow on this machine).
  constexpr double kTransposeBytes = 16.0 * (1 << 20);
  const bool transpose = expected_neighbour_pairs(p, radius) * sizeof(int) <= kTransposeBytes;
  return detail::find_neighbours(p, radius, transpose ? detail::RowOrder::Transpose : detail::RowOrder::Sort);
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

#define SPHSTAB_INSTANTIATE(D)                                                                        \
  template double expected_neighbour_pairs<D>(const ParticleSet<D>&, double);                         \
  template NeighbourList detail::find_neighbours<D>(const ParticleSet<D>&, double, detail::RowOrder); \
  template NeighbourList find_neighbours<D>(const ParticleSet<D>&, double);                           \
  template NeighbourList find_neighbours_brute_force<D>(const ParticleSet<D>&, double);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
