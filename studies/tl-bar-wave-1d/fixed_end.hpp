#pragma once
// The fixed (right) end of Ismail's validation bar (common/ismail_bar.hpp) [Ismail2009, §2.8.3, (2.42), (2.46)-(2.47);
// operators/ismail_boundary.hpp]: how the right ghost layers get their displacement from the free particles (clamped,
// odd mirror, eta method, modified SPH matrix), and the ghost sets and operators of one resolution (built once per
// resolution): the fixed particles, the right ghosts, the mirror partner of each, the ghosts within the wall's support
// (the constrained set of the eta and modified closures), Ismail's SPH matrix W, the eta and modified-matrix operators.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/ismail_bar.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/operators/ismail_boundary.hpp"
#include "sphstab/operators/operators.hpp"

namespace bar_wave {

using namespace sphstab;
using namespace sphstab::study::ismail_bar;

/// The fixed (right) end: how the right ghost layers get their displacement from the free particles.
enum class FixedEnd {
  Clamped,   ///< u = 0 on every right ghost
  Mirror,    ///< odd mirror about the wall x = L: u(L + s) = -u(L - s)
  Eta,       ///< Ismail's eta method (2.42) at the wall point x = L, one-sided on the ghosts within its support
  Modified,  ///< Ismail's modified SPH matrix (2.46)-(2.47): <u> = 0 on every right ghost row (exact form)
};
constexpr NamedValue<FixedEnd> kFixedEndNames[] = {{FixedEnd::Clamped, "clamped"},
                                                   {FixedEnd::Mirror, "mirror"},
                                                   {FixedEnd::Eta, "eta"},
                                                   {FixedEnd::Modified, "modified"}};
inline std::string fixed_end_name(FixedEnd e) { return name_of(e, kFixedEndNames); }

/// The right end's ghost sets of one resolution.
struct RightGhosts {
  std::vector<int> fixed_index;   ///< particle index of each fixed particle (the order of Bar::x_fixed)
  std::vector<int> right_ghosts;  ///< the fixed particles beyond L
  std::vector<int> mirror_free;   ///< per fixed particle: the free slot of its mirror partner about L, or -1
  std::vector<int> eta_targets;   ///< the right ghosts within the wall's support (the eta / modified constrained set)
  std::vector<int> by_distance;   ///< the right ghosts, nearest to the wall first
};

inline RightGhosts right_ghosts(const Bar& bar) {
  const auto& disc = bar.disc;
  const std::vector<double>& x_fixed = bar.x_fixed;
  RightGhosts g;
  g.mirror_free.assign(x_fixed.size(), -1);
  for (int i = 0; i < disc->size(); ++i)
    if (disc->free_slot[i] < 0) g.fixed_index.push_back(i);
  for (std::size_t k = 0; k < x_fixed.size(); ++k) {
    if (x_fixed[k] < kLength) continue;
    g.right_ghosts.push_back(g.fixed_index[k]);
    if (x_fixed[k] - kLength < bar.kernel.support_radius(bar.h)) g.eta_targets.push_back(g.fixed_index[k]);
    for (int f = 0; f < disc->free_count(); ++f)
      if (std::abs(disc->particles.x(disc->free[f], 0) - (2 * kLength - x_fixed[k])) < 1e-6 * bar.dx)
        g.mirror_free[k] = f;
  }
  g.by_distance = g.right_ghosts;
  std::sort(g.by_distance.begin(), g.by_distance.end(),
            [&](int a, int b) { return disc->particles.x(a, 0) < disc->particles.x(b, 0); });
  return g;
}

/// The right end of one resolution: its ghosts, the eta and modified-matrix operators (built once per resolution).
struct FixedEndOperators {
  RightGhosts ghosts;
  EtaBoundary1D eta;                 ///< Ismail (2.42) at the wall point x = L on the ghosts within its support
  SparseMatrix<> wmat;               ///< Ismail's SPH matrix W_ij = W(x_i - x_j) V_j
  ModifiedMatrixDirichlet modified;  ///< Ismail (2.46)-(2.47) on the ghosts within the wall's support
  explicit FixedEndOperators(const Bar& bar)
      : ghosts(right_ghosts(bar)),
        eta(bar.disc->particles, bar.kernel, bar.h, kLength, ghosts.eta_targets, BoundaryCondition::Dirichlet),
        wmat(kernel_matrix(bar.disc->particles, bar.disc->neighbours, bar.kernel, bar.h)),
        modified(wmat, ghosts.eta_targets) {}
};

}  // namespace bar_wave
