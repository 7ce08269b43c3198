#pragma once
/// \file particle_set.hpp
/// A set of particles: positions, volumes, roles (free/fixed) and an optional periodic box.
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

namespace sphstab {

enum class Role : unsigned char { Free, Fixed };

/// Plain value type describing N particles in Dim dimensions.
///
/// Shapes: x is N x Dim (row i = particle i); volume, role and depth have N entries.
/// Vector degrees of freedom everywhere in sphstab are interleaved: dof = i * Dim + a.
template <int Dim>
struct ParticleSet {
  using Point = Eigen::Matrix<double, 1, Dim>;
  using Points = Eigen::Matrix<double, Eigen::Dynamic, Dim>;

  Points x;                ///< positions, N x Dim
  Eigen::VectorXd volume;  ///< V_i > 0
  std::vector<Role> role;  ///< Free: an unknown; Fixed: displacement prescribed (boundary layer, clamp)
  /// Boundary level (Powell ch. 2, Fig. 4.3): 0 for the outermost layer of the body, 1 for the next, ...;
  /// lattices set it to the lattice distance from the outside of the body (fixed layers included).
  std::vector<int> depth;
  std::array<bool, Dim> periodic{};  ///< periodic in axis a (minimum-image convention)
  Point box_lo = Point::Zero();      ///< periodic box, used where periodic[a]
  Point box_hi = Point::Zero();
  double spacing = 0;  ///< lattice spacing dx (nearest-neighbour distance), 0 if not a lattice

  /// n free particles of a grid with spacing dp: volume dp^Dim, depth 0, positions left for the caller to set.
  static ParticleSet free_grid(int n, double dp);

  int size() const { return static_cast<int>(x.rows()); }
  int count(Role r) const;
  /// Indices of the particles with role r, ascending.
  std::vector<int> indices(Role r) const;
  /// Positions of the particles with role r, in ascending index (count(r) x Dim): the free block of the DOFs.
  Points positions(Role r) const;
  Point box_length() const { return box_hi - box_lo; }

  /// Minimum-image separation x_i - x_j.
  Point separation(int i, int j) const {
    Point d = x.row(i) - x.row(j);
    for (int a = 0; a < Dim; ++a)
      if (periodic[a]) {
        double L = box_hi[a] - box_lo[a];
        d[a] -= L * std::round(d[a] / L);
      }
    return d;
  }

  /// Throws std::invalid_argument naming the problem if the set is empty, has non-finite coordinates,
  /// non-positive volumes, mismatched array sizes or particles outside a periodic box.
  void validate(const char* who) const;
};

}  // namespace sphstab
