#include "sphstab/integrate/xsph.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab {

namespace {

void check_options(const XsphOptions& o, const char* who) {
  if (!(o.epsilon >= 0) || !std::isfinite(o.epsilon))
    throw std::invalid_argument(std::string(who) + ": epsilon must be finite and >= 0 (got " +
                                std::to_string(o.epsilon) + ")");
}

/// w = v + eps sum_j (v_j - v_i) W_ij over the free particles, W given on the neighbour pattern.
template <int Dim>
void smooth(const Discretisation<Dim>& d, const SparseMatrix<>& W, const XsphOptions& o, const Eigen::VectorXd& v,
            Eigen::VectorXd& w) {
  const NeighbourList& nl = d.neighbours;
  const double* val = W.valuePtr();
  w.resize(v.size());
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    double acc[Dim] = {};
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) continue;
      const int g = d.free_slot[j];
      if (g < 0 && !o.include_fixed) continue;
      for (int a = 0; a < Dim; ++a) acc[a] += ((g >= 0 ? v[g * Dim + a] : 0.0) - v[f * Dim + a]) * val[k];
    }
    for (int a = 0; a < Dim; ++a) w[f * Dim + a] = v[f * Dim + a] + o.epsilon * acc[a];
  }
}

}  // namespace

template <int Dim>
VelocityHook xsph_hook(std::shared_ptr<const Discretisation<Dim>> discretisation, const XsphOptions& options) {
  if (!discretisation) throw std::invalid_argument("xsph_hook: discretisation is null");
  check_options(options, "xsph_hook");
  struct State {
    std::shared_ptr<const Discretisation<Dim>> d;
    XsphOptions o;
    Operators<Dim> ops;
    Positions<Dim> x;
  };
  auto s = std::make_shared<State>();
  s->d = std::move(discretisation);
  s->o = options;
  const OperatorRequest req{.kernel = true, .gradient = false, .hessian = false};
  assemble_operators_into<Dim, double>(s->ops, s->d->particles, s->d->neighbours, s->d->kernel, s->d->h, req);
  return [s, req](const Eigen::VectorXd& u, const Eigen::VectorXd& v, Eigen::VectorXd& w) {
    const Discretisation<Dim>& d = *s->d;
    if (u.size() != d.dofs() || v.size() != d.dofs())
      throw std::invalid_argument("xsph_hook: u and v need " + std::to_string(d.dofs()) + " entries (got " +
                                  std::to_string(u.size()) + ", " + std::to_string(v.size()) + ")");
    if (s->o.current_positions) {
      s->x = d.particles.x;
      for (int f = 0; f < d.free_count(); ++f)
        for (int a = 0; a < Dim; ++a) s->x(d.free[f], a) += u[f * Dim + a];
      assemble_operators_into<Dim, double>(s->ops, d.particles, d.neighbours, d.kernel, d.h, req, &s->x);
    }
    smooth<Dim>(d, s->ops.W, s->o, v, w);
  };
}

template <int Dim>
SparseMatrix<> xsph_smoothing_matrix(const Discretisation<Dim>& d, const XsphOptions& o) {
  check_options(o, "xsph_smoothing_matrix");
  const SparseMatrix<> W = kernel_matrix(d.particles, d.neighbours, d.kernel, d.h);
  const NeighbourList& nl = d.neighbours;
  std::vector<Eigen::Triplet<double>> t;
  for (int f = 0; f < d.free_count(); ++f) {
    const int i = d.free[f];
    double diag = 1.0;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) continue;
      const int g = d.free_slot[j];
      const double wij = W.valuePtr()[k];
      if (g >= 0) t.emplace_back(f, g, o.epsilon * wij);
      if (g >= 0 || o.include_fixed) diag -= o.epsilon * wij;
    }
    t.emplace_back(f, f, diag);
  }
  SparseMatrix<> S(d.free_count(), d.free_count());
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

template VelocityHook xsph_hook<1>(std::shared_ptr<const Discretisation<1>>, const XsphOptions&);
template VelocityHook xsph_hook<2>(std::shared_ptr<const Discretisation<2>>, const XsphOptions&);
template SparseMatrix<> xsph_smoothing_matrix<1>(const Discretisation<1>&, const XsphOptions&);
template SparseMatrix<> xsph_smoothing_matrix<2>(const Discretisation<2>&, const XsphOptions&);

}  // namespace sphstab
