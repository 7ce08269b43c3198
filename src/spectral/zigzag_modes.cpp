#include "sphstab/spectral/zigzag_modes.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

template <int Dim>
GridIndices<Dim> grid_indices(const Discretisation<Dim>& d, double dx) {
  if (!(dx > 0) || !std::isfinite(dx))
    throw std::invalid_argument("grid_indices: dx must be finite and > 0 (got " + format_number(dx) + ")");
  GridIndices<Dim> g;
  g.index.resize(d.free_count());
  for (int a = 0; a < Dim; ++a) {
    double lo = std::numeric_limits<double>::infinity();
    for (int f = 0; f < d.free_count(); ++f) lo = std::min(lo, d.particles.x(d.free[f], a));
    int hi = 0;
    for (int f = 0; f < d.free_count(); ++f) {
      const double s = (d.particles.x(d.free[f], a) - lo) / dx;
      g.index[f][a] = static_cast<int>(std::lround(s));
      if (std::abs(s - g.index[f][a]) > 1e-6)
        throw std::invalid_argument("grid_indices: free particle " + std::to_string(d.free[f]) +
                                    " is off the grid of spacing " + format_number(dx) + " along axis " +
                                    std::to_string(a));
      hi = std::max(hi, g.index[f][a]);
    }
    g.extent[a] = hi + 1;
  }
  return g;
}

template <int Dim>
double hourglass_fraction(const Eigen::VectorXd& phi, const GridIndices<Dim>& grid) {
  const auto& g = grid.index;
  const auto& n = grid.extent;
  if (phi.size() != Dim * static_cast<long>(g.size()))
    throw std::invalid_argument("hourglass_fraction: phi has " + std::to_string(phi.size()) + " entries, expected " +
                                std::to_string(Dim * g.size()) + " (Dim per free particle)");
  long cells = 1;
  for (int a = 0; a < Dim; ++a) cells *= n[a];
  std::array<std::vector<std::complex<double>>, Dim> w;  // DFT twiddles per axis
  for (int a = 0; a < Dim; ++a) {
    w[a].resize(n[a]);
    for (int q = 0; q < n[a]; ++q) w[a][q] = std::exp(std::complex<double>(0, -2 * std::numbers::pi * q / n[a]));
  }
  auto high = [](int q, int m) { return 4 * std::min(q, m - q) > m; };  // |k| > pi / 2
  auto key = [&](const std::array<int, Dim>& ix) {
    long k = 0;
    for (int a = Dim - 1; a >= 0; --a) k = k * n[a] + ix[a];
    return k;
  };
  double total = 0, hi = 0;
  for (int c = 0; c < Dim; ++c) {
    std::vector<std::complex<double>> field(cells, 0.0), tmp(cells);
    for (std::size_t f = 0; f < g.size(); ++f) field[key(g[f])] = phi[Dim * f + c];
    long stride = 1;  // separable DFT, one axis at a time (axis a has stride n_0 ... n_{a-1})
    for (int a = 0; a < Dim; stride *= n[a], ++a) {
      const int m = n[a];
      for (long k = 0; k < cells; ++k) {
        const int qk = static_cast<int>(k / stride % m);
        const long base = k - qk * stride;
        std::complex<double> s = 0;
        for (int j = 0; j < m; ++j) s += field[base + j * stride] * w[a][(static_cast<long>(qk) * j) % m];
        tmp[k] = s;
      }
      field.swap(tmp);
    }
    for (long k = 0; k < cells; ++k) {
      const double e = std::norm(field[k]);
      total += e;
      bool h = false;
      long r = k;
      for (int a = 0; a < Dim; r /= n[a], ++a) h = h || high(static_cast<int>(r % n[a]), n[a]);
      if (h) hi += e;
    }
  }
  return total > 0 ? hi / total : 0;
}

template <int Dim>
std::vector<ZigzagMode> classify_modes(const Eigen::VectorXcd& values, const Eigen::MatrixXcd& vectors,
                                       const GridIndices<Dim>& grid) {
  if (vectors.cols() != values.size())
    throw std::invalid_argument("classify_modes: " + std::to_string(values.size()) + " eigenvalues but " +
                                std::to_string(vectors.cols()) + " eigenvectors");
  std::vector<ZigzagMode> modes;
  modes.reserve(values.size());
  for (long k = 0; k < values.size(); ++k) {
    Eigen::VectorXd phi = vectors.col(k).real();
    if (phi.norm() < 1e-8) phi = vectors.col(k).imag();
    phi /= phi.norm();
    modes.push_back({values[k].real(), std::abs(values[k].imag()), hourglass_fraction<Dim>(phi, grid), phi});
  }
  std::sort(modes.begin(), modes.end(), [](const ZigzagMode& a, const ZigzagMode& b) { return a.mu < b.mu; });
  return modes;
}

template <int Dim>
std::vector<ZigzagMode> zigzag_spectrum(const Eigen::MatrixXd& A, const GridIndices<Dim>& grid) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  return classify_modes<Dim>(es.eigenvalues(), es.eigenvectors(), grid);
}

template struct GridIndices<1>;
template struct GridIndices<2>;
template GridIndices<1> grid_indices<1>(const Discretisation<1>&, double);
template GridIndices<2> grid_indices<2>(const Discretisation<2>&, double);
template double hourglass_fraction<1>(const Eigen::VectorXd&, const GridIndices<1>&);
template double hourglass_fraction<2>(const Eigen::VectorXd&, const GridIndices<2>&);
template std::vector<ZigzagMode> classify_modes<1>(const Eigen::VectorXcd&, const Eigen::MatrixXcd&,
                                                   const GridIndices<1>&);
template std::vector<ZigzagMode> classify_modes<2>(const Eigen::VectorXcd&, const Eigen::MatrixXcd&,
                                                   const GridIndices<2>&);
template std::vector<ZigzagMode> zigzag_spectrum<1>(const Eigen::MatrixXd&, const GridIndices<1>&);
template std::vector<ZigzagMode> zigzag_spectrum<2>(const Eigen::MatrixXd&, const GridIndices<2>&);

}  // namespace sphstab
