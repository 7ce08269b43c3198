#include "sphstab/jacobian/matrix_free_linearisation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "../linalg/tall_block_algebra.hpp"
#include "../operators/pair_derivatives.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/core/named_values.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/jacobian/analytic_jacobian_2d.hpp"

namespace sphstab {

namespace {

template <int Dim>
long free_row_pairs(const Discretisation<Dim>& d) {
  long pairs = 0;
  for (int i : d.free) pairs += d.neighbours.count(i);
  return pairs;
}

/// The force's discretisation, after checking that the closed form covers the force.
const Discretisation<2>& covered_discretisation(const ElasticForm2D& force) {
  require_closed_form_coverage(force, "MatrixFreeLinearisation");
  return force.discretisation();
}

/// Values between the starts of two component grids of ByOffset: the grid's sites rounded up to 4 KB, plus 576 bytes,
/// so that the 2 x 6 streams of step 3 (sigma at i +- d) fall into different L1 cache sets. Without it a padded
/// 32^3 grid (n = 24 in 3D) put every component 256 KB apart, on one set: A0 ran 4x slower than its flops.
long component_stride(long sites) { return (sites + 511) / 512 * 512 + 72; }

/// Index of the symmetric pair (a, b), a <= b, in row-by-row order (2D: xx, xy, yy; 3D: xx, xy, xz, yy, yz, zz).
template <int Dim>
constexpr int upper(int a, int b) {
  return a * Dim - a * (a - 1) / 2 + (b - a);
}

template <int Dim>
void check_operators(const Discretisation<Dim>& d, const Operators<Dim>& ops, const std::string& who) {
  const int n = d.size();
  const auto check = [&](const SparseMatrix<>& m, const std::string& name) {
    if (m.rows() != n || m.cols() != n || m.nonZeros() != d.neighbours.nonzeros() || !m.isCompressed())
      throw std::invalid_argument(who + ": operator " + name + " must be " + std::to_string(n) + " x " +
                                  std::to_string(n) +
                                  " with the neighbour-list pattern (assemble with gradient = true, hessian = true)");
  };
  const char* axis = "xyz";
  for (int a = 0; a < Dim; ++a) check(ops.G[a], std::string("G[") + axis[a] + "]");
  for (int a = 0; a < Dim; ++a)
    for (int b = a; b < Dim; ++b) check(ops.H[a][b], std::string("H[") + axis[a] + "][" + axis[b] + "]");
}

}  // namespace

constexpr NamedValue<MatrixFreeStorage> kStorageNames[] = {{MatrixFreeStorage::Auto, "auto"},
                                                           {MatrixFreeStorage::PerPair, "per-pair"},
                                                           {MatrixFreeStorage::ByOffset, "by-offset"}};

MatrixFreeStorage parse_matrix_free_storage(const std::string& name) {
  return parse_named(name, kStorageNames, "matrix-free storage");
}
std::string matrix_free_storage_name(MatrixFreeStorage storage) { return name_of(storage, kStorageNames); }

/// The free box and offset set of ByOffset (header comment), or the reason it does not apply.
template <int Dim>
struct MatrixFreeLinearisation<Dim>::Lattice {
  std::string refusal;                     ///< empty: ByOffset applies
  std::array<int, Dim> box{};              ///< free particles per axis
  double dx = 0, volume = 0;               ///< spacing, common volume
  int reach = 0;                           ///< max |d_a|
  std::vector<std::array<int, Dim>> half;  ///< D+: of each pair +-d the one whose last non-zero component is > 0
};

template <int Dim>
typename MatrixFreeLinearisation<Dim>::Lattice MatrixFreeLinearisation<Dim>::find_lattice(
    const Discretisation<Dim>& d) {
  Lattice L;
  const auto refuse = [&L](std::string why) {
    L.refusal = std::move(why);
    return L;
  };
  const char* axis = "xyz";
  const ParticleSet<Dim>& p = d.particles;
  for (int a = 0; a < Dim; ++a)
    if (p.periodic[a]) return refuse(std::string("axis ") + axis[a] + " is periodic");
  const int nf = d.free_count();
  if (nf < 2) return refuse("fewer than 2 free particles");
  const auto X = [&](long f, int a) { return p.x(d.free[f], a); };
  const double dx1 = X(1, 0) - X(0, 0);
  if (!(dx1 > 0) || !std::isfinite(dx1)) return refuse("free particles 0 and 1 are not x-neighbours");
  const double tol = 1e-9 * dx1;
  const auto same_line = [&](long f, long g, int from) {  // equal coordinates on the axes >= from
    for (int a = from; a < Dim; ++a)
      if (std::abs(X(f, a) - X(g, a)) > tol) return false;
    return true;
  };
  // The box from the DOF order: n_0 along the first row, n_1 rows in the first plane, n_2 = the rest.
  int n0 = 1;
  while (n0 < nf && same_line(n0, 0, 1)) ++n0;
  L.box.fill(1);
  L.box[0] = n0;
  if constexpr (Dim == 2) {
    L.box[1] = nf / n0;
  } else {
    int n1 = 1;
    while (static_cast<long>(n1) * n0 < nf && same_line(static_cast<long>(n1) * n0, 0, 2)) ++n1;
    L.box[1] = n1;
    L.box[2] = nf / (n0 * n1);
  }
  long count = 1;
  for (int a = 0; a < Dim; ++a) count *= L.box[a];
  std::string box_text = std::to_string(L.box[0]);
  for (int a = 1; a < Dim; ++a) box_text += " x " + std::to_string(L.box[a]);
  if (count != nf) return refuse(std::to_string(nf) + " free particles do not fill an " + box_text + " box");
  L.dx = n0 > 1 ? (X(n0 - 1, 0) - X(0, 0)) / (n0 - 1) : dx1;
  for (long f = 0; f < nf; ++f) {
    std::array<int, Dim> site;
    long rest = f;
    for (int a = 0; a < Dim; ++a) {
      site[a] = static_cast<int>(rest % L.box[a]);
      rest /= L.box[a];
    }
    for (int a = 0; a < Dim; ++a)
      if (std::abs(X(f, a) - (X(0, a) + L.dx * site[a])) > tol)
        return refuse("free particle " + std::to_string(f) + " is off its site of an " + box_text + " box of spacing " +
                      format_number(L.dx, 6) + " in DOF order (x fastest)");
  }

  // The offset set of the central free particle.
  const NeighbourList& nl = d.neighbours;
  long centre_f = 0;
  for (int a = Dim - 1; a >= 0; --a) centre_f = centre_f * L.box[a] + L.box[a] / 2;
  const int centre = d.free[centre_f];
  L.volume = p.volume[centre];
  // Offset of neighbour j of i in lattice units; false when j is off a site or of another volume.
  const auto offset = [&](int i, int j, std::array<int, Dim>& o) {
    for (int a = 0; a < Dim; ++a) {
      const double t = (p.x(j, a) - p.x(i, a)) / L.dx;
      o[a] = static_cast<int>(std::lround(t));
      if (std::abs(p.x(j, a) - p.x(i, a) - o[a] * L.dx) > tol) return false;
    }
    return std::abs(p.volume[j] - L.volume) <= 1e-12 * std::abs(L.volume);
  };
  std::vector<std::array<int, Dim>> set;
  for (long k = nl.offsets[centre]; k < nl.offsets[centre + 1]; ++k) {
    std::array<int, Dim> o;
    if (!offset(centre, nl.indices[k], o))
      return refuse("neighbour " + std::to_string(nl.indices[k]) + " of free particle " + std::to_string(centre) +
                    " is off the lattice or of another volume");
    bool self = true;
    for (int a = 0; a < Dim; ++a) self = self && o[a] == 0;
    if (self && nl.indices[k] != centre)
      return refuse("particles " + std::to_string(centre) + " and " + std::to_string(nl.indices[k]) + " share a site");
    if (self) continue;
    set.push_back(o);
    for (int a = 0; a < Dim; ++a) L.reach = std::max(L.reach, std::abs(o[a]));
  }
  const int w = 2 * L.reach + 1;
  const auto table_index = [&](const std::array<int, Dim>& o) {
    long t = 0;
    for (int a = Dim - 1; a >= 0; --a) t = t * w + o[a] + L.reach;
    return t;
  };
  long cells = 1;
  for (int a = 0; a < Dim; ++a) cells *= w;
  std::vector<int> id(cells, -1);
  for (size_t s = 0; s < set.size(); ++s) id[table_index(set[s])] = static_cast<int>(s);
  for (const auto& o : set) {
    std::array<int, Dim> m;
    for (int a = 0; a < Dim; ++a) m[a] = -o[a];
    if (id[table_index(m)] < 0)
      return refuse("the neighbour offsets of free particle " + std::to_string(centre) + " are not symmetric");
    int last = Dim - 1;
    while (o[last] == 0) --last;
    if (o[last] > 0) L.half.push_back(o);
  }
  std::sort(L.half.begin(), L.half.end(),
            [&](const auto& a, const auto& b) { return table_index(a) < table_index(b); });

  // Every free row has exactly this set (so is complete: no neighbour missing, none extra).
  std::vector<char> bad(nf, 0);
  const long want = static_cast<long>(set.size()) + 1;
#pragma omp parallel for schedule(static) num_threads(threads_for(nf))
  for (long f = 0; f < nf; ++f) {
    const int i = d.free[f];
    if (nl.offsets[i + 1] - nl.offsets[i] != want) {
      bad[f] = 1;
      continue;
    }
    std::vector<char> seen(set.size() + 1, 0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1] && !bad[f]; ++k) {
      std::array<int, Dim> o;
      bool in = offset(i, nl.indices[k], o);
      int slot = static_cast<int>(set.size());  // the self pair
      for (int a = 0; a < Dim && in; ++a) in = std::abs(o[a]) <= L.reach;
      if (in && o != std::array<int, Dim>{})
        slot = id[table_index(o)];
      else if (in)
        in = nl.indices[k] == i;
      if (!in || slot < 0 || seen[slot])
        bad[f] = 1;
      else
        seen[slot] = 1;
    }
  }
  for (long f = 0; f < nf; ++f)
    if (bad[f])
      return refuse("free particle " + std::to_string(d.free[f]) + " has another neighbour set than free particle " +
                    std::to_string(centre) + " (incomplete near a free surface, or off the lattice)");
  return L;
}

