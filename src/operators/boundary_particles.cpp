#include "sphstab/operators/boundary_particles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

/// e_i of (2.51) over the neighbours j != i of i for which `use(j)`.
template <int Dim, class Use>
Eigen::Matrix<double, 1, Dim> gradient_sum(const ParticleSet<Dim>& p, const Kernel<Dim>& kernel, double h,
                                           const NeighbourList& nl, int i, Use&& use) {
  Eigen::Matrix<double, 1, Dim> e = Eigen::Matrix<double, 1, Dim>::Zero();
  for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
    const int j = nl.indices[k];
    if (j == i || !use(j)) continue;
    const Eigen::Matrix<double, 1, Dim> r = p.separation(i, j);
    const double rn = r.norm();
    if (rn > 0) e += kernel.d1(rn, h) / rn * r;  // grad_i W(x_i - x_j) = W'(r) r / |r|
  }
  return e;
}

}  // namespace

template <int Dim>
BoundaryParticles<Dim> boundary_particles(const ParticleSet<Dim>& p, const Kernel<Dim>& kernel, double h,
                                          const NeighbourList& nl, const BoundaryDetectionOptions& o) {
  if (!(o.outer_ratio > 0 && o.outer_ratio < 1))
    throw std::invalid_argument("boundary_particles: outer_ratio must be in (0, 1) (got " +
                                format_number(o.outer_ratio) + ")");
  if (!(o.exclusion_ratio >= 0 && std::isfinite(o.exclusion_ratio)))
    throw std::invalid_argument("boundary_particles: exclusion_ratio must be >= 0 and finite (got " +
                                format_number(o.exclusion_ratio) + ")");
  if (o.max_passes < 1) throw std::invalid_argument("boundary_particles: max_passes must be >= 1");
  const int n = p.size();
  if (n == 0) throw std::domain_error("boundary_particles: no particles");
  BoundaryParticles<Dim> b;
  b.layer.assign(n, -1);
  b.normal = Eigen::Matrix<double, Eigen::Dynamic, Dim>::Zero(n, Dim);
  b.e_norm.resize(n);
  Eigen::Matrix<double, Eigen::Dynamic, Dim> e(n, Dim);
  for (int i = 0; i < n; ++i) {
    e.row(i) = gradient_sum(p, kernel, h, nl, i, [](int) { return true; });
    b.e_norm[i] = e.row(i).norm();
  }
  const double emax = b.e_norm.maxCoeff();
  // A full neighbourhood sums to rounding (~1e-16 of one term |W'(h)|): below 1e-10 of it there is no boundary.
  if (!(emax > 1e-10 * std::abs(kernel.d1(h, h))))
    throw std::domain_error("boundary_particles: no boundary (max |e_i| = " + format_number(emax) + " over " +
                            std::to_string(n) + " particles: every neighbourhood is full, e.g. a periodic set)");
  const double threshold = o.outer_ratio * emax;
  for (int i = 0; i < n; ++i)
    if (b.e_norm[i] > threshold) {
      b.layer[i] = 0;
      b.normal.row(i) = -e.row(i) / b.e_norm[i];
    }
  // Candidates (2.53): non-boundary neighbours of the outer layer, with exclusion_ratio > 0 only the kernel-deficient
  // ones; |e| below 1e-10 emax is rounding of a full neighbourhood and counts as 0 (also in min |e|).
  const double floor = 1e-10 * emax;
  double emin = emax;
  for (int i = 0; i < n; ++i) emin = std::min(emin, b.e_norm[i] > floor ? b.e_norm[i] : 0.0);
  auto deficient = [&](int j) {
    return o.exclusion_ratio == 0 || (b.e_norm[j] > floor && b.e_norm[j] > o.exclusion_ratio * emin);
  };
  std::vector<char> candidate(n, 0);
  for (int i = 0; i < n; ++i) {
    if (b.layer[i] != 0) continue;
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (b.layer[j] < 0 && deficient(j)) candidate[j] = 1;
    }
  }
  b.layers = 1;
  for (int pass = 1;; ++pass) {
    std::vector<int> joined;
    for (int i = 0; i < n; ++i) {
      if (!candidate[i]) continue;
      const Eigen::Matrix<double, 1, Dim> ei = gradient_sum(p, kernel, h, nl, i, [&](int j) { return b.layer[j] < 0; });
      const double en = ei.norm();
      if (en > threshold) {
        joined.push_back(i);
        b.normal.row(i) = -ei / en;
      }
    }
    if (joined.empty()) break;
    b.passes = pass;
    if (pass > o.max_passes)
      throw std::domain_error("boundary_particles: loop guard: " + std::to_string(o.max_passes) +
                              " passes with candidates still joining (" + std::to_string(joined.size()) +
                              " in the last pass)");
    for (int i : joined) b.layer[i] = pass, candidate[i] = 0;
    b.layers = pass + 1;
  }
  b.candidates_left = static_cast<int>(std::count(candidate.begin(), candidate.end(), 1));
  for (int i = 0; i < n; ++i)
    if (b.layer[i] >= 0) b.particles.push_back(i);
  return b;
}

template <int Dim>
void set_manual_normals(BoundaryParticles<Dim>& b, const Eigen::Matrix<double, Eigen::Dynamic, Dim>& normals) {
  if (normals.rows() != static_cast<Eigen::Index>(b.particles.size()))
    throw std::invalid_argument("set_manual_normals: " + std::to_string(normals.rows()) + " normals for " +
                                std::to_string(b.particles.size()) + " boundary particles");
  for (std::size_t k = 0; k < b.particles.size(); ++k) {
    const double len = normals.row(k).norm();
    if (!(len > 0) || !std::isfinite(len))
      throw std::invalid_argument("set_manual_normals: the normal of boundary particle " +
                                  std::to_string(b.particles[k]) + " has length " + format_number(len));
  }
  for (std::size_t k = 0; k < b.particles.size(); ++k)
    b.normal.row(b.particles[k]) = normals.row(k) / normals.row(k).norm();
}

template BoundaryParticles<1> boundary_particles(const ParticleSet<1>&, const Kernel<1>&, double, const NeighbourList&,
                                                 const BoundaryDetectionOptions&);
template BoundaryParticles<2> boundary_particles(const ParticleSet<2>&, const Kernel<2>&, double, const NeighbourList&,
                                                 const BoundaryDetectionOptions&);
template void set_manual_normals(BoundaryParticles<1>&, const Eigen::Matrix<double, Eigen::Dynamic, 1>&);
template void set_manual_normals(BoundaryParticles<2>&, const Eigen::Matrix<double, Eigen::Dynamic, 2>&);

}  // namespace sphstab
