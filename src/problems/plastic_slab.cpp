#include "sphstab/problems/plastic_slab.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"

namespace sphstab {

namespace {

/// ceil(v) with a relative tolerance of 1e-9, so that a whole number computed with rounding error stays itself.
long cells_to_cover(double v, const std::string& what) {
  return checked_floor_count(std::ceil(v - 1e-9 * v), kMaxIndexCount, what);
}

}  // namespace

PlasticSlab make_plastic_slab(const PlasticSlabOptions& o) {
  const std::string who = "make_plastic_slab: ";
  if (!std::isfinite(o.length) || !std::isfinite(o.width) || !std::isfinite(o.spacing) || !std::isfinite(o.end_zone) ||
      !std::isfinite(o.acceleration))
    throw std::invalid_argument(who + "options must be finite (got L " + format_number(o.length) + ", W " +
                                format_number(o.width) + ", dp " + format_number(o.spacing) + ", end_zone " +
                                format_number(o.end_zone) + ", a " + format_number(o.acceleration) + ")");
  if (!(o.length > 0) || !(o.width > 0) || !(o.spacing > 0) || !(o.end_zone > 0))
    throw std::invalid_argument(who + "need L, W, dp, end_zone > 0 (got L " + format_number(o.length) + ", W " +
                                format_number(o.width) + ", dp " + format_number(o.spacing) + ", end_zone " +
                                format_number(o.end_zone) + ")");
  check_length(o.length, "make_plastic_slab: length");
  check_length(o.width, "make_plastic_slab: width");
  check_length(o.spacing, "make_plastic_slab: spacing");
  if (!(2 * o.end_zone < o.length))
    throw std::invalid_argument(who + "the two end zones (2 x " + format_number(o.end_zone) +
                                ") must be shorter than the slab (L = " + format_number(o.length) + ")");
  const double dp = o.spacing;
  const long nx = cells_to_cover(o.length / dp, "make_plastic_slab: columns");
  const long ny = cells_to_cover(o.width / dp, "make_plastic_slab: rows");
  if (ny < 2)
    throw std::invalid_argument(who + "W / dp = " + format_number(o.width / dp) +
                                " gives fewer than 2 rows: use a smaller spacing");
  const int n =
      checked_index_count(checked_mul(nx, ny, "make_plastic_slab: particles"), "make_plastic_slab: particles");
  require_memory(static_cast<double>(n) * (4 * sizeof(double) + 2 * sizeof(int)),
                 "make_plastic_slab: " + std::to_string(nx) + " x " + std::to_string(ny) + " particles");

  // Driven columns, counted from each end (the grid is symmetric about x = 0, so the counts are equal).
  auto column_x = [&](long c) { return (static_cast<double>(c) - 0.5 * static_cast<double>(nx - 1)) * dp; };
  const double tol = 1e-9 * dp, left_edge = -0.5 * o.length + o.end_zone, right_edge = 0.5 * o.length - o.end_zone;
  long left_columns = 0, right_columns = 0;
  for (long c = 0; c < nx; ++c) {
    if (column_x(c) <= left_edge + tol) ++left_columns;
    if (column_x(c) >= right_edge - tol) ++right_columns;
  }
  if (left_columns == 0 || right_columns == 0)
    throw std::invalid_argument(who + "end zone " + format_number(o.end_zone) + " holds no column of particles (dp = " +
                                format_number(dp) + "): use a wider zone or a smaller spacing");
  if (left_columns + right_columns >= nx)
    throw std::invalid_argument(who + "the end zones (" + format_number(o.end_zone) +
                                " each) leave no free column of " + std::to_string(nx) +
                                ": use a longer slab or a smaller spacing");

  PlasticSlab slab;
  slab.options = o;
  slab.columns = static_cast<int>(nx);
  slab.rows = static_cast<int>(ny);
  slab.particles = ParticleSet<2>::free_grid(static_cast<int>(n), dp);
  ParticleSet<2>& set = slab.particles;
  int p = 0;
  for (long c = 0; c < nx; ++c)
    for (long r = 0; r < ny; ++r, ++p) {
      set.x(p, 0) = column_x(c);
      set.x(p, 1) = (static_cast<double>(r) - 0.5 * static_cast<double>(ny - 1)) * dp;
      set.depth[p] = static_cast<int>(std::min({c, nx - 1 - c, r, ny - 1 - r}));
      if (c < left_columns) slab.left_end.push_back(p);
      if (c >= nx - right_columns) slab.right_end.push_back(p);
    }
  slab.driven = slab.left_end;
  slab.driven.insert(slab.driven.end(), slab.right_end.begin(), slab.right_end.end());
  slab.driven_acceleration.resize(2, static_cast<Eigen::Index>(slab.driven.size()));
  for (std::size_t k = 0; k < slab.driven.size(); ++k)
    slab.driven_acceleration.col(static_cast<Eigen::Index>(k)) =
        Eigen::Vector2d(k < slab.left_end.size() ? -o.acceleration : o.acceleration, 0);
  set.validate("make_plastic_slab");
  return slab;
}

double slab_end_displacement(double time, double acceleration) {
  if (!std::isfinite(time) || !std::isfinite(acceleration))
    throw std::invalid_argument("slab_end_displacement: t and a must be finite (got t " + format_number(time) + ", a " +
                                format_number(acceleration) + ")");
  return 0.5 * acceleration * time * time;
}

}  // namespace sphstab
