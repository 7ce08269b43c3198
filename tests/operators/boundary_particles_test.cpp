// Boundary particles and normals (operators/boundary_particles.hpp, [Powell2012, (2.51)-(2.53), algorithm 2.2]) on
// regular grids: outer layer, inner layers, exact edge normals, diagonal corners; the loop guard and the one-line
// errors.
#include "sphstab/operators/boundary_particles.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "../forms/forms_fixture.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/particles/lattice.hpp"

namespace sphstab {
namespace boundary_particles_test {

using test::free_block;

TEST(BoundaryParticles, SquareBlockLayersAndNormals) {
  const int nx = 20, ny = 16;
  const double dx = 0.01;
  const Kernel<2> kernel(KernelType::CubicSpline);
  for (double hdx : {1.3, 1.7}) {
    const double h = hdx * dx;
    const ParticleSet<2> p = free_block(nx, ny, dx);
    const NeighbourList nl = find_neighbours(p, kernel.support_radius(h));
    const BoundaryParticles<2> b = boundary_particles(p, kernel, h, nl);
    const int expected_layers = static_cast<int>(std::floor(2 * hdx)) + 1;  // Powell: floor(2h / dx) + 1
    EXPECT_EQ(b.layers, expected_layers) << hdx;
    EXPECT_EQ(b.candidates_left, 0);
    // (2.53) literally: the layer at distance floor(2h / dx) has full support and is excluded.
    const BoundaryParticles<2> literal = boundary_particles(p, kernel, h, nl, {.exclusion_ratio = 10});
    EXPECT_EQ(literal.layers, expected_layers - 1) << hdx;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int k = j * nx + i;
        const int d = std::min({i, j, nx - 1 - i, ny - 1 - j});  // grid distance to the outside
        if (d >= expected_layers) {
          EXPECT_EQ(b.layer[k], -1) << i << "," << j;
          continue;
        }
        EXPECT_EQ(b.layer[k], d) << hdx << ": " << i << "," << j;
        // Edge normals (away from the corners' reach) are exact; corners are diagonal.
        const bool corner = (i == j || i == nx - 1 - j) && (i < expected_layers || nx - 1 - i < expected_layers);
        const Eigen::RowVector2d n = b.normal.row(k);
        EXPECT_NEAR(n.norm(), 1.0, 1e-14);
        if (i == 0 && j >= expected_layers + 2 && j < ny - expected_layers - 2) EXPECT_NEAR(n[0], -1.0, 1e-12);
        if (j == ny - 1 && i >= expected_layers + 2 && i < nx - expected_layers - 2) EXPECT_NEAR(n[1], 1.0, 1e-12);
        if (corner && i == 0 && j == 0) {
          EXPECT_NEAR(n[0], -std::sqrt(0.5), 1e-12);
          EXPECT_NEAR(n[1], -std::sqrt(0.5), 1e-12);
        }
      }
  }
}

TEST(BoundaryParticles, LineEndsAndErrors) {
  const Kernel<1> kernel(KernelType::CubicSpline);
  const double dx = 0.01, h = 1.3 * dx;
  const ParticleSet<1> p = make_lattice<1>(LatticeType::Line, 100, {.spacing = dx, .fixed_layers = 0});
  const NeighbourList nl = find_neighbours(p, kernel.support_radius(h));
  const BoundaryParticles<1> b = boundary_particles(p, kernel, h, nl);
  EXPECT_EQ(b.layers, 3);  // floor(2h/dx) + 1 = 3 layers in 1D at h = 1.3 dx ([Powell2012, Fig. 2.12])
  for (int i = 0; i < 100; ++i) {
    const int d = std::min(i, 99 - i);
    EXPECT_EQ(b.layer[i], d < 3 ? d : -1) << i;
    if (d < 3) EXPECT_EQ(b.normal(i, 0), i < 50 ? -1.0 : 1.0) << i;
  }
  // A periodic line has no boundary.
  const ParticleSet<1> ring = make_lattice<1>(LatticeType::Line, 100, {.spacing = dx, .periodic = true});
  EXPECT_THROW(boundary_particles(ring, kernel, h, find_neighbours(ring, kernel.support_radius(h))), std::domain_error);
  // The loop guard: one pass allowed, a second needed.
  EXPECT_THROW(boundary_particles(p, kernel, h, nl, {.max_passes = 1}), std::domain_error);
  EXPECT_THROW(boundary_particles(p, kernel, h, nl, {.outer_ratio = 1.0}), std::invalid_argument);
  EXPECT_THROW(boundary_particles(p, kernel, h, nl, {.exclusion_ratio = -1}), std::invalid_argument);
  // (2.53) with Powell's ratio 10 excludes the full-support particles: only the two deficient layers remain.
  const BoundaryParticles<1> literal = boundary_particles(p, kernel, h, nl, {.exclusion_ratio = 10});
  EXPECT_EQ(literal.layers, 2);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(literal.layer[i], std::min(i, 99 - i) < 2 ? std::min(i, 99 - i) : -1) << i;
  // Manual normals: normalised; zero length refused with the particle named.
  BoundaryParticles<1> m = b;
  Eigen::Matrix<double, Eigen::Dynamic, 1> normals = Eigen::VectorXd::Constant(b.particles.size(), 3.0);
  set_manual_normals(m, normals);
  EXPECT_EQ(m.normal(0, 0), 1.0);
  normals(2, 0) = 0;
  try {
    set_manual_normals(m, normals);
    FAIL() << "zero normal accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("particle " + std::to_string(b.particles[2])), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sphstab
