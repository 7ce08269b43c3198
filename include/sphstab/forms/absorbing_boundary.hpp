#pragma once
/// \file absorbing_boundary.hpp
/// The acceleration of a boundary particle under a first-order non-reflecting condition, which replaces the momentum
/// equation there [Powell2012, (2.54)-(2.62)]: the elastic condition written along the particle's outward normal n
/// (tangent t, any orientation) in velocity form,
///     dv/dt = -B(n, t) (grad v) + (v . grad) v,
/// with the convective term optional (2.65: it shifts the effective speeds by |v|, so it matters only at high particle
/// speeds). L = grad v (L_ab = dv_a / dx_b) is the particle's velocity gradient (upwind or not, the caller's choice).
///   - ClaytonEngquist ("P", (2.42)): a = -c_p ((L n) . n) n - c_s ((L n) . t) t.
///   - Sochaki ("M", (2.45)): a = -[c_p (L n) . n + (c_p - c_s) (L t) . t] n - [c_s (L n) . t + (c_p - c_s) (L t) . n]
///   t.
///     The thesis's pseudocode for M has the signs flipped and the cross terms swapped (our check); this is (2.45)
///     itself, and it does not depend on the orientation of t.
///   - Higdon's condition is second order in time and has no such velocity form; Powell's "H" (c_p, c_s scaled by
///     the a-priori k . n) is the ClaytonEngquist law with those speeds (AbsorbingParticles::speed_scale), and
///     Higdon's own first-order factor (cos a d_t + c d_n, our correction of (2.33)) the same law with the
///     speeds divided by k . n.
///   - ViscousTraction (Powell (2.75), the LS-DYNA / Lysmer-Kuhlemeyer viscous boundary, his baseline): not a
///     replacement of the momentum equation but a traction sigma n = -rho (c_p (v . n) n + c_s (v . t) t) on the
///     body's outer face, which adds viscous_traction_acceleration() to the particle's momentum acceleration.
/// The plane-wave analysis of the same conditions is spectral/plane_wave_reflection.hpp.
///
/// \code{.cpp}
/// Eigen::Vector2d a = sphstab::absorbing_acceleration(sphstab::AbsorbingCondition::Sochaki, c_p, c_s, n, L, v);
/// \endcode
#include <Eigen/Core>
#include <vector>

