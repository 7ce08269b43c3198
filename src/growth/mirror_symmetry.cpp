#include "sphstab/growth/mirror_symmetry.hpp"

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace sphstab {

MirrorSymmetry mirror_symmetry(const Eigen::VectorXd& positions, const Eigen::Vector2d& centre, double tolerance) {
  const char* who = "mirror_symmetry";
  if (positions.size() % 2 != 0 || positions.size() == 0)
    throw std::invalid_argument(std::string(who) + ": positions need 2 entries per particle (got " +
                                std::to_string(positions.size()) + ")");
  if (!(tolerance > 0)) throw std::invalid_argument(std::string(who) + ": tolerance must be > 0");
  const int n = static_cast<int>(positions.size() / 2);
  // Bucket positions on a grid of the tolerance for O(n log n) matching.
  std::map<std::pair<long, long>, std::vector<int>> grid;
  auto key = [&](double x, double y) { return std::make_pair(std::lround(x / tolerance), std::lround(y / tolerance)); };
  for (int p = 0; p < n; ++p) grid[key(positions[2 * p], positions[2 * p + 1])].push_back(p);
  auto find = [&](double x, double y) -> int {
    const auto k = key(x, y);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        auto it = grid.find({k.first + dx, k.second + dy});
        if (it == grid.end()) continue;
        for (int q : it->second)
          if (std::abs(positions[2 * q] - x) <= tolerance && std::abs(positions[2 * q + 1] - y) <= tolerance) return q;
      }
    return -1;
  };
  MirrorSymmetry s;
  s.centre = centre;
  s.mirror_x.resize(n);
  s.mirror_y.resize(n);
  for (int p = 0; p < n; ++p) {
    const double x = positions[2 * p], y = positions[2 * p + 1];
    s.mirror_x[p] = find(2 * centre[0] - x, y);
    s.mirror_y[p] = find(x, 2 * centre[1] - y);
    if (s.mirror_x[p] < 0 || s.mirror_y[p] < 0)
      throw std::invalid_argument(std::string(who) + ": particle " + std::to_string(p) +
                                  " has no mirror partner (the set is not symmetric about the centre)");
  }
  return s;
}

Eigen::VectorXd reflect(const MirrorSymmetry& s, int axis, const Eigen::VectorXd& f) {
  if (axis != 0 && axis != 1) throw std::invalid_argument("reflect: axis must be 0 or 1");
  if (f.size() != 2 * s.size())
    throw std::invalid_argument("reflect: field has " + std::to_string(f.size()) + " entries, expected " +
                                std::to_string(2 * s.size()));
  const std::vector<int>& m = axis == 0 ? s.mirror_x : s.mirror_y;
  Eigen::VectorXd g(f.size());
  for (int p = 0; p < s.size(); ++p)
    for (int c = 0; c < 2; ++c) g[2 * p + c] = (c == axis ? -1.0 : 1.0) * f[2 * m[p] + c];
  return g;
}

namespace {
void check_parity(int px, int py, const char* who) {
  if ((px != 1 && px != -1) || (py != 1 && py != -1))
    throw std::invalid_argument(std::string(who) + ": parities must be +1 or -1 (got " + std::to_string(px) + ", " +
                                std::to_string(py) + ")");
}
/// P f = (1/4)(f + px T_x f + py T_y f + px py T_x T_y f)
Eigen::VectorXd project(const MirrorSymmetry& s, int px, int py, const Eigen::VectorXd& f) {
  const Eigen::VectorXd tx = reflect(s, 0, f);
  return 0.25 * (f + px * tx + py * reflect(s, 1, f) + px * py * reflect(s, 1, tx));
}
}  // namespace

Eigen::MatrixXd symmetry_basis(const MirrorSymmetry& s, int px, int py) {
  check_parity(px, py, "symmetry_basis");
  const int n = s.size();
  std::vector<Eigen::VectorXd> cols;
  std::vector<char> done(n, 0);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(2 * n);
  for (int p = 0; p < n; ++p) {
    if (done[p]) continue;
    const int orbit[4] = {p, s.mirror_x[p], s.mirror_y[p], s.mirror_y[s.mirror_x[p]]};
    for (int q : orbit) done[q] = 1;
    for (int c = 0; c < 2; ++c) {
      e[2 * p + c] = 1;
      Eigen::VectorXd v = project(s, px, py, e);
      e[2 * p + c] = 0;
      const double norm = v.norm();
      if (norm > 1e-12) cols.push_back(v / norm);  // orbits and components have disjoint supports: orthonormal
    }
  }
  Eigen::MatrixXd Q(2 * n, static_cast<Eigen::Index>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) Q.col(static_cast<Eigen::Index>(k)) = cols[k];
  return Q;
}

double class_share(const MirrorSymmetry& s, int px, int py, const Eigen::VectorXd& f) {
  check_parity(px, py, "class_share");
  const double total = f.squaredNorm();
  return total > 0 ? project(s, px, py, f).squaredNorm() / total : 0.0;
}

double commutation_error(const MirrorSymmetry& s, const SparseMatrix<>& A) {
  const int n = 2 * s.size();
  if (A.rows() != n || A.cols() != n)
    throw std::invalid_argument("commutation_error: A must be " + std::to_string(n) + " x " + std::to_string(n));
  const Eigen::MatrixXd Ad(A);
  const double norm = Ad.norm();
  if (!(norm > 0)) return 0.0;
  double worst = 0;
  for (int axis = 0; axis < 2; ++axis) {
    Eigen::MatrixXd TA(n, n), AT(n, n);
    for (int k = 0; k < n; ++k) TA.col(k) = reflect(s, axis, Ad.col(k));
    // (A T)^T = T^T A^T and T^T = T (an involution that is also orthogonal)
    const Eigen::MatrixXd At = Ad.transpose();
    for (int k = 0; k < n; ++k) AT.col(k) = reflect(s, axis, At.col(k));
    worst = std::max(worst, (TA - AT.transpose()).norm() / norm);
  }
  return worst;
}

}  // namespace sphstab
