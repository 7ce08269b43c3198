#include "sphstab/operators/ncsph.hpp"

#include <Eigen/Dense>
#include <sstream>

#include "correction_detail.hpp"
#include "sphstab/numerics/instantiation.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {

template <int Dim, class Scalar>
std::array<SparseMatrix<Scalar>, Dim> ncsph_gradient(const ParticleSet<Dim>& p, const SparseMatrix<Scalar>& W,
                                                     const std::array<SparseMatrix<Scalar>, Dim>& G,
                                                     const Positions<Dim, Scalar>* positions, double min_rcond) {
  const char* who = "ncsph_gradient";
  p.validate(who);
  detail::check_operator(W, who, "W");
  if (W.rows() != p.size())
    throw std::invalid_argument(std::string(who) + ": W is " + std::to_string(W.rows()) + " x " +
                                std::to_string(W.cols()) + " but the particle set has " + std::to_string(p.size()) +
                                " particles");
  if (positions && positions->rows() != p.size())
    throw std::invalid_argument(std::string(who) + ": positions have " + std::to_string(positions->rows()) +
                                " rows but the particle set has " + std::to_string(p.size()) + " particles");
  if (!(min_rcond >= 0) || !(min_rcond < 1))
    throw std::invalid_argument(std::string(who) + ": min_rcond must lie in [0, 1) (got " + std::to_string(min_rcond) +
                                ")");
  SparseMatrix<Scalar> w = W;
  w.makeCompressed();
  std::array<SparseMatrix<Scalar>, Dim> gt;
  for (int a = 0; a < Dim; ++a) {
    SparseMatrix<Scalar> g = G[a];
    g.makeCompressed();
    if (!detail::same_pattern(w, g))
      throw std::invalid_argument(std::string(who) + ": W and G[" + std::to_string(a) +
                                  "] must share one sparsity pattern (assemble them together)");
    gt[a] = shepard_gradient(w, g);
    gt[a].makeCompressed();
    if (!detail::same_pattern(w, gt[a]))  // cannot happen for equal input patterns; guards the loop below
      throw std::invalid_argument(std::string(who) + ": internal pattern mismatch");
  }

  std::array<SparseMatrix<Scalar>, Dim> out = gt;
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  for (int i = 0; i < p.size(); ++i) {
    const int begin = w.outerIndexPtr()[i], end = w.outerIndexPtr()[i + 1];
    Mat m = Mat::Zero();
    for (int k = begin; k < end; ++k) {
      const int j = w.innerIndexPtr()[k];
      for (int a = 0; a < Dim; ++a) {
        // x_j - x_i, minimum image decided on the real part (as in assemble_operators).
        Scalar d = positions ? Scalar((*positions)(j, a) - (*positions)(i, a)) : Scalar(p.x(j, a) - p.x(i, a));
        if (p.periodic[a]) {
          const double L = p.box_hi[a] - p.box_lo[a];
          d -= L * std::round(detail::re(d) / L);
        }
        for (int b = 0; b < Dim; ++b) m(a, b) += d * gt[b].valuePtr()[k];
      }
    }
    Eigen::Matrix<double, Dim, Dim> mr;
    for (int a = 0; a < Dim; ++a)
      for (int b = 0; b < Dim; ++b) mr(a, b) = detail::re(m(a, b));
    double rcond = 0;
    if (mr.allFinite()) {
      Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(mr);
      const auto& sv = svd.singularValues();
      if (sv[0] > 0) rcond = sv[Dim - 1] / sv[0];
    }
    if (!(rcond >= min_rcond)) {
      std::ostringstream msg;
      msg << who << ": moment matrix of particle " << i << " is singular or ill-conditioned (rcond " << rcond << " < "
          << min_rcond << ", " << (end - begin) << " neighbours incl. itself); NCSPH needs neighbours "
          << "whose separations span every axis (increase h)";
      throw std::invalid_argument(msg.str());
    }
    const Mat minv = m.inverse();
    for (int k = begin; k < end; ++k) {
      Eigen::Matrix<Scalar, 1, Dim> row;
      for (int c = 0; c < Dim; ++c) row[c] = gt[c].valuePtr()[k];
      Eigen::Matrix<Scalar, 1, Dim> corrected = row * minv;
      for (int b = 0; b < Dim; ++b) out[b].valuePtr()[k] = corrected[b];
    }
  }
  return out;
}

#define SPHSTAB_INSTANTIATE(D, S)                                                                             \
  template std::array<SparseMatrix<S>, D> ncsph_gradient<D, S>(const ParticleSet<D>&, const SparseMatrix<S>&, \
                                                               const std::array<SparseMatrix<S>, D>&,         \
                                                               const Positions<D, S>*, double);
SPHSTAB_FOR_EACH_DIM_AND_SCALAR(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
