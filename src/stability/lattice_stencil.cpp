#include "sphstab/stability/lattice_stencil.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

template <int Dim>
const char* lattice_word() {
  return Dim == 2 ? "square" : "cubic";
}

/// "n x n" or "n x n x n".
template <int Dim>
std::string lattice_size(int n) {
  std::string s = std::to_string(n);
  for (int a = 1; a < Dim; ++a) s += " x " + std::to_string(n);
  return s;
}

/// "(i, j)" or "(i, j, k)" for a site, or the names of its indices.
template <int Dim>
std::string site_text(const std::array<int, Dim>& s) {
  std::string t = "(" + std::to_string(s[0]);
  for (int a = 1; a < Dim; ++a) t += ", " + std::to_string(s[a]);
  return t + ")";
}

}  // namespace

template <int Dim>
long LatticeDofs<Dim>::count() const {
  long c = 1;
  for (int a = 0; a < Dim; ++a) c *= n;
  return c;
}

template <int Dim>
std::array<int, Dim> LatticeDofs<Dim>::site(long f) const {
  std::array<int, Dim> s;
  for (int a = 0; a < Dim; ++a, f /= n) s[a] = static_cast<int>(f % n);
  return s;
}

template <int Dim>
long LatticeDofs<Dim>::flat(const std::array<int, Dim>& s) const {
  long f = 0;
  for (int a = Dim - 1; a >= 0; --a) f = f * n + s[a];
  return f;
}

template <int Dim>
LatticeDofs<Dim> lattice_dofs(const Eigen::MatrixXd& x, const std::string& who) {
  const long nf = x.rows();
  const std::string word = lattice_word<Dim>();
  if (x.cols() != Dim)
    throw std::invalid_argument(who + ": free positions need " + std::to_string(Dim) + " columns (got " +
                                std::to_string(x.cols()) + "): a " + std::to_string(Dim) + "D " + word +
                                " lattice is required");
  const int n = static_cast<int>(std::lround(std::pow(static_cast<double>(nf), 1.0 / Dim)));
  LatticeDofs<Dim> s;
  s.n = n;
  if (s.count() != nf)
    throw std::invalid_argument(who + ": " + std::to_string(nf) + " free particles are not an " +
                                (Dim == 2 ? "n x n" : "n x n x n") + " " + word + " lattice (not " +
                                (Dim == 2 ? "a square" : "a cube") + " number)");
  if (n < 2)
    throw std::invalid_argument(who + ": a " + word + " lattice needs n >= 2 free particles per side (got " +
                                std::to_string(n) + ")");
  s.origin = x.row(0).transpose();
  s.dx = x(1, 0) - x(0, 0);
  if (!(s.dx > 0) || !std::isfinite(s.dx))
    throw std::invalid_argument(who + ": free particles 0 and 1 are not x-neighbours of a " + word +
                                " lattice (dx = " + format_number(s.dx, 6) + ")");
  const double tol = 1e-9 * s.dx;
  for (long f = 0; f < nf; ++f) {
    const std::array<int, Dim> site = s.site(f);
    bool off = false;
    for (int a = 0; a < Dim; ++a) off = off || std::abs(x(f, a) - (s.origin[a] + s.dx * site[a])) > tol;
    if (!off) continue;
    std::string at = "(" + format_number(x(f, 0), 6);
    for (int a = 1; a < Dim; ++a) at += ", " + format_number(x(f, a), 6);
    throw std::invalid_argument(who + ": free particle " + std::to_string(f) + " at " + at + ") is not at site " +
                                (Dim == 2 ? "(i, j) = " : "(i, j, k) = ") + site_text<Dim>(site) + " of an " +
                                lattice_size<Dim>(n) + " " + word + " lattice in DOF order (f = i + n j" +
                                (Dim == 2 ? "" : " + n^2 k") + ", i along x, spacing " + format_number(s.dx, 6) + ")");
  }
  return s;
}

template <int Dim>
long LatticeStencil<Dim>::blocks() const {
  long c = 1;
  for (int a = 0; a < Dim; ++a) c *= width();
  return c;
}

template <int Dim>
long LatticeStencil<Dim>::index(const std::array<int, Dim>& d) const {
  long t = 0;
  for (int a = Dim - 1; a >= 0; --a) t = t * width() + d[a] + radius;
  return t;
}

template <int Dim>
double LatticeStencil<Dim>::scale() const {
  double m = 0;
  for (const auto* v : {&k, &l})
    for (const Block& b : *v) m = std::max(m, b.cwiseAbs().maxCoeff());
  return m;
}

namespace {

/// y = K e (which = 0) or L e (which = 1) for the unit vector e at dof `dof`.
template <int Dim>
void probe_column(const MatrixFreeLinearisation<Dim>& lin, double sgn, int which, long dof, Eigen::VectorXd& e,
                  Eigen::VectorXd& y) {
  e.setZero();
  e[dof] = 1.0;
  if (which == 0)
    lin.apply_A0(e, y);
  else
    lin.apply_combination(0.0, -sgn, e, y);
}

/// Every offset d in [-r, r]^Dim, x fastest (the stencil's index order).
template <int Dim, class F>
void for_each_offset(int r, F&& f) {
  std::array<int, Dim> d;
  d.fill(-r);
  while (true) {
    f(d);
    int a = 0;
    while (a < Dim && d[a] == r) d[a++] = -r;
    if (a == Dim) return;
    ++d[a];
  }
}

}  // namespace

