#include "sphstab/particles/lattice.hpp"

#include <gtest/gtest.h>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"

namespace sphstab {
namespace lattice_test {

TEST(Lattice, FixedLayerCountFollowsSupport) {
  EXPECT_EQ(fixed_layers_needed(2.6, 1.0), 2);    // h = 1.3 dx: neighbours at 1, 2 dx
  EXPECT_EQ(fixed_layers_needed(4.0, 1.0), 4);    // borderline layer at exactly 2h kept (see header)
  EXPECT_EQ(fixed_layers_needed(0.03, 0.01), 3);  // 3 * 0.01 rounds above 0.03: still kept
  EXPECT_EQ(fixed_layers_needed(1.6, 1.0), 1);
  auto p = make_lattice<1>(LatticeType::Line, 30, {.spacing = 1.0, .support_radius = 2.6});
  EXPECT_EQ(p.size(), 34);
  EXPECT_EQ(p.count(Role::Free), 30);
  for (int i = 0; i < 30; ++i) EXPECT_EQ(p.role[i], Role::Free);
}

// Every free particle has a complete neighbourhood: sum_j W_ij and sum_j G_ij equal the interior values.
template <int Dim>
void expect_complete(LatticeType type, int n, double h) {
  Kernel<Dim> k(KernelType::QuinticSpline);
  auto p = make_lattice<Dim>(type, n, {.spacing = 1.0, .support_radius = k.support_radius(h)});
  auto nl = find_neighbours(p, k.support_radius(h));
  auto ops = assemble_operators(p, nl, k, h);
  Eigen::VectorXd ws = ops.W * Eigen::VectorXd::Ones(p.size());
  auto periodic = make_lattice<Dim>(type, type == LatticeType::Line ? 40 : 16, {.spacing = 1.0, .periodic = true});
  auto pnl = find_neighbours(periodic, k.support_radius(h));
  double interior = (kernel_matrix(periodic, pnl, k, h) * Eigen::VectorXd::Ones(periodic.size()))[0];
  for (int i = 0; i < p.size(); ++i)
    if (p.role[i] == Role::Free) {
      EXPECT_NEAR(ws[i], interior, 1e-12) << "particle " << i;
      for (int a = 0; a < Dim; ++a) EXPECT_NEAR((ops.G[a] * Eigen::VectorXd::Ones(p.size()))[i], 0.0, 1e-12);
    }
}

TEST(Lattice, FreeParticlesHaveCompleteNeighbourhoods) {
  for (double h : {1.0, 1.3, 2.0, 2.7}) {
    expect_complete<1>(LatticeType::Line, 12, h);
    expect_complete<2>(LatticeType::Square, 6, h);
    expect_complete<2>(LatticeType::Hexagonal, 6, h);
    expect_complete<2>(LatticeType::FaceCentred, 6, h);
  }
}

TEST(Lattice, RejectsBadInput) {
  EXPECT_THROW(make_lattice<1>(LatticeType::Line, 0, {.support_radius = 2}), std::invalid_argument);
  EXPECT_THROW(make_lattice<1>(LatticeType::Square, 5, {.support_radius = 2}), std::invalid_argument);
  EXPECT_THROW(make_lattice<2>(LatticeType::Square, 5, {.spacing = -1, .support_radius = 2}), std::invalid_argument);
  EXPECT_THROW(make_lattice<2>(LatticeType::Hexagonal, 5, {.periodic = true}), std::invalid_argument);
  EXPECT_THROW(make_lattice<2>(LatticeType::Square, 5, {}), std::invalid_argument);  // no support radius
  EXPECT_THROW(parse_lattice_type("triangle"), std::invalid_argument);
}

TEST(Lattice, PerturbationIsSeededAndStretchScales) {
  LatticeOptions opt{.spacing = 1.0, .support_radius = 2.0, .perturbation = 0.2, .seed = 7};
  auto a = make_lattice<2>(LatticeType::Square, 5, opt), b = make_lattice<2>(LatticeType::Square, 5, opt);
  EXPECT_EQ(a.x, b.x);
  auto plain = make_lattice<2>(LatticeType::Square, 5, {.spacing = 1.0, .support_radius = 2.0});
  double max_shift = (a.x - plain.x).cwiseAbs().maxCoeff();
  EXPECT_GT(max_shift, 0.05);
  EXPECT_LE(max_shift, 0.2);
  auto s = make_lattice<2>(LatticeType::Square, 5, {.spacing = 1.0, .support_radius = 2.0, .stretch = 1.01});
  EXPECT_NEAR((s.x - 1.01 * plain.x).norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.volume[0], 1.01 * 1.01, 1e-15);
}

}  // namespace
}  // namespace sphstab
