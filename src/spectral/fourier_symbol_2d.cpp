#include "sphstab/spectral/fourier_symbol_2d.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "sphstab/core/checked_arithmetic.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"

namespace sphstab {

namespace {

constexpr double kInf2D = std::numeric_limits<double>::infinity();

/// Positive real roots of c0 + c1 e + c2 e^2 (appended to `roots`).
void positive_roots(double c0, double c1, double c2, std::vector<double>& roots) {
  const double scale = std::max({std::abs(c0), std::abs(c1), std::abs(c2)});
  if (scale == 0) return;
  if (std::abs(c2) <= 1e-14 * scale) {
    if (std::abs(c1) > 1e-14 * scale) {
      const double r = -c0 / c1;
      if (r > 0 && std::isfinite(r)) roots.push_back(r);
    }
    return;
  }
  const double disc = c1 * c1 - 4 * c2 * c0;
  if (disc < 0) return;
  const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
  for (double r : {q / c2, q != 0 ? c0 / q : kInf2D})
    if (r > 0 && std::isfinite(r)) roots.push_back(r);
}

struct TwoByTwo {
  double tr, det, disc;
};
TwoByTwo invariants(const Eigen::Matrix2d& a) {
  const double d = a(0, 0) - a(1, 1);
  return {a(0, 0) + a(1, 1), a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0), d * d + 4 * a(0, 1) * a(1, 0)};
}
bool stable(const Eigen::Matrix2d& a) {
  const TwoByTwo v = invariants(a);
  return v.tr > 0 && v.det > 0 && v.disc >= 0;
}

}  // namespace

ElasticSymbol2D::ElasticSymbol2D(LatticeType type, const Kernel<2>& kernel, double h, double dx,
                                 const ElasticMaterial& material, MomentumForm form, PreStrainKind kind)
    : m_lattice(bravais_lattice_2d(type, dx)), m_material(material), m_form(form), m_kind(kind) {
  material.validate("ElasticSymbol2D");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("ElasticSymbol2D: h must be finite and > 0 (got " + format_number(h) + ")");
  m_s0 = PreStrain{kind, 1.0}.stress(material);
  const double support = kernel.support_radius(h), vol = m_lattice.cell_area();
  const int reach = static_cast<int>(checked_floor_count(std::ceil(2 * support / m_lattice.a2.y()), kMaxLatticeReach,
                                                         "ElasticSymbol2D: lattice rows in twice the support")) +
                    2;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j) {
      const Eigen::Vector2d r = i * m_lattice.a1 + j * m_lattice.a2;
      const double d = r.norm();
      if (d == 0 || !(d < support)) continue;  // strict, like find_neighbours
      const Eigen::Vector2d e = r / d;
      const double w1 = kernel.d1(d, h), w2 = kernel.d2(d, h);
      m_r.push_back(r);
      m_grad.push_back(-vol * w1 * e);
      Eigen::Matrix2d hm =
          vol * (w2 * e * e.transpose() + (w1 / d) * (Eigen::Matrix2d::Identity() - e * e.transpose()));
      m_hess.push_back(hm);
      m_gscale += vol * std::abs(w1);
      m_hscale += hm.cwiseAbs().maxCoeff();
    }
}

ElasticSymbol2D::Value ElasticSymbol2D::operator()(const Eigen::Vector2d& k) const {
  Value v;
  v.s.setZero();
  v.l.setZero();
  for (size_t m = 0; m < m_r.size(); ++m) {
    const double phase = k.dot(m_r[m]);
    v.s += std::sin(phase) * m_grad[m];
    v.l += (1 - std::cos(phase)) * m_hess[m];
  }
  const double inv_rho = 1.0 / m_material.density(), lam = m_material.lambda(), mu = m_material.mu();
  v.a0 = inv_rho * ((lam + mu) * v.s * v.s.transpose() + mu * v.s.squaredNorm() * Eigen::Matrix2d::Identity());
  if (m_form == MomentumForm::Conservative)
    v.a1 = -2 * inv_rho * (m_s0 * v.l + v.l * m_s0);
  else
    v.a1 = -(1 + momentum_form_alpha(m_form)) * inv_rho * (m_s0 * v.l);
  return v;
}