template <int Dim>
double MatrixFreeLinearisation<Dim>::bytes_of(const Discretisation<Dim>& d, const Lattice* L) {
  const double n = d.size(), nf = d.free_count(), pairs = d.neighbours.nonzeros();
  constexpr double S = kSymmetric;
  if (L) {
    // free index and positions, the padded grids of x and sigma, the offset tables
    long sites = 1;
    for (int a = 0; a < Dim; ++a) sites *= L->box[a] + 4 * L->reach;
    const double grid = static_cast<double>(component_stride(sites));
    const double half = static_cast<double>(L->half.size());
    return 4 * nf + 8 * Dim * nf + 8 * (Dim + S) * grid + half * (8 + 8 * Dim + 8 * Dim * Dim);
  }
  const double free_pairs = free_row_pairs(d);
  // CSR (8 per offset, 4 per index), G pairs and row sums, free map and stress rows, H of the free rows with eta,
  // the stress buffer, the free positions.
  return 8 * (n + 1) + 4 * pairs + 8 * Dim * pairs + 8 * Dim * n + 4 * (2 * n + nf) + 8 * (nf + 1) +
         8 * S * free_pairs + 8 * S * nf + 8 * S * n + 8 * Dim * nf;
}

template <int Dim>
std::string MatrixFreeLinearisation<Dim>::lattice_refusal(const Discretisation<Dim>& d) {
  return find_lattice(d).refusal;
}