template <int Dim>
LatticeStencil<Dim> probe_lattice_stencil(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction) {
  const std::string who = "probe_lattice_stencil";
  if (!lin.symmetric())
    throw std::invalid_argument(who +
                                ": the linearisation is not symmetric (needs equal volumes, complete "
                                "neighbourhoods, and the conservative form or isotropic pre-strain)");
  const LatticeDofs<Dim> g = lattice_dofs<Dim>(lin.free_positions(), who);
  const int n = g.n, pc = n / 2;
  std::array<int, Dim> centre;
  centre.fill(pc);
  const long fc = g.flat(centre);
  const double sgn = load_sign(direction);
  Eigen::VectorXd e(lin.dofs()), y[2][Dim];
  int radius = 0;
  bool touches_edge = false;
  for (int which = 0; which < 2; ++which)
    for (int c = 0; c < Dim; ++c) {
      y[which][c].resize(lin.dofs());
      probe_column(lin, sgn, which, Dim * fc + c, e, y[which][c]);
    }
  for (int which = 0; which < 2; ++which)
    for (int c = 0; c < Dim; ++c)
      for (long q = 0; q < lin.free_count(); ++q) {
        bool zero = true;
        for (int r = 0; r < Dim; ++r) zero = zero && y[which][c][Dim * q + r] == 0.0;
        if (zero) continue;
        const std::array<int, Dim> s = g.site(q);
        for (int a = 0; a < Dim; ++a) {
          radius = std::max(radius, std::abs(s[a] - pc));
          if (s[a] == 0 || s[a] == n - 1) touches_edge = true;
        }
      }
  if (touches_edge)
    throw std::invalid_argument(who + ": the " + lattice_size<Dim>(n) +
                                " lattice is too small: the probed column of the central particle reaches the free "
                                "edge (probe a larger lattice of the same kernel, h, material and form)");
  LatticeStencil<Dim> s;
  s.n = n;
  s.radius = radius;
  s.k.assign(s.blocks(), LatticeStencil<Dim>::Block::Zero());
  s.l.assign(s.blocks(), LatticeStencil<Dim>::Block::Zero());
  // Column (p, c) holds, at particle p - d, the row of p - d: y_(p - d, e) = S(d)_{e c}.
  for_each_offset<Dim>(radius, [&](const std::array<int, Dim>& d) {
    std::array<int, Dim> site;
    for (int a = 0; a < Dim; ++a) site[a] = pc - d[a];
    const long q = g.flat(site), t = s.index(d);
    for (int c = 0; c < Dim; ++c)
      for (int r = 0; r < Dim; ++r) {
        s.k[t](r, c) = y[0][c][Dim * q + r];
        s.l[t](r, c) = y[1][c][Dim * q + r];
      }
  });
  return s;
}

template <int Dim>
double lattice_stencil_deviation(const MatrixFreeLinearisation<Dim>& lin, LoadDirection direction,
                                 const LatticeStencil<Dim>& st, const std::vector<int>& free_particles) {
  const std::string who = "lattice_stencil_deviation";
  const LatticeDofs<Dim> g = lattice_dofs<Dim>(lin.free_positions(), who);
  if (g.n != st.n)
    throw std::invalid_argument(who + ": the stencil was probed on n = " + std::to_string(st.n) +
                                ", the linearisation has n = " + std::to_string(g.n));
  const int r = st.radius;
  const double sgn = load_sign(direction), scale = st.scale();
  Eigen::VectorXd e(lin.dofs()), y(lin.dofs());
  double worst = 0;
  for (int p : free_particles) {
    if (p < 0 || p >= lin.free_count())
      throw std::invalid_argument(who + ": free particle " + std::to_string(p) + " outside [0, " +
                                  std::to_string(lin.free_count()) + ")");
    const std::array<int, Dim> sp = g.site(p);
    for (int which = 0; which < 2; ++which)
      for (int c = 0; c < Dim; ++c) {
        // Row (p, c) of A is column (p, c) of A (A symmetric is not assumed: compare A^T e = rows through the
        // column of the translation-invariant operator, y_(q, e) = S(p - q)_{e c}).
        probe_column(lin, sgn, which, static_cast<long>(Dim) * p + c, e, y);
        for (long q = 0; q < lin.free_count(); ++q) {
          const std::array<int, Dim> sq = g.site(q);
          std::array<int, Dim> d;
          bool inside = true;
          for (int a = 0; a < Dim; ++a) {
            d[a] = sp[a] - sq[a];
            inside = inside && std::abs(d[a]) <= r;
          }
          Eigen::Matrix<double, Dim, 1> pred = Eigen::Matrix<double, Dim, 1>::Zero();
          if (inside) pred = (which == 0 ? st.k[st.index(d)] : st.l[st.index(d)]).col(c);
          for (int a = 0; a < Dim; ++a) worst = std::max(worst, std::abs(y[Dim * q + a] - pred[a]));
        }
      }
  }
  return scale > 0 ? worst / scale : worst;
}

#define SPHSTAB_INSTANTIATE(D)                                                                           \
  template struct LatticeDofs<D>;                                                                        \
  template LatticeDofs<D> lattice_dofs<D>(const Eigen::MatrixXd&, const std::string&);                   \
  template struct LatticeStencil<D>;                                                                     \
  template LatticeStencil<D> probe_lattice_stencil<D>(const MatrixFreeLinearisation<D>&, LoadDirection); \
  template double lattice_stencil_deviation<D>(const MatrixFreeLinearisation<D>&, LoadDirection,         \
                                               const LatticeStencil<D>&, const std::vector<int>&);
SPHSTAB_INSTANTIATE(2)
SPHSTAB_INSTANTIATE(3)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
