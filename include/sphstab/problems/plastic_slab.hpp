#pragma once
/// \file plastic_slab.hpp
/// The slab in tension of Gray, Monaghan & Swift [GMS2001, §7.3 "Fracture"]: a slab of length L = 3 (along x) and
/// width W = 1 (along y), square grid of spacing dp = 0.016, pulled apart by giving the particles within 0.2 of each
/// end a constant acceleration a = 5e-6 along the long axis (-a x̂ at the left end, +a x̂ at the right end). Units of
/// GMS: rho0 = c0 = 1, cm; mu = 0.3, von Mises yield 0.03, no damage model (fracture emerges from necking). With
/// eps = 0 the slab breaks unphysically at the forced/free junction by t = 119; with eps = 0.3 it necks from t = 394
/// and breaks at t = 542 with the neck ~10 particles thick ([GMS2001, §7.3, Figs. 8-10]).
///
/// Each end moves d(t) = a t^2 / 2 (slab_end_displacement): 2.5e-6 t^2, 0.4 at t = 400.
/// \note GMS's "strain 0.13" at t = 400 is 0.4 / 3, the displacement of ONE end over the length. Both ends move, so
///       the elongation is 2 d = 0.8 and the engineering strain 2 d / L = 0.27 (or 2 d / (L - 2 * 0.2) = 0.31 over
///       the part between the driven zones). [GMS2001, §7.3] is ambiguous here; this file does not pick a strain, it
///       gives d(t).
///
/// Grid (our choices where GMS give none): L / dp = 187.5 and W / dp = 62.5 are not whole numbers, so the slab has
/// n_x = ceil(L / dp) columns and n_y = ceil(W / dp) rows (1e-9 relative tolerance, so a whole number stays itself),
/// centred on the origin: x = (c - (n_x - 1)/2) dp, y = (r - (n_y - 1)/2) dp. GMS: 188 x 63 = 11844 particles; the
/// particle body (cells of side dp) is n_x dp = 3.008 by n_y dp = 1.008. A particle is driven at the left end when
/// x <= -L/2 + end_zone, at the right end when x >= L/2 - end_zone (tolerance 1e-9 dp), distances measured from the
/// nominal ends x = -+L/2. GMS: the first column is 0.004 inside the nominal end, so 13 columns (0.004 + 12 dp = 0.196
/// <= 0.2) are driven at each end, 13 x 63 = 819 particles per end.
#include <Eigen/Core>
#include <vector>

#include "sphstab/particles/particle_set.hpp"

namespace sphstab {

struct PlasticSlabOptions {
  double length = 3;           ///< L > 0, along x
  double width = 1;            ///< W > 0, along y (GMS's "height")
  double spacing = 0.016;      ///< dp > 0, with at least 2 rows and a free column between the driven zones
  double end_zone = 0.2;       ///< > 0, width of each driven zone (from the nominal end); 2 end_zone < L
  double acceleration = 5e-6;  ///< a, finite (negative: the ends are pushed in)
};

struct PlasticSlab {
  PlasticSlabOptions options;
  /// n_x n_y particles by column (x ascending) then row (y ascending): particle c n_y + r. All Role::Free, volume
  /// dp^2, spacing dp, depth = min(c, n_x - 1 - c, r, n_y - 1 - r) (grid distance from the outside).
  ParticleSet<2> particles;
  int columns = 0, rows = 0;   ///< n_x, n_y
  std::vector<int> left_end;   ///< driven particles at the left end, ascending
  std::vector<int> right_end;  ///< driven particles at the right end, ascending
  std::vector<int> driven;     ///< left_end then right_end (ascending, as the left end has the lower indices)
  /// Prescribed acceleration of driven[k] in column k, 2 x driven.size(): (-a, 0) at the left end, (+a, 0) at the
  /// right end.
  Eigen::Matrix2Xd driven_acceleration;

  int size() const { return particles.size(); }
};

/// Builds the slab of [GMS2001, §7.3] (see the file comment for the grid and the driven zones). Throws
/// std::invalid_argument with a one-line message for non-finite options, L, W, dp or end_zone <= 0, fewer than 2
/// rows, an end zone holding no column or leaving no free column between the zones, or lengths outside
/// check_length()'s range; std::length_error when the counts overflow; MemoryLimitError (core/memory_budget.hpp) when
/// the particles do not fit the memory limit.
PlasticSlab make_plastic_slab(const PlasticSlabOptions& options = {});

/// Displacement a t^2 / 2 of one driven end at time t from rest (the prescribed motion of [GMS2001, §7.3]:
/// 2.5e-6 t^2 for a = 5e-6). Throws std::invalid_argument for non-finite t or a.
double slab_end_displacement(double time, double acceleration = 5e-6);

}  // namespace sphstab