constexpr NamedValue<InstabilityMechanism> kMechanismNames[] = {{InstabilityMechanism::None, "none"},
                                                                {InstabilityMechanism::RealCrossing, "real-crossing"},
                                                                {InstabilityMechanism::ComplexPair, "complex-pair"},
                                                                {InstabilityMechanism::ZeroSymbol, "zero-symbol"},
                                                                {InstabilityMechanism::Neutral, "neutral"}};

std::string mechanism_name(InstabilityMechanism m) { return name_of(m, kMechanismNames); }

CriticalStrain2x2 critical_strain_2x2(const Eigen::Matrix2d& a0, const Eigen::Matrix2d& a1_in, LoadDirection sign,
                                      double zero_tol) {
  const double sgn = sign == LoadDirection::Tension ? 1.0 : -1.0;
  const Eigen::Matrix2d a1 = sgn * a1_in;  // search e' = sgn e > 0
  CriticalStrain2x2 out;
  out.e = sgn * kInf2D;
  if (a0.cwiseAbs().maxCoeff() <= zero_tol) {
    // A = e' a1: stable for small e' > 0 iff both eigenvalues of a1 are real and positive.
    const TwoByTwo v = invariants(a1);
    if (v.disc < 0) {
      out.e = 0;
      out.mechanism = InstabilityMechanism::ZeroSymbol;
      return out;
    }
    const double root = std::sqrt(v.disc);
    const double lo = 0.5 * (v.tr - root);
    if (lo < -zero_tol) {
      out.e = 0;
      out.mechanism = InstabilityMechanism::ZeroSymbol;
    } else if (lo <= zero_tol) {
      out.e = 0;
      out.mechanism = InstabilityMechanism::Neutral;
    }
    return out;
  }
  // Roots of trace, determinant and discriminant; stability is constant between consecutive roots.
  const double a = a0(0, 0), b = a0(0, 1), c = a0(1, 0), d = a0(1, 1);
  const double p = a1(0, 0), q = a1(0, 1), r = a1(1, 0), s = a1(1, 1);
  std::vector<double> roots;
  positive_roots(a + d, p + s, 0, roots);
  positive_roots(a * d - b * c, a * s + p * d - b * r - q * c, p * s - q * r, roots);
  positive_roots((a - d) * (a - d) + 4 * b * c, 2 * (a - d) * (p - s) + 4 * (b * r + q * c),
                 (p - s) * (p - s) + 4 * q * r, roots);
  std::sort(roots.begin(), roots.end());
  double left = 0;
  for (size_t i = 0; i <= roots.size(); ++i) {
    const double right = i < roots.size() ? roots[i] : kInf2D;
    if (right <= left) continue;
    const double mid = std::isinf(right) ? 2 * left + 1 : 0.5 * (left + right);
    const Eigen::Matrix2d m = a0 + mid * a1;
    if (!stable(m)) {
      out.e = sgn * left;
      const TwoByTwo v = invariants(m);
      out.mechanism = v.disc < 0 ? InstabilityMechanism::ComplexPair : InstabilityMechanism::RealCrossing;
      return out;
    }
    left = right;
  }
  return out;
}

namespace {

/// Per-k critical strain with the zone-boundary zeros handled exactly.
struct PointResult {
  CriticalStrain2x2 r;
  bool zone_zero = false;
};

bool is_zone_boundary_zero(const BravaisLattice2D& lat, const Eigen::Vector2d& k) {
  const Eigen::Vector2d u = 2 * (lat.reciprocal().inverse() * k);  // 2k in reciprocal coordinates
  return std::abs(u[0] - std::round(u[0])) < 1e-9 && std::abs(u[1] - std::round(u[1])) < 1e-9;
}

PointResult evaluate(const ElasticSymbol2D& sym, const Eigen::Vector2d& k, LoadDirection sign, bool zone_zero) {
  const ElasticSymbol2D::Value v = sym(k);
  PointResult p;
  p.zone_zero = zone_zero;
  if (zone_zero) {
    // s = 0 exactly (sin(k . r) = 0 for every lattice vector); the rounding residue is dropped.
    const double tol = 1e-12 * std::max(v.a1.cwiseAbs().maxCoeff(), 1e-300);
    p.r = critical_strain_2x2(Eigen::Matrix2d::Zero(), v.a1, sign, tol);
  } else {
    p.r = critical_strain_2x2(v.a0, v.a1, sign, 0);
  }
  return p;
}

}  // namespace

