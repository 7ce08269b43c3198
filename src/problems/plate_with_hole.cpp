#include "sphstab/problems/plate_with_hole.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab {

PlateWithHole make_plate_with_hole(const PlateWithHoleOptions& o) {
  const std::string who = "make_plate_with_hole: ";
  if (!(o.radius > 0) || !std::isfinite(o.radius))
    throw std::invalid_argument(who + "hole radius a must be finite and > 0");
  if (!(o.width > o.radius) || !std::isfinite(o.width)) throw std::invalid_argument(who + "width W must exceed a");
  if (!(o.spacing > 0) || !std::isfinite(o.spacing)) throw std::invalid_argument(who + "spacing dx must be > 0");
  if (!(o.ghost_depth >= 0) || !std::isfinite(o.ghost_depth))
    throw std::invalid_argument(who + "ghost depth must be finite and >= 0");
  const double cells = o.width / o.spacing;
  const long n = std::lround(cells);
  if (std::abs(cells - static_cast<double>(n)) > 1e-9 * cells || n < 1)
    throw std::invalid_argument(who + "W / dx must be a whole number");
  if (n > 20000) throw std::invalid_argument(who + "W / dx above 20000: too many particles");
  PlateWithHole p;
  p.options = o;
  const double dx = o.spacing;
  std::vector<Eigen::Vector2d> real;
  for (long j = 0; j < n; ++j)
    for (long i = 0; i < n; ++i) {
      const Eigen::Vector2d x((i + 0.5) * dx, (j + 0.5) * dx);
      if (x.norm() < o.radius) {
        ++p.removed;
        continue;
      }
      if (i == n - 1) {
        p.edge.push_back(static_cast<int>(real.size()));
      }
      real.push_back(x);
    }
  if (real.empty()) throw std::invalid_argument(who + "the hole leaves no particle");
  p.real_count = static_cast<int>(real.size());
  std::vector<Eigen::Vector2d> all = real;
  for (int sx : {1, -1})
    for (int sy : {1, -1}) {
      if (sx == 1 && sy == 1) continue;
      for (int k = 0; k < p.real_count; ++k) {
        if (sx < 0 && real[k].x() >= o.ghost_depth) continue;
        if (sy < 0 && real[k].y() >= o.ghost_depth) continue;
        all.emplace_back(sx * real[k].x(), sy * real[k].y());
        p.image_of.push_back(k);
        p.sign.emplace_back(sx, sy);
      }
    }
  const int N = static_cast<int>(all.size());
  p.particles.x.resize(N, 2);
  for (int k = 0; k < N; ++k) p.particles.x.row(k) = all[k].transpose();
  p.particles.volume = Eigen::VectorXd::Constant(N, dx * dx);
  p.particles.role.assign(N, Role::Free);
  p.particles.spacing = dx;
  p.edge_length = Eigen::VectorXd::Constant(static_cast<int>(p.edge.size()), dx);
  return p;
}

SparseMatrix<> mirror_map(const PlateWithHole& p) {
  const int N = p.particles.size();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(2 * N);
  for (int k = 0; k < p.real_count; ++k)
    for (int d = 0; d < 2; ++d) t.emplace_back(2 * k + d, 2 * k + d, 1.0);
  for (std::size_t g = 0; g < p.image_of.size(); ++g) {
    const int row = 2 * (p.real_count + static_cast<int>(g));
    for (int d = 0; d < 2; ++d) t.emplace_back(row + d, 2 * p.image_of[g] + d, p.sign[g][d]);
  }
  SparseMatrix<> T(2 * N, 2 * p.real_count);
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

Eigen::VectorXd lumped_traction(const PlateWithHole& p, double traction) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * p.real_count);
  for (std::size_t e = 0; e < p.edge.size(); ++e) f[2 * p.edge[e]] = traction * p.edge_length[static_cast<int>(e)];
  return f;
}

Eigen::VectorXd consistent_traction(const PlateWithHole& p, const Discretisation<2>& disc, double traction) {
  const std::string who = "consistent_traction: ";
  if (disc.size() != p.particles.size() || !disc.particles.x.isApprox(p.particles.x, 0.0))
    throw std::invalid_argument(who + "the discretisation is not built on this plate's particles");
  const double s = disc.kernel.support_radius(disc.h);
  const double W = p.options.width, a = p.options.radius;
  if (W - a < 2 * s)
    throw std::invalid_argument(who + "the hole's boundary band meets the loaded band: make W - a >= 2 support");
  const SparseMatrix<> Gx = gradient_matrix(disc.particles, disc.neighbours, disc.kernel, disc.h, 0);
  const Eigen::VectorXd g = Gx * Eigen::VectorXd::Ones(disc.size());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * p.real_count);
  for (int i = 0; i < p.real_count; ++i)
    if (p.particles.x(i, 0) > W - s) f[2 * i] = -2 * p.particles.volume[i] * traction * g[i];
  return f;
}

Eigen::Vector3d kirsch_polar_stress(double a, double r, double theta, double S) {
  if (!(a > 0)) throw std::invalid_argument("kirsch_polar_stress: hole radius a must be > 0");
  if (!(r >= a)) throw std::invalid_argument("kirsch_polar_stress: r must be >= a (outside the hole)");
  const double q = a * a / (r * r), c = std::cos(2 * theta), sn = std::sin(2 * theta);
  return {S / 2 * (1 - q) + S / 2 * (1 - 4 * q + 3 * q * q) * c, S / 2 * (1 + q) - S / 2 * (1 + 3 * q * q) * c,
          -S / 2 * (1 + 2 * q - 3 * q * q) * sn};
}

double heywood_gross_concentration(double a, double W) {
  if (!(a > 0) || !(W > a)) throw std::invalid_argument("heywood_gross_concentration: needs 0 < a < W");
  const double r = a / W;
  return (2 + std::pow(1 - r, 3)) / (1 - r);
}

}  // namespace sphstab
