#include "sphstab/neighbours/neighbour_list.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "sphstab/core/simd_dispatch.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace neighbour_list_test {

template <int Dim>
ParticleSet<Dim> random_set(int n, double box, bool periodic, unsigned seed) {
  ParticleSet<Dim> p;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, box);
  p.x.resize(n, Dim);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < Dim; ++a) p.x(i, a) = u(rng);
  // Coincident points: duplicate a few particles exactly.
  for (int i = 0; i + 1 < n && i < 6; i += 2) p.x.row(i + 1) = p.x.row(i);
  p.volume = Eigen::VectorXd::Ones(n);
  p.role.assign(n, Role::Free);
  if (periodic) {
    p.periodic.fill(true);
    p.box_lo.setZero();
    p.box_hi.setConstant(box);
  }
  return p;
}

/// The search (both ways of sorting its rows; the 2D scan by the AVX2 clone, where the CPU has it, and by the baseline
/// build) against the brute-force reference.
template <int Dim>
void expect_same(const ParticleSet<Dim>& p, double radius) {
  const NeighbourList b = find_neighbours_brute_force(p, radius);
  for (bool portable : {false, true}) {
    std::optional<PortableSimdGuard> guard;
    if (portable) guard.emplace();
    for (detail::RowOrder order : {detail::RowOrder::Transpose, detail::RowOrder::Sort}) {
      const NeighbourList a = detail::find_neighbours(p, radius, order);
      ASSERT_EQ(a.offsets, b.offsets);
      ASSERT_EQ(a.indices, b.indices);
    }
  }
  ASSERT_EQ(find_neighbours(p, radius).indices, b.indices);
}

TEST(NeighbourList, MatchesBruteForceOnRandomSets) {
  for (bool periodic : {false, true})
    for (unsigned seed : {1u, 2u, 3u}) {
      expect_same(random_set<1>(300, 10.0, periodic, seed), 0.37);
      expect_same(random_set<2>(600, 10.0, periodic, seed), 0.81);
      expect_same(random_set<3>(800, 6.0, periodic, seed), 1.3);
    }
}

TEST(NeighbourList, MatchesBruteForceInSmallPeriodicBoxesAndSparseSets) {
  // The cells are half the radius, a row visits 2 ceil(r / edge) + 1 cells per axis: periodic boxes of 2.05 r (every
  // cell visited), 3 r and 5.3 r (runs that wrap), and sets so sparse that the grid is coarsened (cells wider than r).
  for (double box_over_r : {2.05, 3.0, 5.3})
    for (unsigned seed : {4u, 5u}) {
      expect_same(random_set<1>(40, 1.0, true, seed), 1.0 / box_over_r);
      expect_same(random_set<2>(150, 1.0, true, seed), 1.0 / box_over_r);
      expect_same(random_set<3>(200, 1.0, true, seed), 1.0 / box_over_r);
    }
  for (bool periodic : {false, true}) {
    expect_same(random_set<2>(40, 1000.0, periodic, 6u), 40.0);
    expect_same(random_set<3>(40, 1000.0, periodic, 6u), 120.0);
  }
}

TEST(NeighbourList, SameListOnAnyThreadCount) {
  // Rows are searched in one block per thread and the blocks joined in order: the list may not depend on the count.
  // 3000 rows: at least kMinRowsPerThread rows for each of 3 threads, so every count really splits the rows.
  ASSERT_GE(3000 / 3, kMinRowsPerThread);
  for (bool periodic : {false, true}) {
    const ParticleSet<2> p = random_set<2>(3000, 30.0, periodic, 7u);
    const NeighbourList reference = find_neighbours_brute_force(p, 0.81);
    ASSERT_GT(reference.indices.size(), 3u * 3000u);  // not only the particles themselves
    for (int threads : {1, 2, 3}) {
      const ThreadCountGuard guard(threads);
      ASSERT_EQ(threads_for(3000), threads);
      for (detail::RowOrder order : {detail::RowOrder::Transpose, detail::RowOrder::Sort}) {
        const NeighbourList list = detail::find_neighbours(p, 0.81, order);
        EXPECT_EQ(list.offsets, reference.offsets) << threads << " threads, periodic " << periodic;
        EXPECT_EQ(list.indices, reference.indices) << threads << " threads, periodic " << periodic;
      }
    }
  }
}

TEST(NeighbourList, MatchesBruteForceOnLattices) {
  LatticeOptions opt{.spacing = 0.1, .support_radius = 0.26};
  expect_same(make_lattice<1>(LatticeType::Line, 40, opt), 0.26);
  expect_same(make_lattice<2>(LatticeType::Square, 17, opt), 0.26);
  expect_same(make_lattice<2>(LatticeType::Hexagonal, 16, opt), 0.26);
  expect_same(make_lattice<3>(LatticeType::Cubic, 7, opt), 0.26);
  opt.periodic = true;
  expect_same(make_lattice<1>(LatticeType::Line, 40, opt), 0.26);
  expect_same(make_lattice<2>(LatticeType::Square, 12, opt), 0.26);
  expect_same(make_lattice<2>(LatticeType::Hexagonal, 12, opt), 0.26);
  expect_same(make_lattice<3>(LatticeType::Cubic, 6, opt), 0.26);
}

TEST(NeighbourList, PeriodicWrapFindsImages) {
  auto p = make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .periodic = true});
  auto nl = find_neighbours(p, 1.5);
  // Particle 0 at 0.5 sees 9 (at 9.5) through the wrap.
  std::vector<int> row0(nl.indices.begin() + nl.offsets[0], nl.indices.begin() + nl.offsets[1]);
  EXPECT_EQ(row0, (std::vector<int>{0, 1, 9}));
}

TEST(NeighbourList, RejectsBadInput) {
  auto p = make_lattice<1>(LatticeType::Line, 10, {.spacing = 1.0, .periodic = true});
  EXPECT_THROW(find_neighbours(p, 0.0), std::invalid_argument);
  EXPECT_THROW(find_neighbours(p, -1.0), std::invalid_argument);
  EXPECT_THROW(find_neighbours(p, 6.0), std::invalid_argument);  // box 10 < 2 x 6
  ParticleSet<2> empty;
  EXPECT_THROW(find_neighbours(empty, 1.0), std::invalid_argument);
  auto q = random_set<2>(10, 1.0, false, 1);
  q.x(3, 1) = std::nan("");
  EXPECT_THROW(find_neighbours(q, 0.3), std::invalid_argument);
}

}  // namespace neighbour_list_test
}  // namespace sphstab