namespace {

/// +-inf (no instability found yet), or NaN with a reason when no lattice vector lies inside the support (the symbol
/// is 0 and stability is undefined).
SymbolCriticalStrain initial_result(const ElasticSymbol2D& sym, double sgn) {
  SymbolCriticalStrain out;
  out.e = sgn * kInf2D;
  if (sym.stencil_size() == 0) {
    out.e = SymbolCriticalStrain::nan;
    out.reason = "no lattice neighbour inside the kernel support (h too small)";
  }
  return out;
}

}  // namespace

SymbolCriticalStrain critical_strain_infinite_2d(const ElasticSymbol2D& sym, LoadDirection sign, int grid) {
  if (grid < 16)
    throw std::invalid_argument("critical_strain_infinite_2d: grid must be >= 16 (got " + std::to_string(grid) + ")");
  const BravaisLattice2D& lat = sym.lattice();
  const Eigen::Matrix2d b = lat.reciprocal();
  const double sgn = sign == LoadDirection::Tension ? 1.0 : -1.0;
  SymbolCriticalStrain out = initial_result(sym, sgn);
  if (std::isnan(out.e)) return out;
  auto report_k = [&](const Eigen::Vector2d& k) {
    const Eigen::Vector2d f = lat.fold(k) * lat.dx / M_PI;
    out.kx_over_pi = f[0];
    out.ky_over_pi = f[1];
  };
  // 1. The zone-boundary zeros, exactly (all of them listed in the reason; the first is reported as the k).
  std::string unstable_zeros;
  for (const Eigen::Vector2d& u : {Eigen::Vector2d(0.5, 0), Eigen::Vector2d(0, 0.5), Eigen::Vector2d(0.5, 0.5)}) {
    const Eigen::Vector2d k = b * u;
    const PointResult p = evaluate(sym, k, sign, true);
    if (p.r.mechanism == InstabilityMechanism::ZeroSymbol) {
      if (unstable_zeros.empty()) {
        out.e = 0;
        out.mechanism = InstabilityMechanism::ZeroSymbol;
        report_k(k);
      }
      const Eigen::Vector2d f = lat.fold(k) * lat.dx / M_PI;
      unstable_zeros += " (" + format_number(f[0]) + " " + format_number(f[1]) + ")";
    }
    if (p.r.mechanism == InstabilityMechanism::Neutral) ++out.neutral_points;
  }
  if (!unstable_zeros.empty()) {
    out.reason = "zone-boundary zero: A0^ = 0 and the initial-stress symbol destabilises at k dx/pi =" + unstable_zeros;
    return out;
  }
  // 2. Grid over the reciprocal cell (zone-boundary zeros and k = 0 excluded), then patch refinement.
  auto value = [&](const Eigen::Vector2d& u, InstabilityMechanism* mech) {
    const Eigen::Vector2d w = u - u.array().floor().matrix();
    const Eigen::Vector2d frac2 = 2 * w;
    if ((w.array().abs() < 1e-13).all() ||
        ((frac2.array() - frac2.array().round()).abs() < 1e-12).all())  // k = 0 or a zone-boundary zero
      return kInf2D;
    const PointResult p = evaluate(sym, b * u, sign, false);
    if (mech) *mech = p.r.mechanism;
    return std::abs(p.r.e);
  };
  struct Best {
    double e;
    Eigen::Vector2d u;
  };
  std::vector<Best> best;
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      const Eigen::Vector2d u(double(i) / grid, double(j) / grid);
      const double e = value(u, nullptr);
      if (std::isinf(e)) continue;
      best.push_back({e, u});
    }
  if (best.empty()) {
    out.reason = "A^(k, e) stable for every sampled k and every e of this sign";
    if (out.neutral_points) out.reason += "; " + std::to_string(out.neutral_points) + " neutral zone-boundary zero(s)";
    return out;
  }
  const size_t keep = std::min<size_t>(4, best.size());
  std::partial_sort(best.begin(), best.begin() + keep, best.end(),
                    [](const Best& x, const Best& y) { return x.e < y.e; });
  double e_best = kInf2D;
  Eigen::Vector2d u_best = best[0].u;
  for (size_t t = 0; t < keep; ++t) {
    Best cur = best[t];
    double step = 1.0 / grid;
    for (int level = 0; level < 6; ++level) {
      step /= 4;
      const Best centre = cur;
      for (int i = -4; i <= 4; ++i)
        for (int j = -4; j <= 4; ++j) {
          const Eigen::Vector2d u = centre.u + step * Eigen::Vector2d(i, j);
          const double e = value(u, nullptr);
          if (e < cur.e) cur = {e, u};
        }
    }
    if (cur.e < e_best) {
      e_best = cur.e;
      u_best = cur.u;
    }
  }
  InstabilityMechanism mech = InstabilityMechanism::None;
  value(u_best, &mech);
  out.e = sgn * e_best;
  out.mechanism = mech;
  report_k(b * u_best);
  out.reason = "minimum over the Brillouin zone (grid " + std::to_string(grid) + " + refinement)";
  if (out.neutral_points)
    out.reason += "; " + std::to_string(out.neutral_points) + " neutral zone-boundary zero(s) skipped";
  return out;
}

