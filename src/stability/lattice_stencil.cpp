#include "sphstab/stability/lattice_stencil.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

SquareLatticeDofs square_lattice(const Eigen::MatrixXd& x, const std::string& who) {
  const long nf = x.rows();
  if (x.cols() != 2)
    throw std::invalid_argument(who + ": free positions need 2 columns (got " + std::to_string(x.cols()) +
                                "): a 2D square lattice is required");
  const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(nf))));
  if (static_cast<long>(n) * n != nf)
    throw std::invalid_argument(who + ": " + std::to_string(nf) +
                                " free particles are not an n x n square lattice (not a square number)");
  if (n < 2)
    throw std::invalid_argument(who + ": a square lattice needs n >= 2 free particles per side (got " +
                                std::to_string(n) + ")");
  SquareLatticeDofs s;
  s.n = n;
  s.origin = x.row(0).transpose();
  s.dx = x(1, 0) - x(0, 0);
  if (!(s.dx > 0) || !std::isfinite(s.dx))
    throw std::invalid_argument(who + ": free particles 0 and 1 are not x-neighbours of a square lattice (dx = " +
                                format_number(s.dx, 6) + ")");
  const double tol = 1e-9 * s.dx;
  for (long f = 0; f < nf; ++f) {
    const long i = f % n, j = f / n;
    const double ex = s.origin.x() + s.dx * i, ey = s.origin.y() + s.dx * j;
    if (std::abs(x(f, 0) - ex) > tol || std::abs(x(f, 1) - ey) > tol)
      throw std::invalid_argument(who + ": free particle " + std::to_string(f) + " at (" + format_number(x(f, 0), 6) +
                                  ", " + format_number(x(f, 1), 6) + ") is not at site (i, j) = (" + std::to_string(i) +
                                  ", " + std::to_string(j) + ") of an " + std::to_string(n) + " x " +
                                  std::to_string(n) + " square lattice in DOF order (f = i + n j, i along x, spacing " +
                                  format_number(s.dx, 6) + ")");
  }
  return s;
}

double LatticeStencil::scale() const {
  double m = 0;
  for (const auto* v : {&k, &l})
    for (const Eigen::Matrix2d& b : *v) m = std::max(m, b.cwiseAbs().maxCoeff());
  return m;
}

namespace {

/// y = K e (which = 0) or L e (which = 1) for the unit vector e at dof `dof`.
void probe_column(const MatrixFreeLinearisation& lin, double sgn, int which, int dof, Eigen::VectorXd& e,
                  Eigen::VectorXd& y) {
  e.setZero();
  e[dof] = 1.0;
  if (which == 0)
    lin.apply_A0(e, y);
  else
    lin.apply_combination(0.0, -sgn, e, y);
}

}  // namespace

LatticeStencil probe_lattice_stencil(const MatrixFreeLinearisation& lin, LoadDirection direction) {
  const std::string who = "probe_lattice_stencil";
  if (!lin.symmetric())
    throw std::invalid_argument(who +
                                ": the linearisation is not symmetric (needs equal volumes, complete "
                                "neighbourhoods, and the conservative form or isotropic pre-strain)");
  const SquareLatticeDofs g = square_lattice(lin.free_positions(), who);
  const int n = g.n, pc = n / 2, fc = pc + n * pc;
  const double sgn = load_sign(direction);
  Eigen::VectorXd e(lin.dofs()), y[2][2];
  int radius = 0;
  bool touches_edge = false;
  double ymax = 0;
  for (int which = 0; which < 2; ++which)
    for (int c = 0; c < 2; ++c) {
      y[which][c].resize(lin.dofs());
      probe_column(lin, sgn, which, 2 * fc + c, e, y[which][c]);
      ymax = std::max(ymax, y[which][c].cwiseAbs().maxCoeff());
    }
  for (int which = 0; which < 2; ++which)
    for (int c = 0; c < 2; ++c)
      for (int q = 0; q < lin.free_count(); ++q) {
        if (y[which][c][2 * q] == 0.0 && y[which][c][2 * q + 1] == 0.0) continue;
        const int i = q % n, j = q / n;
        radius = std::max({radius, std::abs(i - pc), std::abs(j - pc)});
        if (i == 0 || j == 0 || i == n - 1 || j == n - 1) touches_edge = true;
      }
  if (touches_edge)
    throw std::invalid_argument(who + ": the " + std::to_string(n) + " x " + std::to_string(n) +
                                " lattice is too small: the probed column of the central particle reaches the free "
                                "edge (probe a larger lattice of the same kernel, h, material and form)");
  LatticeStencil s;
  s.n = n;
  s.radius = radius;
  const int w = s.width();
  s.k.assign(w * w, Eigen::Matrix2d::Zero());
  s.l.assign(w * w, Eigen::Matrix2d::Zero());
  // Column (p, c) holds, at particle p - d, the row of p - d: y_(p - d, e) = S(d)_{e c}.
  for (int dj = -radius; dj <= radius; ++dj)
    for (int di = -radius; di <= radius; ++di) {
      const int q = (pc - di) + n * (pc - dj);
      Eigen::Matrix2d& bk = s.k[(dj + radius) * w + di + radius];
      Eigen::Matrix2d& bl = s.l[(dj + radius) * w + di + radius];
      for (int c = 0; c < 2; ++c)
        for (int r = 0; r < 2; ++r) {
          bk(r, c) = y[0][c][2 * q + r];
          bl(r, c) = y[1][c][2 * q + r];
        }
    }
  return s;
}

double lattice_stencil_deviation(const MatrixFreeLinearisation& lin, LoadDirection direction, const LatticeStencil& st,
                                 const std::vector<int>& free_particles) {
  const std::string who = "lattice_stencil_deviation";
  const SquareLatticeDofs g = square_lattice(lin.free_positions(), who);
  if (g.n != st.n)
    throw std::invalid_argument(who + ": the stencil was probed on n = " + std::to_string(st.n) +
                                ", the linearisation has n = " + std::to_string(g.n));
  const int n = g.n, r = st.radius;
  const double sgn = load_sign(direction), scale = st.scale();
  Eigen::VectorXd e(lin.dofs()), y(lin.dofs());
  double worst = 0;
  for (int p : free_particles) {
    if (p < 0 || p >= lin.free_count())
      throw std::invalid_argument(who + ": free particle " + std::to_string(p) + " outside [0, " +
                                  std::to_string(lin.free_count()) + ")");
    const int ip = p % n, jp = p / n;
    for (int which = 0; which < 2; ++which)
      for (int c = 0; c < 2; ++c) {
        // Row (p, c) of A is column (p, c) of A (A symmetric is not assumed: compare A^T e = rows through the
        // column of the translation-invariant operator, y_(q, e) = S(p - q)_{e c}).
        probe_column(lin, sgn, which, 2 * p + c, e, y);
        for (int q = 0; q < lin.free_count(); ++q) {
          const int di = ip - q % n, dj = jp - q / n;
          Eigen::Vector2d pred = Eigen::Vector2d::Zero();
          if (std::abs(di) <= r && std::abs(dj) <= r) pred = (which == 0 ? st.k_at(di, dj) : st.l_at(di, dj)).col(c);
          for (int d = 0; d < 2; ++d) worst = std::max(worst, std::abs(y[2 * q + d] - pred[d]));
        }
      }
  }
  return scale > 0 ? worst / scale : worst;
}

}  // namespace sphstab
