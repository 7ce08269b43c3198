#include "sphstab/operators/local_polish.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "correction_detail.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

constexpr NamedValue<NeighbourCounting> kCountingNames[] = {{NeighbourCounting::Actual, "actual"},
                                                            {NeighbourCounting::BoundaryLevel, "boundary-level"}};

NeighbourCounting parse_neighbour_counting(const std::string& name) {
  return parse_named(name, kCountingNames, "neighbour counting");
}

template <int Dim>
Eigen::VectorXd neighbour_counts(const ParticleSet<Dim>& p, const NeighbourList& nl, NeighbourCounting counting) {
  const char* who = "neighbour_counts";
  if (nl.size() != p.size())
    throw std::invalid_argument(std::string(who) + ": neighbour list has " + std::to_string(nl.size()) +
                                " rows but the particle set has " + std::to_string(p.size()) + " particles");
  Eigen::VectorXd n(p.size());
  for (int i = 0; i < p.size(); ++i) n[i] = nl.count(i);
  if (counting == NeighbourCounting::Actual) return n;
  if (static_cast<int>(p.depth.size()) != p.size())
    throw std::invalid_argument(std::string(who) + ": boundary-level counting needs a depth per particle (got " +
                                std::to_string(p.depth.size()) + " for " + std::to_string(p.size()) + " particles)");
  for (int i = 0; i < p.size(); ++i) {
    const int di = p.depth[i];
    int deepest = di;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) deepest = std::max(deepest, p.depth[nl.indices[k]]);
    if (!(di < deepest - di)) continue;  // complete: keep the actual count
    double count = 1;                    // self
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) continue;
      if (p.depth[j] > di)
        count += 2;
      else if (p.depth[j] == di)
        count += 1;
    }
    n[i] = count;
  }
  return n;
}

template <class Scalar>
LocalMeans<Scalar> local_means(const SparseMatrix<Scalar>& G, const Eigen::VectorXd& n) {
  const char* who = "local_means";
  detail::check_operator(G, who, "G");
  if (n.size() != G.rows())
    throw std::invalid_argument(std::string(who) + ": counts have " + std::to_string(n.size()) + " entries but G is " +
                                std::to_string(G.rows()) + " x " + std::to_string(G.cols()));
  for (Eigen::Index i = 0; i < n.size(); ++i)
    if (!(n[i] > 0) || !std::isfinite(n[i]))
      throw std::invalid_argument(std::string(who) + ": neighbour count of particle " + std::to_string(i) +
                                  " must be finite and > 0 (got " + std::to_string(n[i]) + ")");
  LocalMeans<Scalar> m;
  m.row = detail::row_sums(G);
  m.column = detail::column_sums(G);
  for (Eigen::Index i = 0; i < n.size(); ++i) {
    m.row[i] /= n[i];
    m.column[i] /= n[i];
  }
  m.mean_of_columns = detail::Vector<Scalar>::Zero(G.rows());
  for (int i = 0; i < G.outerSize(); ++i) {
    for (typename SparseMatrix<Scalar>::InnerIterator it(G, i); it; ++it) m.mean_of_columns[i] += m.column[it.col()];
    m.mean_of_columns[i] /= n[i];
  }
  return m;
}

template <class Scalar>
SparseMatrix<Scalar> local_polish(const SparseMatrix<Scalar>& G, const LocalMeans<Scalar>& m) {
  const char* who = "local_polish";
  detail::check_operator(G, who, "G");
  if (m.row.size() != G.rows() || m.column.size() != G.rows() || m.mean_of_columns.size() != G.rows())
    throw std::invalid_argument(std::string(who) + ": means must have " + std::to_string(G.rows()) + " entries");
  SparseMatrix<Scalar> c = G;
  c.makeCompressed();
  for (int i = 0; i < c.outerSize(); ++i)
    for (typename SparseMatrix<Scalar>::InnerIterator it(c, i); it; ++it)
      it.valueRef() += m.mean_of_columns[i] - m.row[i] - m.column[it.col()];
  return c;
}

template <class Scalar>
SparseMatrix<Scalar> local_polish(const SparseMatrix<Scalar>& G, const Eigen::VectorXd& counts) {
  return local_polish<Scalar>(G, local_means<Scalar>(G, counts));
}

#define SPHSTAB_INSTANTIATE(D) \
  template Eigen::VectorXd neighbour_counts<D>(const ParticleSet<D>&, const NeighbourList&, NeighbourCounting);
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

#define SPHSTAB_INSTANTIATE(S)                                                            \
  template struct LocalMeans<S>;                                                          \
  template LocalMeans<S> local_means<S>(const SparseMatrix<S>&, const Eigen::VectorXd&);  \
  template SparseMatrix<S> local_polish<S>(const SparseMatrix<S>&, const LocalMeans<S>&); \
  template SparseMatrix<S> local_polish<S>(const SparseMatrix<S>&, const Eigen::VectorXd&);
SPHSTAB_FOR_EACH_SCALAR(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
