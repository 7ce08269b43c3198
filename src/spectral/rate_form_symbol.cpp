#include "sphstab/spectral/rate_form_symbol.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"

namespace sphstab {

namespace {

template <int Dim>
using Key = std::array<long, Dim>;

/// Lattice offsets as integer keys (offsets on one lattice differ by at least its row step >> 1e-6 dx).
template <int Dim>
Key<Dim> key_of(const Eigen::Matrix<double, Dim, 1>& d, double spacing) {
  Key<Dim> key{};
  for (int a = 0; a < Dim; ++a) key[a] = std::lround(d[a] / (1e-6 * spacing));
  return key;
}

}  // namespace

template <int Dim>
Eigen::MatrixXcd RateFormSymbol<Dim>::at(const Wavevector& k) const {
  Eigen::MatrixXcd s = Eigen::MatrixXcd::Zero(states, states);
  for (std::size_t j = 0; j < blocks.size(); ++j)
    s += std::polar(1.0, k.dot(offsets[j])) * blocks[j].template cast<std::complex<double>>();
  return s;
}

template <int Dim>
RateFormSymbol<Dim> rate_form_symbol(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y) {
  const ParticleSet<Dim>& p = scheme.discretisation().particles;
  const int n = p.size();
  const int s = 2 * Dim + 1 + RateFormScheme<Dim>::kStress;
  if (y.size() != scheme.size())
    throw std::invalid_argument("rate_form_symbol: state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  for (int a = 0; a < Dim; ++a)
    if (!p.periodic[a])
      throw std::invalid_argument("rate_form_symbol: the lattice is not periodic in axis " + std::to_string(a) +
                                  " (a Fourier symbol needs a periodic lattice)");
  if (p.count(Role::Fixed) > 0)
    throw std::invalid_argument("rate_form_symbol: " + std::to_string(p.count(Role::Fixed)) +
                                " fixed particles (a Fourier symbol needs every particle free)");
  const double dx = p.spacing > 0 ? p.spacing : 1.0;

  // Column owner: particle and component of every state.
  std::vector<int> owner(scheme.size(), -1);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < s; ++c) owner[scheme.position_offset(i) + c] = i;

  const SparseMatrix<> J = jacobian(scheme, y);
  const double scale = std::max(J.nonZeros() ? J.coeffs().cwiseAbs().maxCoeff() : 0.0, 1e-300);
  if (!J.coeffs().allFinite()) throw std::invalid_argument("rate_form_symbol: non-finite Jacobian at the state");

  // The structural stencil (every coupling the scheme's pattern allows, zero or not) against the box.
  const SparsityPattern pattern = scheme.pattern();
  RateFormSymbol<Dim> out;
  out.states = s;
  Eigen::Matrix<double, Dim, 1> row_step = Eigen::Matrix<double, Dim, 1>::Constant(INFINITY);
  for (int j = 1; j < n; ++j) {
    const auto d = p.separation(j, 0);
    for (int a = 0; a < Dim; ++a)
      if (std::abs(d[a]) > 1e-9 * dx) row_step[a] = std::min(row_step[a], std::abs(d[a]));
  }
  for (int r = scheme.position_offset(0); r < scheme.position_offset(0) + s; ++r)
    for (long e = pattern.offsets[r]; e < pattern.offsets[r + 1]; ++e) {
      const auto d = p.separation(owner[pattern.indices[e]], 0);
      for (int a = 0; a < Dim; ++a) out.stencil_extent[a] = std::max(out.stencil_extent[a], std::abs(d[a]));
    }
  const auto box = p.box_length();
  for (int a = 0; a < Dim; ++a)
    if (2 * out.stencil_extent[a] + 1.5 * row_step[a] > box[a] * (1 + 1e-12))
      throw std::invalid_argument("rate_form_symbol: periodic box " + format_number(box[a] / dx, 6) + " dx in axis " +
                                  std::to_string(a) + ", the stencil reaches " +
                                  format_number(out.stencil_extent[a] / dx, 6) +
                                  " dx: particles would couple through two images; use a box longer than " +
                                  format_number((2 * out.stencil_extent[a] + 1.5 * row_step[a]) / dx, 6) + " dx");

  // Block rows of every particle, keyed by offset; particle 0's is the symbol.
  auto block_row = [&](int i) {
    std::map<Key<Dim>, std::pair<int, Eigen::MatrixXd>> row;
    const int r0 = scheme.position_offset(i);
    for (int r = 0; r < s; ++r)
      for (SparseMatrix<>::InnerIterator it(J, r0 + r); it; ++it) {
        const int j = owner[it.col()];
        auto [pos, fresh] =
            row.try_emplace(key_of<Dim>(Eigen::Matrix<double, Dim, 1>(p.separation(j, i).transpose()), dx), j,
                            Eigen::MatrixXd::Zero(s, s));
        pos->second.second(r, it.col() - scheme.position_offset(j)) = it.value();
      }
    return row;
  };
  const auto reference = block_row(0);
  for (const auto& [key, entry] : reference) {
    out.offsets.push_back(p.separation(entry.first, 0).transpose());
    out.blocks.push_back(entry.second);
  }
  double residual = 0;
  for (int i = 1; i < n; ++i) {
    const auto row = block_row(i);
    for (const auto& [key, entry] : row) {
      const auto ref = reference.find(key);
      residual = std::max(residual,
                          (ref == reference.end() ? entry.second : Eigen::MatrixXd(entry.second - ref->second.second))
                              .cwiseAbs()
                              .maxCoeff());
    }
    for (const auto& [key, entry] : reference)
      if (!row.count(key)) residual = std::max(residual, entry.second.cwiseAbs().maxCoeff());
  }
  out.invariance_residual = residual / scale;
  if (out.invariance_residual > 1e-9)
    throw std::invalid_argument("rate_form_symbol: J is not translation invariant (block rows differ by " +
                                format_number(out.invariance_residual, 3) +
                                " relative): the state is not uniform or the lattice has more than one particle "
                                "per cell");
  return out;
}

template <int Dim>
RateFormDispersion rate_form_dispersion(const RateFormSymbol<Dim>& symbol,
                                        const typename RateFormSymbol<Dim>::Wavevector& k) {
  if (!k.allFinite()) throw std::invalid_argument("rate_form_dispersion: non-finite wavevector");
  const Eigen::MatrixXcd S = symbol.at(k);
  const int s = symbol.states;
  RateFormDispersion out;
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> full(S, false);
  out.lambda = full.eigenvalues();
  std::sort(out.lambda.data(), out.lambda.data() + s,
            [](std::complex<double> a, std::complex<double> b) { return std::abs(a) > std::abs(b); });
  out.growth_rate = out.lambda.real().maxCoeff();  // replaced by the acoustic roots when the structure holds
  out.slaved_lambda = s > 2 * Dim ? out.lambda.tail(s - 2 * Dim).cwiseAbs().maxCoeff() : 0.0;

  // The at-rest reduction (x: 0..Dim-1, v: Dim..2Dim-1, q: the rest).
  const double scale = std::max(S.cwiseAbs().maxCoeff(), 1e-300);
  const int q = s - 2 * Dim;
  const double zero =
      std::max({S.topLeftCorner(Dim, Dim).cwiseAbs().maxCoeff(), S.topRightCorner(Dim, q).cwiseAbs().maxCoeff(),
                S.bottomLeftCorner(q, Dim).cwiseAbs().maxCoeff(), S.bottomRightCorner(q, q).cwiseAbs().maxCoeff()});
  out.structure_residual = zero / scale;
  const Eigen::MatrixXcd X = S.block(0, Dim, Dim, Dim), Jvx = S.block(Dim, 0, Dim, Dim),
                         Jvv = S.block(Dim, Dim, Dim, Dim), Jvq = S.block(Dim, 2 * Dim, Dim, q),
                         Jqv = S.block(2 * Dim, Dim, q, Dim);
  const Eigen::MatrixXcd B = Jvx * X + Jvq * Jqv;
  out.omega2.resize(Dim);
  out.polarisation.resize(Dim, Dim);
  const bool at_rest = out.structure_residual <= 1e-12;
  if (Jvv.cwiseAbs().maxCoeff() <= 1e-14 * scale) {
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> reduced(B, true);
    out.omega2 = -reduced.eigenvalues();
    out.polarisation = reduced.eigenvectors();
    if (at_rest) {
      out.growth_rate = 0;
      for (int m = 0; m < Dim; ++m) out.growth_rate = std::max(out.growth_rate, std::sqrt(-out.omega2[m]).real());
    }
  } else {  // companion [[0, I], [B, Jvv]]: per velocity mode the root of larger real part
    Eigen::MatrixXcd C = Eigen::MatrixXcd::Zero(2 * Dim, 2 * Dim);
    C.topRightCorner(Dim, Dim).setIdentity();
    C.bottomLeftCorner(Dim, Dim) = B;
    C.bottomRightCorner(Dim, Dim) = Jvv;
    Eigen::ComplexEigenSolver<Eigen::MatrixXcd> companion(C, true);
    std::vector<int> order(2 * Dim);
    for (int i = 0; i < 2 * Dim; ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return companion.eigenvalues()[a].imag() > companion.eigenvalues()[b].imag(); });
    if (at_rest) out.growth_rate = companion.eigenvalues().real().maxCoeff();
    for (int m = 0; m < Dim; ++m) {  // the Dim roots with Im lambda >= 0 (waves moving forward)
      const std::complex<double> l = companion.eigenvalues()[order[m]];
      out.omega2[m] = -l * l;
      out.polarisation.col(m) = companion.eigenvectors().col(order[m]).head(Dim).normalized();
    }
  }
  std::vector<int> order(Dim);
  for (int i = 0; i < Dim; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return out.omega2[a].real() > out.omega2[b].real(); });
  Eigen::VectorXcd w(Dim);
  Eigen::MatrixXcd pol(Dim, Dim);
  for (int i = 0; i < Dim; ++i) {
    w[i] = out.omega2[order[i]];
    pol.col(i) = out.polarisation.col(order[i]).normalized();
  }
  out.omega2 = w;
  out.polarisation = pol;
  return out;
}

template struct RateFormSymbol<1>;
template struct RateFormSymbol<2>;
template RateFormSymbol<1> rate_form_symbol(const RateFormScheme<1>&, const Eigen::VectorXd&);
template RateFormSymbol<2> rate_form_symbol(const RateFormScheme<2>&, const Eigen::VectorXd&);
template RateFormDispersion rate_form_dispersion(const RateFormSymbol<1>&, const RateFormSymbol<1>::Wavevector&);
template RateFormDispersion rate_form_dispersion(const RateFormSymbol<2>&, const RateFormSymbol<2>::Wavevector&);

}  // namespace sphstab