template <>
Eigen::Matrix2d prestress<2>(PreStrainKind kind, const ElasticMaterial& material) {
  return PreStrain{kind, 1.0}.stress(material);
}

template <>
Eigen::Matrix3d prestress<3>(PreStrainKind kind, const ElasticMaterial& m) {
  const double lam = m.lambda(), mu = m.mu();
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  if (kind == PreStrainKind::Isotropic)
    s.diagonal().setConstant(3 * lam + 2 * mu);
  else
    s.diagonal() << lam + 2 * mu, lam, lam;
  return s;
}

template <int Dim>
double MatrixFreeLinearisation<Dim>::estimated_bytes(const Discretisation<Dim>& d, MatrixFreeStorage storage) {
  if (storage == MatrixFreeStorage::PerPair) return bytes_of(d, nullptr);
  const Lattice L = find_lattice(d);
  return bytes_of(d, L.refusal.empty() ? &L : nullptr);
}

template <int Dim>
MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const Discretisation<Dim>& d, const Operators<Dim>& ops,
                                                      const ElasticMaterial& material, MomentumForm form,
                                                      PreStrainKind kind) {
  material.validate("MatrixFreeLinearisation");
  check_operators(d, ops, "MatrixFreeLinearisation");
  build(d, &ops, material, form, kind, MatrixFreeStorage::PerPair);
}

