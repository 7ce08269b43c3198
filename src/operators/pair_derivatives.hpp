#pragma once
// The per-pair kernel derivatives behind G and H (operators.hpp), shared by assemble_operators_into and the
// matrix-free linearisation (which computes them without assembling the matrices), so both hold the same bits.
#include <Eigen/Core>
#include <array>
#include <cmath>

#include "sphstab/kernel/kernel.hpp"
#include "sphstab/numerics/dual.hpp"
#include "sphstab/particles/particle_set.hpp"

namespace sphstab::detail {

/// x_i - x_j at `positions` (N x Dim) or the particles' own positions, with the minimum image on periodic axes
/// (neighbours are closer than half the box, so one shift suffices; decided on the real part). `box`: extent per axis.
template <int Dim, class Scalar, class PositionMatrix>
Eigen::Matrix<Scalar, 1, Dim> pair_separation(const ParticleSet<Dim>& p, const PositionMatrix* positions,
                                              const std::array<double, Dim>& box, int i, int j) {
  Eigen::Matrix<Scalar, 1, Dim> d;
  for (int a = 0; a < Dim; ++a) {
    if (positions)
      d[a] = (*positions)(i, a) - (*positions)(j, a);
    else
      d[a] = Scalar(p.x(i, a) - p.x(j, a));
    if (p.periodic[a]) {
      const double L = box[a], dr = re(d[a]);
      if (dr > 0.5 * L)
        d[a] -= L;
      else if (dr < -0.5 * L)
        d[a] += L;
    }
  }
  return d;
}

/// G and H entries of a pair at separation d, r2 = |d|^2 > 0, r = sqrt(r2), neighbour volume vj:
/// g[a] = W'(r) d_a / r vj (when g is given), h[a][b] = (W''(r) e_ab + W'(r)/r (delta_ab - e_ab)) vj for a <= b with
/// e_ab = d_a d_b / r2 (when h is given).
template <int Dim, class Scalar>
void pair_derivatives(const Kernel<Dim>& kernel, double h, const Eigen::Matrix<Scalar, 1, Dim>& d, const Scalar& r2,
                      const Scalar& r, double vj, Scalar* g, std::array<std::array<Scalar, Dim>, Dim>* hh) {
  const Scalar dw = kernel.d1(r, h);
  if (g)
    for (int a = 0; a < Dim; ++a) g[a] = dw * d[a] / r * vj;
  if (hh) {
    const Scalar ddw = kernel.d2(r, h);
    const Scalar over_r = dw / r;
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) {
        Scalar eab = d[a] * d[b] / r2;
        (*hh)[a][b] = (ddw * eab + over_r * ((a == b ? 1.0 : 0.0) - eab)) * vj;
      }
  }
}

}  // namespace sphstab::detail
