#include "sphstab/spectral/dominant_wavevector.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab {

namespace {

using Cd = std::complex<double>;

/// S(u) by direct summation, u in reciprocal coordinates.
double structure_factor(const Eigen::VectorXcd& mode, const Eigen::MatrixX2d& x, const Eigen::Vector2d& k) {
  Cd sx = 0, sy = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Cd phase = std::polar(1.0, -(k[0] * x(i, 0) + k[1] * x(i, 1)));
    sx += mode[2 * i] * phase;
    sy += mode[2 * i + 1] * phase;
  }
  return std::norm(sx) + std::norm(sy);
}

}  // namespace

WavevectorEstimate dominant_wavevector(const Eigen::VectorXd& mode, const Eigen::MatrixX2d& x,
                                       const BravaisLattice2D& lattice) {
  return dominant_wavevector(Eigen::VectorXcd(mode.cast<Cd>()), x, lattice);
}

WavevectorEstimate dominant_wavevector(const Eigen::VectorXcd& mode, const Eigen::MatrixX2d& x,
                                       const BravaisLattice2D& lattice) {
  const Eigen::Index n = x.rows();
  if (n == 0 || mode.size() != 2 * n)
    throw std::invalid_argument("dominant_wavevector: mode must have 2 x " + std::to_string(n) +
                                " entries and at least one particle (got " + std::to_string(mode.size()) + ")");
  WavevectorEstimate out;
  const double norm2 = mode.squaredNorm();
  if (!(norm2 > 0) || !std::isfinite(norm2)) return out;
  const Eigen::Matrix2d b = lattice.reciprocal();
  Eigen::Matrix2d a;
  a.col(0) = lattice.a1;
  a.col(1) = lattice.a2;
  const Eigen::Matrix2d ainv = a.inverse();

  // Integer lattice coordinates relative to the first particle, if the positions are lattice sites.
  std::vector<int> p(n), q(n);
  bool on_lattice = true;
  int pmin = 0, pmax = 0, qmin = 0, qmax = 0;
  for (Eigen::Index i = 0; i < n && on_lattice; ++i) {
    const Eigen::Vector2d c = ainv * (x.row(i) - x.row(0)).transpose();
    const double rp = std::round(c[0]), rq = std::round(c[1]);
    if (std::abs(c[0] - rp) > 1e-6 || std::abs(c[1] - rq) > 1e-6) on_lattice = false;
    p[i] = static_cast<int>(rp);
    q[i] = static_cast<int>(rq);
    pmin = std::min(pmin, p[i]), pmax = std::max(pmax, p[i]);
    qmin = std::min(qmin, q[i]), qmax = std::max(qmax, q[i]);
  }

  double best = -1;
  Eigen::Vector2d u_best(0, 0);
  // Refines the coarse maximiser on ever finer 9 x 9 stencils.
  auto refine = [&](int g) {
    double step = 1.0 / g;
    for (int level = 0; level < 9; ++level) {
      step /= 4;
      const Eigen::Vector2d centre = u_best;
      for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j) {
          const Eigen::Vector2d u = centre + step * Eigen::Vector2d(i, j);
          const double s = structure_factor(mode, x, b * u);
          if (s > best) best = s, u_best = u;
        }
    }
  };
  if (on_lattice) {
    const int extent = std::max(pmax - pmin, qmax - qmin) + 1;
    const int g = std::min(1024, std::max(16, 4 * extent));
    const int rows = qmax - qmin + 1;
    // F[c][q][j] = sum_{i in row q} u_i^c exp(-2 pi i (j/g) p_i)
    std::vector<Cd> twiddle(g);
    for (int j = 0; j < g; ++j) twiddle[j] = std::polar(1.0, -2 * M_PI * j / g);
    std::vector<Cd> f(2 * static_cast<size_t>(rows) * g, Cd(0));
    for (Eigen::Index i = 0; i < n; ++i) {
      const int pm = ((p[i] % g) + g) % g;
      Cd* fx = &f[(0 * static_cast<size_t>(rows) + (q[i] - qmin)) * g];
      Cd* fy = &f[(1 * static_cast<size_t>(rows) + (q[i] - qmin)) * g];
      for (int j = 0; j < g; ++j) {
        const Cd t = twiddle[(static_cast<long>(j) * pm) % g];
        fx[j] += mode[2 * i] * t;
        fy[j] += mode[2 * i + 1] * t;
      }
    }
    for (int j2 = 0; j2 < g; ++j2)
      for (int j1 = 0; j1 < g; ++j1) {
        Cd sx = 0, sy = 0;
        for (int r = 0; r < rows; ++r) {
          const int qm = (((r + qmin) % g) + g) % g;
          const Cd t = twiddle[(static_cast<long>(j2) * qm) % g];
          sx += f[(0 * static_cast<size_t>(rows) + r) * g + j1] * t;
          sy += f[(1 * static_cast<size_t>(rows) + r) * g + j1] * t;
        }
        const double s = std::norm(sx) + std::norm(sy);
        if (s > best) {
          best = s;
          u_best = {double(j1) / g, double(j2) / g};
        }
      }
    refine(g);
  } else {
    const int g = 64;
    for (int j2 = 0; j2 < g; ++j2)
      for (int j1 = 0; j1 < g; ++j1) {
        const Eigen::Vector2d u(double(j1) / g, double(j2) / g);
        const double s = structure_factor(mode, x, b * u);
        if (s > best) best = s, u_best = u;
      }
    refine(g);
  }
  const Eigen::Vector2d k = lattice.fold(b * u_best) * lattice.dx / M_PI;
  out.kx_over_pi = k[0];
  out.ky_over_pi = k[1];
  out.peak_fraction = best / (double(n) * norm2);
  return out;
}

}  // namespace sphstab