template <int Dim>
MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const Discretisation<Dim>& d, const ElasticMaterial& material,
                                                      MomentumForm form, PreStrainKind kind,
                                                      MatrixFreeStorage storage) {
  material.validate("MatrixFreeLinearisation");
  if (d.neighbours.radius + 1e-12 * d.h < d.kernel.support_radius(d.h) * (1 - 1e-12))
    throw std::invalid_argument("MatrixFreeLinearisation: neighbour radius " + format_number(d.neighbours.radius) +
                                " is smaller than the kernel support " + format_number(d.kernel.support_radius(d.h)));
  build(d, nullptr, material, form, kind, storage);
}

template <int Dim>
template <int D>
requires(D == 2 && D == Dim) MatrixFreeLinearisation<Dim>::MatrixFreeLinearisation(const ElasticForm2D& force)
    : MatrixFreeLinearisation(covered_discretisation(force), force.material(), force.form(), force.prestrain().kind) {}

template <int Dim>
void MatrixFreeLinearisation<Dim>::build(const Discretisation<Dim>& d, const Operators<Dim>* ops,
                                         const ElasticMaterial& material, MomentumForm form, PreStrainKind kind,
                                         MatrixFreeStorage storage) {
  Lattice lattice;
  if (storage != MatrixFreeStorage::PerPair) {
    lattice = find_lattice(d);
    if (storage == MatrixFreeStorage::ByOffset && !lattice.refusal.empty())
      throw std::invalid_argument("MatrixFreeLinearisation: by-offset storage needs a perfect lattice: " +
                                  lattice.refusal);
  }
  const bool by_offset = storage != MatrixFreeStorage::PerPair && lattice.refusal.empty();
  require_memory(bytes_of(d, by_offset ? &lattice : nullptr),
                 "MatrixFreeLinearisation: " + std::to_string(d.dofs()) + " DOFs");
  const int n = d.size(), nf = d.free_count();
  const NeighbourList& nl = d.neighbours;
  const bool cons = form == MomentumForm::Conservative;
  m_form = form;
  m_inv_rho = 1.0 / material.density();
  m_lambda = material.lambda();
  m_mu = material.mu();
  m_alpha = cons ? 1.0 : momentum_form_alpha(form);
  m_a1_factor = cons ? 2.0 * m_inv_rho : (1.0 + momentum_form_alpha(form)) * m_inv_rho;
  m_s0 = prestress<Dim>(kind, material);
  m_free = d.free;
  m_free_positions = d.free_positions();
  if (by_offset) {
    m_storage = MatrixFreeStorage::ByOffset;
    build_by_offset(d, lattice);
    m_complete = true;  // g = 0 exactly on every free row (header comment)
    m_periodic = false;
    m_symmetric = cons || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic;  // equal volumes
    return;
  }
  m_storage = MatrixFreeStorage::PerPair;
  m_free_slot = d.free_slot;
  m_offsets = nl.offsets;
  m_indices = nl.indices;

  // Pair values: copied from the operators, or computed as assemble_operators does (without its matrices).
  const long pairs = nl.nonzeros();
  m_h_offsets.assign(nf + 1, 0);
  for (int f = 0; f < nf; ++f) m_h_offsets[f + 1] = m_h_offsets[f] + nl.count(d.free[f]);
  m_g.resize(Dim * pairs);
  m_h.resize(kSymmetric * m_h_offsets[nf]);
  const ParticleSet<Dim>& p = d.particles;
  std::array<double, Dim> box;
  for (int a = 0; a < Dim; ++a) box[a] = p.box_hi[a] - p.box_lo[a];
  const double d20 = d.kernel.d2(0.0, d.h);
#pragma omp parallel for schedule(static) num_threads(threads_for(n))
  for (int i = 0; i < n; ++i) {
    const int fi = m_free_slot[i];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      double* g = m_g.data() + Dim * k;
      double* h = fi >= 0 ? m_h.data() + kSymmetric * (m_h_offsets[fi] + k - nl.offsets[i]) : nullptr;
      if (ops) {
        for (int a = 0; a < Dim; ++a) g[a] = ops->G[a].valuePtr()[k];
        if (h)
          for (int a = 0; a < Dim; ++a)
            for (int b = a; b < Dim; ++b) h[upper<Dim>(a, b)] = ops->H[a][b].valuePtr()[k];
        continue;
      }
      std::array<std::array<double, Dim>, Dim> hk{};
      std::fill(g, g + Dim, 0.0);
      const int j = nl.indices[k];
      if (i != j) {  // G_ii = 0 and H_ii = 0
        const Eigen::Matrix<double, 1, Dim> dx =
            detail::pair_separation<Dim, double>(p, static_cast<const Eigen::MatrixXd*>(nullptr), box, i, j);
        double r2 = 0;
        for (int a = 0; a < Dim; ++a) r2 += dx[a] * dx[a];
        if (r2 == 0.0) {
          for (int a = 0; a < Dim; ++a) hk[a][a] = d20 * p.volume[j];
        } else {
          detail::pair_derivatives<Dim, double>(d.kernel, d.h, dx, r2, std::sqrt(r2), p.volume[j], g, &hk);
        }
      }
      if (h)
        for (int a = 0; a < Dim; ++a)
          for (int b = a; b < Dim; ++b) h[upper<Dim>(a, b)] = hk[a][b];
    }
  }

  m_gsum.assign(Dim * n, 0.0);
  double gmax = 0;
  for (int i = 0; i < n; ++i)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      for (int a = 0; a < Dim; ++a) {
        m_gsum[Dim * i + a] += m_g[Dim * k + a];
        gmax = std::max(gmax, std::abs(m_g[Dim * k + a]));
      }

  std::vector<char> needed(n, 0);
  for (int i : d.free)
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) needed[nl.indices[k]] = 1;
  m_stress_rows.clear();
  for (int j = 0; j < n; ++j)
    if (needed[j]) m_stress_rows.push_back(j);

  m_eta.assign(kSymmetric * nf, 0.0);
  for (int f = 0; f < nf; ++f) {
    const int i = d.free[f];
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const long t = kSymmetric * (m_h_offsets[f] + k - nl.offsets[i]);
      for (int c = 0; c < kSymmetric; ++c) m_eta[kSymmetric * f + c] += m_h[t + c];  // all neighbours, fixed ones too
    }
  }
  m_sigma.assign(kSymmetric * n, 0.0);

  // The flags of analytic_jacobian_2d, with the same tolerances.
  bool complete = true, equal_volumes = true;
  for (int i : d.free) {
    for (int a = 0; a < Dim; ++a)
      if (std::abs(m_gsum[Dim * i + a]) > 1e-10 * gmax) complete = false;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k)
      if (std::abs(d.particles.volume[nl.indices[k]] - d.particles.volume[i]) > 1e-12 * std::abs(d.particles.volume[i]))
        equal_volumes = false;
  }
  m_complete = complete;
  m_periodic = true;
  for (int a = 0; a < Dim; ++a) m_periodic = m_periodic && d.particles.periodic[a];
  m_symmetric = complete && equal_volumes && (cons || form == MomentumForm::Minus || kind == PreStrainKind::Isotropic);
}