std::vector<Eigen::Vector2d> periodic_wavevectors(const BravaisLattice2D& lat, int n) {
  if (n < 2) throw std::invalid_argument("periodic_wavevectors: n must be >= 2 (got " + std::to_string(n) + ")");
  if (lat.type != LatticeType::Square && n % 2 != 0)
    throw std::invalid_argument("periodic_wavevectors: periodic hex/face-centred lattices need an even n (got " +
                                std::to_string(n) + ")");
  require_memory(16.0 * n * n,
                 "periodic_wavevectors: " + std::to_string(n) + " x " + std::to_string(n) + " wavevectors");
  std::vector<Eigen::Vector2d> ks;
  ks.reserve(static_cast<size_t>(n) * n);
  const double dy = lat.a2.y();
  for (int m2 = 0; m2 < n; ++m2)
    for (int m1 = 0; m1 < n; ++m1) ks.emplace_back(2 * M_PI * m1 / (n * lat.dx), 2 * M_PI * m2 / (n * dy));
  return ks;
}

SymbolCriticalStrain critical_strain_periodic_symbol_2d(const ElasticSymbol2D& sym, int n, LoadDirection sign) {
  const std::vector<Eigen::Vector2d> ks = periodic_wavevectors(sym.lattice(), n);
  const double sgn = sign == LoadDirection::Tension ? 1.0 : -1.0;
  SymbolCriticalStrain out = initial_result(sym, sgn);
  if (std::isnan(out.e)) return out;
  out.reason = "A^(k_m, e) stable at every admissible k_m";
  for (size_t m = 1; m < ks.size(); ++m) {
    const bool zero = is_zone_boundary_zero(sym.lattice(), ks[m]);
    const PointResult p = evaluate(sym, ks[m], sign, zero);
    if (p.r.mechanism == InstabilityMechanism::None) continue;
    if (p.r.mechanism == InstabilityMechanism::Neutral) ++out.neutral_points;
    if (std::abs(p.r.e) < std::abs(out.e)) {
      out.e = p.r.e;
      out.mechanism = p.r.mechanism;
      const Eigen::Vector2d f = sym.lattice().fold(ks[m]) * sym.lattice().dx / M_PI;
      out.kx_over_pi = f[0];
      out.ky_over_pi = f[1];
      out.reason = zero ? (p.r.mechanism == InstabilityMechanism::Neutral
                               ? "neutral zone-boundary mode: A0^ = 0 and A1^ singular so A(e) is singular for every e"
                               : "zone-boundary zero: A0^ = 0 and the initial-stress symbol destabilises")
                        : "minimum over the admissible wavevectors";
      if (p.r.e == 0) break;
    }
  }
  return out;
}

}  // namespace sphstab
