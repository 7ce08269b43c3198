#include "sphstab/problems/turek_hron_csm3.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace sphstab {

double TurekHronCsm3::attachment_x(double y) {
  const double dy = y - cylinder_y;
  return cylinder_x + std::sqrt(std::max(0.0, radius * radius - dy * dy));
}

TurekHronBeam turek_hron_beam(const TurekHronBeamOptions& options) {
  using C = TurekHronCsm3;
  if (options.across < 2)
    throw std::invalid_argument("turek_hron_beam: across must be >= 2 particles (got " +
                                std::to_string(options.across) + ")");
  if (options.clamp_layers < 1)
    throw std::invalid_argument("turek_hron_beam: clamp_layers must be >= 1 (got " +
                                std::to_string(options.clamp_layers) + ")");
  TurekHronBeam beam;
  const double dx = C::thickness / options.across;
  beam.dx = dx;
  struct Point {
    double x, y;
    int depth;
  };
  std::vector<Point> free, clamp;
  const int columns = static_cast<int>(std::ceil((C::tip_x - C::cylinder_x) / dx)) + options.clamp_layers + 1;
  for (int j = 0; j < options.across; ++j) {
    const double y = C::bottom_y + (j + 0.5) * dx;
    const double xc = C::attachment_x(y);
    const int edge = std::min(j, options.across - 1 - j);
    for (int i = 0; i < columns; ++i) {
      const double x = C::tip_x - (i + 0.5) * dx;
      const double dxc = x - C::cylinder_x, dyc = y - C::cylinder_y;
      if (dxc * dxc + dyc * dyc >= C::radius * C::radius)
        free.push_back({x, y, std::min(edge, i)});
      else if (xc - x <= options.clamp_layers * dx * (1 + 1e-12))
        clamp.push_back({x, y, edge});
    }
  }
  const int n = static_cast<int>(free.size() + clamp.size());
  ParticleSet<2>& p = beam.particles;
  p.x.resize(n, 2);
  p.volume = Eigen::VectorXd::Constant(n, dx * dx);
  p.role.assign(n, Role::Fixed);
  p.depth.assign(n, 0);
  p.spacing = dx;
  int k = 0;
  for (const Point& q : free) {
    p.x(k, 0) = q.x;
    p.x(k, 1) = q.y;
    p.role[k] = Role::Free;
    p.depth[k++] = q.depth;
  }
  for (const Point& q : clamp) {
    p.x(k, 0) = q.x;
    p.x(k, 1) = q.y;
    p.depth[k++] = q.depth;
  }
  beam.free_count = static_cast<int>(free.size());
  beam.clamp_count = static_cast<int>(clamp.size());
  // tip columns: the free particles of columns 0 and 1 nearest y = 0.2
  for (int col = 0; col < 2; ++col) {
    const double x = C::tip_x - (col + 0.5) * dx;
    double best = 1e300;
    for (int f = 0; f < beam.free_count; ++f)
      if (std::abs(p.x(f, 0) - x) < 1e-9 * dx) best = std::min(best, std::abs(p.x(f, 1) - C::cylinder_y));
    for (int f = 0; f < beam.free_count; ++f)
      if (std::abs(p.x(f, 0) - x) < 1e-9 * dx && std::abs(p.x(f, 1) - C::cylinder_y) < best + 1e-9 * dx)
        beam.tip[col].push_back(f);
  }
  p.validate("turek_hron_beam");
  return beam;
}

}  // namespace sphstab