template <int Dim>
double MatrixFreeLinearisation<Dim>::memory_bytes() const {
  auto bytes = [](const auto& v) { return static_cast<double>(v.capacity() * sizeof(v[0])); };
  return bytes(m_free) + bytes(m_free_slot) + bytes(m_offsets) + bytes(m_indices) + bytes(m_g) + bytes(m_gsum) +
         bytes(m_stress_rows) + bytes(m_h_offsets) + bytes(m_h) + bytes(m_eta) + bytes(m_sigma) + bytes(m_shift) +
         bytes(m_og) + bytes(m_ob) + bytes(m_u) + bytes(m_sgrid) + 8.0 * static_cast<double>(m_free_positions.size());
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::check_vectors(const Eigen::Ref<const Eigen::VectorXd>& x,
                                                 const Eigen::Ref<Eigen::VectorXd>& y, const char* who) const {
  if (x.size() != dofs() || y.size() != dofs())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who + ": x has " + std::to_string(x.size()) +
                                " and y " + std::to_string(y.size()) + " entries, need " + std::to_string(dofs()) +
                                " (" + std::to_string(Dim) + " per free particle)");
  const double *xb = x.data(), *yb = y.data();
  if (xb < yb + y.size() && yb < xb + x.size())
    throw std::invalid_argument(std::string("MatrixFreeLinearisation::") + who +
                                ": x and y share storage (pass a separate output vector)");
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_A0(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A0");
  apply_combination(1.0, 0.0, x, y);
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_A1(const Eigen::Ref<const Eigen::VectorXd>& x,
                                            Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply_A1");
  apply_combination(0.0, 1.0, x, y);
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_A0_and_A1(double c1, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                   Eigen::Ref<Eigen::VectorXd> y0,
                                                   Eigen::Ref<Eigen::VectorXd> y1) const {
  check_vectors(x, y0, "apply_A0_and_A1");
  check_vectors(x, y1, "apply_A0_and_A1");
  check_vectors(y0, y1, "apply_A0_and_A1");
  if (m_storage != MatrixFreeStorage::ByOffset) {
    apply_combination(1.0, 0.0, x, y0);
    apply_combination(0.0, c1, x, y1);
    return;
  }
  apply_by_offset(1.0, c1, x.data(), y0.data(), y1.data());
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::apply_combination(double c0, double c1, const Eigen::Ref<const Eigen::VectorXd>& x,
                                                     Eigen::Ref<Eigen::VectorXd> y) const {
  check_vectors(x, y, "apply");
  if (m_storage == MatrixFreeStorage::ByOffset) {
    apply_by_offset(c0, c1, x.data(), y.data());
    return;
  }
  constexpr int S = kSymmetric;
  const bool with_a0 = c0 != 0.0, with_a1 = c1 != 0.0 && m_a1_factor != 0.0;
  const double* xp = x.data();
  double* yp = y.data();
  const double lam = m_lambda, mu = m_mu;
  double* sigma = m_sigma.data();

  if (with_a0) {
    // Steps 1-2 (derivation item 1): (grad x)_j^{cd} = sum_{k free} Dm^d_jk x_k^c, Dm = G - diag(g); then
    // sigma_j = C : grad x_j (C drops the antisymmetric part). Rows are independent: threads own whole rows (same
    // bits for any thread count, core/threads.hpp).
    const long rows = static_cast<long>(m_stress_rows.size());
#pragma omp parallel for schedule(static) num_threads(threads_for(rows))
    for (long s = 0; s < rows; ++s) {
      const int j = m_stress_rows[s];
      double gr[Dim][Dim] = {};  // gr[c][d]: component c, derivative d
      for (long k = m_offsets[j]; k < m_offsets[j + 1]; ++k) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double* u = xp + Dim * kf;
        const double* w = m_g.data() + Dim * k;
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d) gr[c][d] += u[c] * w[d];
      }
      const int jf = m_free_slot[j];
      if (jf >= 0) {
        const double* u = xp + Dim * jf;
        const double* sum = m_gsum.data() + Dim * j;
        for (int c = 0; c < Dim; ++c)
          for (int d = 0; d < Dim; ++d) gr[c][d] -= u[c] * sum[d];
      }
      double tr = gr[0][0];
      for (int c = 1; c < Dim; ++c) tr += gr[c][c];
      double* sj = sigma + S * j;
      for (int c = 0; c < Dim; ++c) sj[c] = lam * tr + 2 * mu * gr[c][c];
      for (int c = 0; c < Dim; ++c)
        for (int d = c + 1; d < Dim; ++d) sj[voigt(c, d)] = mu * (gr[c][d] + gr[d][c]);
    }
  }

  const int nf = free_count();
  const Stress& s0 = m_s0;
  const bool cons = m_form == MomentumForm::Conservative;
  // s0 v and the symmetric product M v (M stored a <= b), each component summed in ascending b.
  const auto s0_times = [&s0](const double* v, double* out) {
    for (int a = 0; a < Dim; ++a) {
      double t = s0(a, 0) * v[0];
      for (int b = 1; b < Dim; ++b) t += s0(a, b) * v[b];
      out[a] = t;
    }
  };
  const auto sym_times = [](const double* m, const double* v, int a) {
    double t = m[upper<Dim>(std::min(a, 0), std::max(a, 0))] * v[0];
    for (int b = 1; b < Dim; ++b) t += m[upper<Dim>(std::min(a, b), std::max(a, b))] * v[b];
    return t;
  };
#pragma omp parallel for schedule(static) num_threads(threads_for(nf))
  for (int f = 0; f < nf; ++f) {
    const int i = m_free[f];
    double out[Dim] = {};
    if (with_a0) {
      // Step 3 (items 2, 3): y_i^a = -(1/rho) sum_j P^b_ij sigma_j^{ab}, P = G + alpha diag(g) (G_ii = 0).
      const double* si = sigma + S * i;
      const double* gi = m_gsum.data() + Dim * i;
      double acc[Dim];
      for (int a = 0; a < Dim; ++a) {
        double t = gi[0] * si[voigt(a, 0)];
        for (int b = 1; b < Dim; ++b) t += gi[b] * si[voigt(a, b)];
        acc[a] = m_alpha * t;
      }
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k) {
        const double* sk = sigma + S * m_indices[k];
        const double* pk = m_g.data() + Dim * k;
        for (int a = 0; a < Dim; ++a) {
          double t = pk[0] * sk[voigt(a, 0)];
          for (int b = 1; b < Dim; ++b) t += pk[b] * sk[voigt(a, b)];
          acc[a] += t;
        }
      }
      for (int a = 0; a < Dim; ++a) out[a] = -c0 * m_inv_rho * acc[a];
    }
    if (with_a1) {
      // A1 x: (L v)_i = eta_i v_i - sum_{k free} H_ik v_k with v = x and, conservative, v = s0 x.
      const double* eta = m_eta.data() + S * f;
      const double* xi = xp + Dim * f;
      double vi[Dim], l[Dim], m[Dim];
      s0_times(xi, vi);
      for (int a = 0; a < Dim; ++a) {
        l[a] = sym_times(eta, xi, a);
        m[a] = sym_times(eta, vi, a);
      }
      const double* h = m_h.data() + S * m_h_offsets[f];
      for (long k = m_offsets[i]; k < m_offsets[i + 1]; ++k, h += S) {
        const int kf = m_free_slot[m_indices[k]];
        if (kf < 0) continue;
        const double* xk = xp + Dim * kf;
        for (int a = 0; a < Dim; ++a) l[a] -= sym_times(h, xk, a);
        if (cons) {
          double v[Dim];
          s0_times(xk, v);
          for (int a = 0; a < Dim; ++a) m[a] -= sym_times(h, v, a);
        }
      }
      double r[Dim];
      s0_times(l, r);
      if (cons)
        for (int a = 0; a < Dim; ++a) r[a] += m[a];
      for (int a = 0; a < Dim; ++a) out[a] -= c1 * m_a1_factor * r[a];
    }
    for (int a = 0; a < Dim; ++a) yp[Dim * f + a] = out[a];
  }
}

template <int Dim>
void MatrixFreeLinearisation<Dim>::build_by_offset(const Discretisation<Dim>& d, const Lattice& L) {
  const int r = L.reach;
  m_box = L.box;
  m_reach = r;
  long sites = 1;
  for (int a = 0; a < Dim; ++a) {
    m_stride[a] = sites;
    sites *= L.box[a] + 4 * r;
  }
  m_grid = component_stride(sites);
  const long half = static_cast<long>(L.half.size());
  m_shift.resize(half);
  m_og.resize(Dim * half);
  m_ob.resize(Dim * Dim * half);
  const bool cons = m_form == MomentumForm::Conservative;
  Stress eta = Stress::Zero();
  std::vector<Stress> hd(half);
  for (long o = 0; o < half; ++o) {
    // The pair (i, j = i + d): separation x_i - x_j = -d dx (pair_separation's sign), as the PerPair values.
    Eigen::Matrix<double, 1, Dim> sep;
    long shift = 0;
    for (int a = 0; a < Dim; ++a) {
      sep[a] = -L.half[o][a] * L.dx;
      shift += L.half[o][a] * m_stride[a];
    }
    m_shift[o] = shift;
    const double r2 = sep.squaredNorm();
    std::array<std::array<double, Dim>, Dim> hk{};
    detail::pair_derivatives<Dim, double>(d.kernel, d.h, sep, r2, std::sqrt(r2), L.volume, m_og.data() + Dim * o, &hk);
    for (int a = 0; a < Dim; ++a)
      for (int b = a; b < Dim; ++b) hd[o](a, b) = hd[o](b, a) = hk[a][b];
    eta += 2 * hd[o];  // H(-d) = H(d): both offsets of the pair
  }
  // A1 = B(0) on the diagonal, B(d) on the offsets (header comment): -m_a1_factor s0 L, conservative also L s0.
  const double f = m_a1_factor;
  m_b0 = cons ? Stress(-f * (m_s0 * eta + eta * m_s0)) : Stress(-f * m_s0 * eta);
  for (long o = 0; o < half; ++o) {
    const Stress b = cons ? Stress(f * (m_s0 * hd[o] + hd[o] * m_s0)) : Stress(f * m_s0 * hd[o]);
    for (int a = 0; a < Dim; ++a)
      for (int c = 0; c < Dim; ++c) m_ob[Dim * Dim * o + Dim * a + c] = b(a, c);
  }
  // Zero off the free box, for good: apply writes only the free sites. Huge pages (tall_block_algebra.hpp) asked
  // before the first write: the stencil sweeps read 2 |D+| streams per grid, rows apart.
  for (auto [grid, size] : {std::pair{&m_u, Dim * m_grid}, std::pair{&m_sgrid, kSymmetric * m_grid}}) {
    grid->reserve(size);
    tall::advise_huge_pages(grid->data(), sizeof(double) * size);
    grid->assign(size, 0.0);
  }
}

template <int Dim>
Linearisation assemble_by_products(const MatrixFreeLinearisation<Dim>& lin) {
  const long n = lin.dofs();
  require_memory(static_cast<double>(n) * n / 8.0,
                 "assemble_by_products: " + std::to_string(n) + " DOFs (one product per column)");
  std::vector<Eigen::Triplet<double>> t0, t1;
  Eigen::VectorXd e = Eigen::VectorXd::Zero(n), y(n);
  for (long c = 0; c < n; ++c) {
    e[c] = 1;
    lin.apply_A0(e, y);
    for (long r = 0; r < n; ++r)
      if (y[r] != 0.0) t0.emplace_back(r, c, y[r]);
    lin.apply_A1(e, y);
    for (long r = 0; r < n; ++r)
      if (y[r] != 0.0) t1.emplace_back(r, c, y[r]);
    e[c] = 0;
  }
  Linearisation out;
  out.A0.resize(n, n);
  out.A0.setFromTriplets(t0.begin(), t0.end());
  out.A1.resize(n, n);
  out.A1.setFromTriplets(t1.begin(), t1.end());
  out.dofs_per_particle = Dim;
  out.free_index = lin.free_index();
  out.x = lin.free_positions();
  out.symmetric = lin.symmetric();
  out.complete = lin.complete();
  out.periodic = lin.periodic();
  return out;
}

template class MatrixFreeLinearisation<2>;
template class MatrixFreeLinearisation<3>;
template MatrixFreeLinearisation<2>::MatrixFreeLinearisation(const ElasticForm2D& force);
template Linearisation assemble_by_products<2>(const MatrixFreeLinearisation<2>&);
template Linearisation assemble_by_products<3>(const MatrixFreeLinearisation<3>&);

}  // namespace sphstab
