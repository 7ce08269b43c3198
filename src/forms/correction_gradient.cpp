#include "sphstab/forms/correction_gradient.hpp"

#include <stdexcept>

#include "sphstab/numerics/instantiation.hpp"
#include "sphstab/operators/shepard.hpp"

namespace sphstab {

template <int Dim>
CorrectionGradient<Dim>::CorrectionGradient(Correction correction, CorrectionGradientOptions options)
    : m_correction(correction), m_options(options) {
  const std::string who = "CorrectionGradient(" + correction_name(correction) + ")";
  if ((options.counting != NeighbourCounting::Actual || options.first_step_shepard) &&
      correction != Correction::LocalPolish)
    throw std::invalid_argument(who +
                                ": neighbour counting and the first-step Shepard means apply to local-polish only");
  if (options.polish_free_only && correction != Correction::MeanPolish)
    throw std::invalid_argument(who + ": polishing over the free particles only applies to mean-polish");
  if (!(options.min_rcond >= 0) || !(options.min_rcond < 1))
    throw std::invalid_argument(who + ": min_rcond must lie in [0, 1) (got " + std::to_string(options.min_rcond) + ")");
}

template <int Dim>
std::string CorrectionGradient<Dim>::name() const {
  std::string s = correction_name(m_correction);
  if (m_options.counting == NeighbourCounting::BoundaryLevel) s += "+fig4.3";
  if (m_options.first_step_shepard) s += "+eq4.18";
  if (m_options.polish_free_only) s += "+free";
  return s;
}

template <int Dim>
OperatorRequest CorrectionGradient<Dim>::requirements() const {
  const Correction c = m_correction;
  const bool w = c == Correction::Shepard || c == Correction::ColumnShepard || c == Correction::Ncsph ||
                 c == Correction::ShepardColumnPolish || (c == Correction::LocalPolish && m_options.first_step_shepard);
  return {.kernel = w, .gradient = true, .hessian = false};
}

template <int Dim>
int CorrectionGradient<Dim>::dependence_radius() const {
  switch (m_correction) {
    case Correction::None:
    case Correction::Minus:
    case Correction::Shepard:  // S_i, g_i: sums over N(i)
    case Correction::Ncsph:    // Shepard + the moment matrix of row i
      return 1;
    case Correction::ColumnShepard:  // column sums of column j in N(i): particles in N(j)
    case Correction::LocalPolish:    // c_j over N(j) and m_i over c_j, j in N(i)
      return 2;
    case Correction::MeanPolish:
    case Correction::ShepardColumnPolish:
      return kFullReach;
  }
  return kFullReach;
}

template <int Dim>
template <class Scalar>
void CorrectionGradient<Dim>::correct_impl(const GradientContext<Dim, Scalar>& c,
                                           std::array<SparseMatrix<Scalar>, Dim>& g) const {
  const Discretisation<Dim>& d = c.discretisation;
  CorrectionOptions<Dim> opt;
  opt.counting = m_options.counting;
  opt.polish_free_only = m_options.polish_free_only;
  opt.min_rcond = m_options.min_rcond;
  std::array<ShepardReference, Dim> reference;
  if (m_options.first_step_shepard) {
    // Powell (4.18): kernel sums frozen at the reference positions x0 (real, not differentiated).
    const Operators<Dim, double> ops0 = assemble_operators<Dim, double>(
        d.particles, d.neighbours, d.kernel, d.h, {.kernel = true, .gradient = true, .hessian = false});
    for (int a = 0; a < Dim; ++a) reference[a] = shepard_reference(ops0.W, ops0.G[a]);
    opt.reference = &reference;
  }
  g = apply_correction<Dim, Scalar>(m_correction, d.particles, d.neighbours, c.operators, opt, &c.positions);
}

template <int Dim>
std::shared_ptr<const GradientProvider<Dim>> make_gradient_provider(Correction correction,
                                                                    CorrectionGradientOptions options) {
  return std::make_shared<CorrectionGradient<Dim>>(correction, options);
}

#define SPHSTAB_INSTANTIATE_SCALAR(D, S)                                                                              \
  template void CorrectionGradient<D>::correct_impl<S>(const GradientContext<D, S>&, std::array<SparseMatrix<S>, D>&) \
      const;
#define SPHSTAB_INSTANTIATE(D)                                                                              \
  template class CorrectionGradient<D>;                                                                     \
  template std::shared_ptr<const GradientProvider<D>> make_gradient_provider<D>(Correction,                 \
                                                                                CorrectionGradientOptions); \
  SPHSTAB_INSTANTIATE_SCALAR(D, double)                                                                     \
  SPHSTAB_INSTANTIATE_SCALAR(D, std::complex<double>)                                                       \
  SPHSTAB_INSTANTIATE_SCALAR(D, Dual<double>)                                                               \
  SPHSTAB_INSTANTIATE_SCALAR(D, Dual<std::complex<double>>)
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE
#undef SPHSTAB_INSTANTIATE_SCALAR

}  // namespace sphstab