namespace sphstab {

/// The first-order absorbing conditions of Powell ch. 2 for the elastic wave equation (u = (u_n, u_t)).
enum class AbsorbingCondition {
  ClaytonEngquist,  ///< "P" (2.42): (d_t + c_p d_n) u_n = 0, (d_t + c_s d_n) u_t = 0
  Sochaki,          ///< "M" (2.45): {d_t + diag(c_p, c_s) d_n + [[0, c_p - c_s], [c_p - c_s, 0]] d_t} u = 0
  Higdon,           ///< (2.41): (d_t + c_p d_n)(d_t + c_s d_n) u = 0 (second order: plane-wave analysis only)
  /// (2.75): sigma . n = -rho (c_p u_t,n n + c_s u_t,t t) on the face; in displacement form (divide the traction by
  /// rho c): {d_t + diag(c_p, c_s) d_n + [[0, c_p - 2 c_s^2 / c_p], [c_s, 0]] d_tangent} u = 0.
  ViscousTraction
};

/// dv/dt of a boundary particle with unit outward normal n, velocity gradient L and velocity v (2D). Throws
/// std::invalid_argument for Higdon (no first-order velocity form) or a normal that is not of unit length (1e-12).
/// Scalar: double, or std::complex<double> for complex-step Jacobians (n and the speeds stay real).
template <class Scalar>
Eigen::Matrix<Scalar, 2, 1> absorbing_acceleration(AbsorbingCondition condition, double c_p, double c_s,
                                                   const Eigen::Vector2d& n, const Eigen::Matrix<Scalar, 2, 2>& L,
                                                   const Eigen::Matrix<Scalar, 2, 1>& v, bool convective = false);

/// The real case for arguments that are Eigen expressions.
inline Eigen::Vector2d absorbing_acceleration(AbsorbingCondition condition, double c_p, double c_s,
                                              const Eigen::Vector2d& n, const Eigen::Matrix2d& L,
                                              const Eigen::Vector2d& v, bool convective = false) {
  return absorbing_acceleration<double>(condition, c_p, c_s, n, L, v, convective);
}

/// The acceleration that the viscous traction (2.75) adds to a particle of the outer face with unit outward normal n
/// and velocity v: (traction x face area) / mass = -(c_p (v . n) n + c_s (v . t) t) / depth, with depth = V / A the
/// particle's volume per unit face area (the spacing on a lattice) at the reference density. 1D: -c_p (v n) n / depth.
template <class Scalar, int Dim>
Eigen::Matrix<Scalar, Dim, 1> viscous_traction_acceleration(double c_p, double c_s,
                                                            const Eigen::Matrix<double, Dim, 1>& n,
                                                            const Eigen::Matrix<Scalar, Dim, 1>& v, double depth) {
  const Eigen::Matrix<Scalar, Dim, 1> nn = n.template cast<Scalar>();
  const Scalar vn = (v.array() * nn.array()).sum();  // bilinear: no conjugation under a complex step
  if constexpr (Dim == 1) {
    return -(c_p * vn / depth) * nn;
  } else {
    const Eigen::Matrix<Scalar, Dim, 1> tt = Eigen::Matrix<double, Dim, 1>(n[1], -n[0]).template cast<Scalar>();
    const Scalar vt = (v.array() * tt.array()).sum();
    return -(c_p * vn * nn + c_s * vt * tt) / depth;
  }
}

/// The 1D condition (2.69)-(2.70): dv/dt = -c n dv/dx (n = +1 at the right end, -1 at the left), plus v dv/dx with
/// the convective term.
template <class Scalar>
Scalar absorbing_acceleration_1d(double c, double n, const Scalar& dvdx, const Scalar& v, bool convective = false) {
  return -c * n * dvdx + (convective ? v * dvdx : Scalar(0));
}

/// The particles of a scheme whose momentum equation is replaced by an absorbing condition, Powell (2.62) and
/// algorithm 2.3 (RateFormScheme::set_absorbing). Their velocity gradient is Powell (1.33) with the scheme's gradient
/// (NCSPH whatever the scheme with `normalised`)
/// (plain or NCSPH) over their neighbours, or with upwind over the neighbours on the interior side only,
/// (x_j - x_i) . n_i <= 0 (Powell (2.67), "j < i" at a right end; the particles on the boundary's own line are kept so
/// that the tangential derivative of the Sochaki condition exists in 2D). The speeds are the scheme material's:
/// c_p = sqrt((K + 4 mu / 3) / rho0) (in 1D the bar's c), c_s = sqrt(mu / rho0), each times the particle's speed_scale
/// when given (Powell's "H": k . n; Higdon's first-order factor: 1 / k . n). Their density and stress evolve as for any
/// particle. With ViscousTraction the particles are the outer face, their momentum equation is kept and the traction's
/// viscous_traction_acceleration() (depth = traction_depth) is added to it; no velocity gradient is formed.
template <int Dim>
struct AbsorbingParticles {
  std::vector<int> particles;                                          ///< free particles, distinct, not driven
  std::vector<Eigen::Matrix<double, Dim, 1>> normals;                  ///< unit outward normal of each (1D: +1 or -1)
  AbsorbingCondition condition = AbsorbingCondition::ClaytonEngquist;  ///< not Higdon (no velocity form)
  bool upwind = false;              ///< Powell (2.67): interior-side neighbours only (use with a normalised gradient)
  bool convective = false;          ///< Powell (2.62)'s + (v . grad) v
  std::vector<double> speed_scale;  ///< per particle, positive: c_p and c_s times this (empty: 1)
  double traction_depth = 0;        ///< ViscousTraction: volume per unit face area (> 0; the spacing on a lattice)
  /// The velocity gradient with the NCSPH normalisation (Powell (1.19)) even in a plain-gradient scheme: a boundary
  /// particle's kernel sums are truncated, and the plain gradient underestimates d/dn there.
  bool normalised = false;
  bool empty() const { return particles.empty(); }
};

}  // namespace sphstab
