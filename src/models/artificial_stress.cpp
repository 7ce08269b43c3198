#include "sphstab/models/artificial_stress.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/models/artificial_stress_particle.hpp"

namespace sphstab {

namespace detail {

inline void check_exponent(const char* who, double n) {
  if (!(n >= 0) || !std::isfinite(n))
    throw std::invalid_argument(std::string(who) + ": exponent n must be finite and >= 0 (got " + std::to_string(n) +
                                ")");
}

inline void check_epsilon(const char* who, double epsilon) {
  if (!(epsilon >= 0) || !std::isfinite(epsilon))
    throw std::invalid_argument(std::string(who) + ": epsilon must be finite and >= 0 (got " + std::to_string(epsilon) +
                                ")");
}

/// x^n without validation (n >= 0 finite): exact for integer n, exp(n log x) otherwise.
template <class Scalar>
Scalar power_unchecked(const Scalar& x, double n) {
  if (n == std::floor(n) && n <= 1024) return ipow(x, static_cast<int>(n));
  if (re(x) <= 0) return Scalar(0);
  using std::exp;
  using std::log;
  return exp(n * log(x));
}

}  // namespace detail

template <class Scalar>
PrincipalFrame<Scalar> principal_frame(const SymmetricTensor2<Scalar>& sigma) {
  return artificial_stress_detail::principal_frame<artificial_stress_detail::Frame::Full>(sigma);
}

template <class Scalar>
SymmetricTensor2<Scalar> rotate_from_frame(const PrincipalFrame<Scalar>& f, const Scalar& rbar_xx,
                                           const Scalar& rbar_yy) {
  return artificial_stress_detail::back_rotate(f, rbar_xx, rbar_yy);
}

template <class Scalar>
SymmetricTensor2<Scalar> artificial_stress(const SymmetricTensor2<Scalar>& sigma, const Scalar& density,
                                           double epsilon) {
  detail::check_epsilon("artificial_stress", epsilon);
  return artificial_stress_detail::particle_artificial_stress<artificial_stress_detail::Frame::Full>(sigma, density,
                                                                                                     epsilon);
}

template <class Scalar>
TensorField2<Scalar> artificial_stress(const TensorField2<Scalar>& sigma,
                                       const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& density, double epsilon) {
  if (density.size() != sigma.rows())
    throw std::invalid_argument("artificial_stress: " + std::to_string(density.size()) + " densities for " +
                                std::to_string(sigma.rows()) + " stress rows");
  TensorField2<Scalar> R(sigma.rows(), 3);
  for (Eigen::Index i = 0; i < sigma.rows(); ++i) {
    const auto r =
        artificial_stress(SymmetricTensor2<Scalar>{sigma(i, 0), sigma(i, 1), sigma(i, 2)}, density[i], epsilon);
    R(i, 0) = r.xx;
    R(i, 1) = r.yy;
    R(i, 2) = r.xy;
  }
  return R;
}

double artificial_stress_reference_kernel(const Kernel<2>& kernel, double h, double dp) {
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument("artificial_stress_reference_kernel: h must be finite and > 0 (got " +
                                std::to_string(h) + ")");
  if (!(dp > 0) || !std::isfinite(dp))
    throw std::invalid_argument("artificial_stress_reference_kernel: spacing dp must be finite and > 0 (got " +
                                std::to_string(dp) + ")");
  const double w = kernel.value(dp, h);
  if (!(w > 0))
    throw std::invalid_argument("artificial_stress_reference_kernel: W(dp) = 0: dp = " + std::to_string(dp) +
                                " is outside the kernel support " + std::to_string(kernel.support_radius(h)));
  return w;
}

template <class Scalar>
Scalar artificial_stress_power(const Scalar& x, double n) {
  detail::check_exponent("artificial_stress_power", n);
  return detail::power_unchecked(x, n);
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 2> artificial_stress_acceleration(const Operators<2, Scalar>& ops,
                                                                        const Eigen::VectorXd& mass,
                                                                        const Eigen::VectorXd& volume,
                                                                        const TensorField2<Scalar>& R, double w_dp,
                                                                        double n) {
  const char* who = "artificial_stress_acceleration";
  detail::check_exponent(who, n);
  if (!(w_dp > 0) || !std::isfinite(w_dp))
    throw std::invalid_argument(std::string(who) + ": W(dp) must be finite and > 0 (got " + std::to_string(w_dp) + ")");
  const Eigen::Index N = R.rows();
  if (mass.size() != N || volume.size() != N)
    throw std::invalid_argument(std::string(who) + ": mass and volume need " + std::to_string(N) + " entries (got " +
                                std::to_string(mass.size()) + ", " + std::to_string(volume.size()) + ")");
  if ((volume.array() <= 0).any() || !volume.allFinite())
    throw std::invalid_argument(std::string(who) + ": volumes must be finite and > 0");
  const SparseMatrix<Scalar>* mats[3] = {&ops.W, &ops.G[0], &ops.G[1]};
  for (const auto* m : mats) {
    if (m->rows() != N || m->cols() != N || !m->isCompressed())
      throw std::invalid_argument(std::string(who) + ": W and G must be assembled (compressed, " + std::to_string(N) +
                                  " x " + std::to_string(N) + ", got " + std::to_string(m->rows()) + " x " +
                                  std::to_string(m->cols()) + ")");
    if (m->nonZeros() != ops.W.nonZeros() ||
        !std::equal(m->outerIndexPtr(), m->outerIndexPtr() + N + 1, ops.W.outerIndexPtr()) ||
        !std::equal(m->innerIndexPtr(), m->innerIndexPtr() + m->nonZeros(), ops.W.innerIndexPtr()))
      throw std::invalid_argument(std::string(who) + ": W and G must share one neighbour pattern");
  }
  Eigen::Matrix<Scalar, Eigen::Dynamic, 2> acc = Eigen::Matrix<Scalar, Eigen::Dynamic, 2>::Zero(N, 2);
  const int* outer = ops.W.outerIndexPtr();
  const int* inner = ops.W.innerIndexPtr();
  const Scalar* w = ops.W.valuePtr();
  const Scalar* gx = ops.G[0].valuePtr();
  const Scalar* gy = ops.G[1].valuePtr();
  for (Eigen::Index i = 0; i < N; ++i) {
    Scalar ax(0), ay(0);
    for (int k = outer[i]; k < outer[i + 1]; ++k) {
      const int j = inner[k];
      if (j == i) continue;  // grad W_ii = 0
      if (detail::re(w[k]) <= 0) continue;
      // f_ij^n (GMS 3.13) with W(r_ij) = W_ij / V_j; m_j grad W_ij = (m_j / V_j) G_ij.
      const Scalar fn = detail::power_unchecked(Scalar(w[k] / (volume[j] * w_dp)), n);
      const Scalar c = (mass[j] / volume[j]) * fn;
      const Scalar rxx = R(i, 0) + R(j, 0), ryy = R(i, 1) + R(j, 1), rxy = R(i, 2) + R(j, 2);
      ax += c * (rxx * gx[k] + rxy * gy[k]);
      ay += c * (rxy * gx[k] + ryy * gy[k]);
    }
    acc(i, 0) = ax;
    acc(i, 1) = ay;
  }
  return acc;
}

#define SPHSTAB_INSTANTIATE(Scalar)                                                                                 \
  template PrincipalFrame<Scalar> principal_frame(const SymmetricTensor2<Scalar>&);                                 \
  template SymmetricTensor2<Scalar> rotate_from_frame(const PrincipalFrame<Scalar>&, const Scalar&, const Scalar&); \
  template SymmetricTensor2<Scalar> artificial_stress(const SymmetricTensor2<Scalar>&, const Scalar&, double);      \
  template TensorField2<Scalar> artificial_stress(const TensorField2<Scalar>&,                                      \
                                                  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>&, double);         \
  template Scalar artificial_stress_power(const Scalar&, double);                                                   \
  template Eigen::Matrix<Scalar, Eigen::Dynamic, 2> artificial_stress_acceleration(                                 \
      const Operators<2, Scalar>&, const Eigen::VectorXd&, const Eigen::VectorXd&, const TensorField2<Scalar>&,     \
      double, double);

SPHSTAB_INSTANTIATE(double)
SPHSTAB_INSTANTIATE(std::complex<double>)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
