#include "sphstab/problems/colliding_rings.hpp"

#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/length_scale.hpp"
#include "sphstab/core/memory_budget.hpp"

namespace sphstab {

namespace {

void validate(const CollidingRingsOptions& o) {
  const std::string who = "make_colliding_rings: ";
  if (!std::isfinite(o.inner_radius) || !std::isfinite(o.outer_radius) || !std::isfinite(o.spacing) ||
      !std::isfinite(o.gap) || !std::isfinite(o.speed))
    throw std::invalid_argument(who + "options must be finite (got r_in " + format_number(o.inner_radius) + ", r_out " +
                                format_number(o.outer_radius) + ", dp " + format_number(o.spacing) + ", gap " +
                                format_number(o.gap) + ", speed " + format_number(o.speed) + ")");
  if (o.inner_radius < 0)
    throw std::invalid_argument(who + "inner radius " + format_number(o.inner_radius) + " must be >= 0");
  if (!(o.outer_radius > o.inner_radius))
    throw std::invalid_argument(who + "outer radius " + format_number(o.outer_radius) +
                                " must exceed the inner radius " + format_number(o.inner_radius));
  if (!(o.spacing > 0)) throw std::invalid_argument(who + "spacing " + format_number(o.spacing) + " must be > 0");
  check_length(o.spacing, "make_colliding_rings: spacing");
  check_length(o.outer_radius, "make_colliding_rings: outer radius");
  if ((o.outer_radius - o.inner_radius) / o.spacing < 2 - 1e-9)
    throw std::invalid_argument(who + "ring width r_out - r_in = " + format_number(o.outer_radius - o.inner_radius) +
                                " is less than 2 spacings (dp = " + format_number(o.spacing) +
                                "): use a smaller spacing");
  if (o.gap < 0) throw std::invalid_argument(who + "gap " + format_number(o.gap) + " must be >= 0");
}

}  // namespace

CollidingRings make_colliding_rings(const CollidingRingsOptions& o) {
  validate(o);
  const double dp = o.spacing;
  // Grid units: cell centres at u = i + 1/2, i in [-M, M); |u| <= M - 1/2 > R + 1/2, so the outer frame is empty.
  const double R_in = o.inner_radius / dp, R_out = o.outer_radius / dp;
  const long M = checked_floor_count(R_out + 2, kMaxIndexCount / 4, "make_colliding_rings: grid half-width");
  const long side = 2 * M, cells = checked_mul(side, side, "make_colliding_rings: grid cells");
  require_memory(static_cast<double>(cells) * (sizeof(int) + sizeof(char)) +
                     M_PI * (R_out * R_out - R_in * R_in) * 2 * (6 * sizeof(double) + 2 * sizeof(int)),
                 "make_colliding_rings: " + std::to_string(side) + " x " + std::to_string(side) + " grid");
  const double q_lo = R_in * R_in * (1 - 1e-9), q_hi = R_out * R_out * (1 + 1e-9);
  auto at = [side](long i, long j) { return i * side + j; };  // i: column (x), j: row (y), both in [0, side)
  auto u = [M](long i) { return static_cast<double>(i - M) + 0.5; };
  std::vector<char> inside(static_cast<size_t>(cells), 0);
  long n = 0;
  for (long i = 0; i < side; ++i)
    for (long j = 0; j < side; ++j) {
      const double q = u(i) * u(i) + u(j) * u(j);
      if (q >= q_lo && q <= q_hi) {
        inside[at(i, j)] = 1;
        ++n;
      }
    }
  const int per_ring = checked_index_count(n, "make_colliding_rings: particles per ring");
  const int total = checked_index_count(2 * n, "make_colliding_rings: particles");

  // Depth: multi-source breadth-first search from every empty cell over the 8 grid neighbours (Chebyshev steps).
  std::vector<int> dist(static_cast<size_t>(cells), -1);
  std::deque<std::pair<long, long>> queue;
  for (long i = 0; i < side; ++i)
    for (long j = 0; j < side; ++j)
      if (!inside[at(i, j)]) {
        dist[at(i, j)] = 0;
        queue.emplace_back(i, j);
      }
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    for (long di = -1; di <= 1; ++di)
      for (long dj = -1; dj <= 1; ++dj) {
        const long a = i + di, b = j + dj;
        if (a < 0 || b < 0 || a >= side || b >= side || dist[at(a, b)] >= 0) continue;
        dist[at(a, b)] = dist[at(i, j)] + 1;
        queue.emplace_back(a, b);
      }
  }

  CollidingRings rings;
  rings.options = o;
  rings.per_ring = per_ring;
  const double offset = o.outer_radius + 0.5 * o.gap;
  rings.centre = {Eigen::Vector2d(-offset, 0), Eigen::Vector2d(offset, 0)};
  rings.particles = ParticleSet<2>::free_grid(static_cast<int>(total), dp);
  ParticleSet<2>& set = rings.particles;
  rings.velocity.resize(2, total);
  rings.ring.resize(total);
  for (int r = 0; r < 2; ++r) {
    int p = r * per_ring;
    for (long i = 0; i < side; ++i)
      for (long j = 0; j < side; ++j) {
        if (!inside[at(i, j)]) continue;
        set.x(p, 0) = rings.centre[r].x() + u(i) * dp;
        set.x(p, 1) = rings.centre[r].y() + u(j) * dp;
        set.depth[p] = dist[at(i, j)] - 1;
        rings.velocity.col(p) = Eigen::Vector2d(r == 0 ? o.speed : -o.speed, 0);
        rings.ring[p] = r;
        ++p;
      }
  }
  set.validate("make_colliding_rings");
  return rings;
}

}  // namespace sphstab
