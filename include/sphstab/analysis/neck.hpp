#pragma once
/// \file neck.hpp
/// Necking and breaking of a slab pulled along x (the slab in tension of [GMS2001, §7.3], problems/plastic_slab.hpp):
/// the width profile across the slab, its narrowest point, and whether the slab has broken. GMS report the neck by
/// eye ("necking from t = 394, breaks at t = 542 with the neck ~10 particles thick"); these are the measurable
/// versions, kept simple:
///   - width of a bin (a strip x in [x_k, x_k + w)): max y - min y + particle_size over the particles in the strip,
///     i.e. the y-extent counting each particle's own size (particle_size = dp: an unstrained slab of n_y rows has
///     width n_y dp). It is an extent: holes inside the strip are not subtracted, and a stray particle widens it;
///   - the neck: the narrowest occupied bin; empty bins (a strip between two columns, which happens once the columns
///     are stretched further apart than the bin width) have no width and do not count, so choose the bin width
///     above the largest column spacing (e.g. 2 dp at strains up to 100 %), and detect a cut by the break flag;
///   - broken: no fragment (analysis/fragments.hpp) holds both a left-end and a right-end driven particle, i.e. no
///     chain of bonds |x_i - x_j| < bond_radius joins the two ends, so the slab no longer carries load. Stray
///     fragments that leave the ends joined do not count.
///
/// \code{.cpp}
/// sphstab::PlasticSlab slab = sphstab::make_plastic_slab();
/// const double dp = slab.particles.spacing;
/// Eigen::Matrix2Xd x = slab.particles.x.transpose();  // or a Map into the run's state
/// sphstab::SlabNeck neck = sphstab::slab_neck(x, slab.left_end, slab.right_end,
///                                             {.bin_width = dp, .particle_size = dp, .bond_radius = 1.5 * dp});
/// // neck.profile.min_width == 63 dp = 1.008 at t = 0; neck.broken == false
/// \endcode
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "sphstab/analysis/fragments.hpp"

namespace sphstab {

struct NeckProfile {
  double x_lo = 0, x_hi = 0;   ///< the analysed range [x_lo, x_hi]
  double bin_width = 0;        ///< (x_hi - x_lo) / bins, the requested width rounded so that the bins tile the range
  std::vector<double> centre;  ///< bin centres x_lo + (k + 1/2) bin_width
  std::vector<double> width;   ///< max y - min y + particle_size per bin; NaN for an empty bin
  std::vector<int> count;      ///< particles per bin
  /// The narrowest occupied bin (the first one on ties), its width and its centre; -1 / NaN when all bins are empty.
  int min_bin = -1;
  double min_width = std::numeric_limits<double>::quiet_NaN();
  double min_x = std::numeric_limits<double>::quiet_NaN();
};

/// Width profile of the particles with x_lo <= x <= x_hi (positions 2 x N, column i = particle i), in
/// max(1, round((x_hi - x_lo) / bin_width)) bins of equal width tiling [x_lo, x_hi] (a particle at x_hi goes in the
/// last bin). Throws std::invalid_argument for non-finite positions or range, x_hi <= x_lo, bin_width <= 0 or
/// non-finite, particle_size < 0 or non-finite, or more than 10^8 bins.
NeckProfile neck_profile(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, double x_lo, double x_hi,
                         double bin_width, double particle_size);

/// True when no fragment holds both a particle of `left` and one of `right` (the ends are not joined by bonds).
/// Throws std::invalid_argument for an empty list or an index outside [0, fragments.label.size()).
bool ends_separated(const Fragments& fragments, const std::vector<int>& left, const std::vector<int>& right);

struct SlabNeckOptions {
  double bin_width = 0;      ///< > 0, e.g. dp (2 dp once the columns are stretched beyond dp apart)
  double particle_size = 0;  ///< >= 0 added to each extent, e.g. dp
  double bond_radius = 0;    ///< > 0, the fragments' bond radius, e.g. 1.5 dp
};

struct SlabNeck {
  NeckProfile profile;  ///< between the driven zones
  Fragments fragments;  ///< of the whole slab
  bool broken = false;  ///< ends_separated(fragments, left_end, right_end)
};

/// The neck of a slab pulled along x between its driven end zones: the profile over [max_x(left_end) + w/2,
/// min_x(right_end) - w/2] at the current positions (w = bin_width), so the range follows the moving ends and holds
/// no driven particle, and at t = 0 on the grid of make_plastic_slab every free column sits at a bin centre; plus the
/// fragments and the break flag. Throws std::invalid_argument for bad options, empty or out-of-range end lists, or
/// ends less than w apart (no range left).
SlabNeck slab_neck(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, const std::vector<int>& left_end,
                   const std::vector<int>& right_end, const SlabNeckOptions& options);

}  // namespace sphstab
