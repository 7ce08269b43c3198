#include "sphstab/operators/correction.hpp"

#include <stdexcept>

#include "sphstab/core/named_values.hpp"
#include "sphstab/numerics/dual.hpp"
#include "sphstab/numerics/instantiation.hpp"
#include "sphstab/operators/column_shepard.hpp"
#include "sphstab/operators/mean_polish.hpp"
#include "sphstab/operators/minus_gradient.hpp"
#include "sphstab/operators/ncsph.hpp"

namespace sphstab {

constexpr NamedValue<Correction> kCorrectionNames[] = {{Correction::None, "none"},
                                                       {Correction::Minus, "minus"},
                                                       {Correction::Shepard, "shepard"},
                                                       {Correction::ColumnShepard, "column-shepard"},
                                                       {Correction::Ncsph, "ncsph"},
                                                       {Correction::LocalPolish, "local-polish"},
                                                       {Correction::MeanPolish, "mean-polish"},
                                                       {Correction::ShepardColumnPolish, "shepard-column-polish"}};

const std::vector<Correction>& all_corrections() {
  static const std::vector<Correction> all = values_of(kCorrectionNames);
  return all;
}
std::string correction_name(Correction c) { return name_of(c, kCorrectionNames); }
Correction parse_correction(const std::string& name) { return parse_named(name, kCorrectionNames, "correction"); }

bool correction_is_dense(Correction c) { return c == Correction::MeanPolish || c == Correction::ShepardColumnPolish; }

template <int Dim, class Scalar>
std::array<SparseMatrix<Scalar>, Dim> apply_correction(Correction c, const ParticleSet<Dim>& p, const NeighbourList& nl,
                                                       const Operators<Dim, Scalar>& ops,
                                                       const CorrectionOptions<Dim>& opt,
                                                       const Positions<Dim, Scalar>* positions) {
  const std::string who = "apply_correction(" + correction_name(c) + ")";
  for (int a = 0; a < Dim; ++a)
    if (ops.G[a].rows() != p.size() || ops.G[a].cols() != p.size())
      throw std::invalid_argument(who + ": G[" + std::to_string(a) + "] is " + std::to_string(ops.G[a].rows()) + " x " +
                                  std::to_string(ops.G[a].cols()) + ", expected " + std::to_string(p.size()) + " x " +
                                  std::to_string(p.size()) + " (assemble the gradient)");
  const bool needs_w = c == Correction::Shepard || c == Correction::ColumnShepard || c == Correction::Ncsph ||
                       c == Correction::ShepardColumnPolish || (c == Correction::LocalPolish && opt.reference);
  if (needs_w && (ops.W.rows() != p.size() || ops.W.cols() != p.size()))
    throw std::invalid_argument(who + ": needs the kernel matrix W of size " + std::to_string(p.size()) +
                                " (assemble the kernel too)");
  if (opt.polish_free_only && c != Correction::MeanPolish)
    throw std::invalid_argument(who + ": polishing over the free particles only applies to mean-polish");
  if (opt.reference && c != Correction::LocalPolish)
    throw std::invalid_argument(who + ": a first-step Shepard reference only applies to local-polish");
  if (opt.counting != NeighbourCounting::Actual && c != Correction::LocalPolish)
    throw std::invalid_argument(who + ": neighbour counting only applies to local-polish");

  std::array<SparseMatrix<Scalar>, Dim> out;
  if (c == Correction::Ncsph) return ncsph_gradient<Dim, Scalar>(p, ops.W, ops.G, positions, opt.min_rcond);
  Eigen::VectorXd counts;
  if (c == Correction::LocalPolish) counts = neighbour_counts(p, nl, opt.counting);
  std::vector<int> subset;
  if (opt.polish_free_only) {
    subset = p.indices(Role::Free);
    if (subset.empty()) throw std::invalid_argument(who + ": the particle set has no free particles");
  }
  for (int a = 0; a < Dim; ++a) {
    switch (c) {
      case Correction::None:
        out[a] = ops.G[a];
        break;
      case Correction::Minus:
        out[a] = minus_gradient(ops.G[a]);
        break;
      case Correction::Shepard:
        out[a] = shepard_gradient(ops.W, ops.G[a]);
        break;
      case Correction::ColumnShepard:
        out[a] = column_shepard_gradient(ops.W, ops.G[a]);
        break;
      case Correction::LocalPolish:
        if (opt.reference)
          out[a] = local_polish(ops.G[a],
                                local_means(reference_shepard_gradient(ops.W, ops.G[a], (*opt.reference)[a]), counts));
        else
          out[a] = local_polish(ops.G[a], counts);
        break;
      case Correction::MeanPolish:
        out[a] = dense_to_sparse_all_entries<Scalar>(mean_polish(ops.G[a], subset));
        break;
      case Correction::ShepardColumnPolish:
        out[a] = dense_to_sparse_all_entries<Scalar>(shepard_column_polish(ops.W, ops.G[a]));
        break;
      case Correction::Ncsph:
        break;  // handled above
    }
  }
  return out;
}

#define SPHSTAB_INSTANTIATE(D, S)                                                                              \
  template std::array<SparseMatrix<S>, D> apply_correction<D, S>(Correction, const ParticleSet<D>&,            \
                                                                 const NeighbourList&, const Operators<D, S>&, \
                                                                 const CorrectionOptions<D>&, const Positions<D, S>*);
SPHSTAB_FOR_EACH_DIM_AND_SCALAR(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
