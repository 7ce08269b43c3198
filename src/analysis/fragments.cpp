#include "sphstab/analysis/fragments.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "sphstab/core/length_scale.hpp"

namespace sphstab {

namespace {

/// Union-find over 0 .. n-1: path halving, union by size.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : m_parent(n), m_size(n, 1) {
    for (int i = 0; i < n; ++i) m_parent[i] = i;
  }
  int find(int i) {
    while (m_parent[i] != i) {
      m_parent[i] = m_parent[m_parent[i]];
      i = m_parent[i];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (m_size[a] < m_size[b]) std::swap(a, b);
    m_parent[b] = a;
    m_size[a] += m_size[b];
  }

 private:
  std::vector<int> m_parent, m_size;
};

}  // namespace

int Fragments::largest() const { return sizes.empty() ? 0 : *std::max_element(sizes.begin(), sizes.end()); }

Fragments fragments_of(const NeighbourList& list) {
  const int n = list.size();
  DisjointSets sets(n);
  for (int i = 0; i < n; ++i)
    for (long k = list.offsets[i]; k < list.offsets[i + 1]; ++k) {
      const int j = list.indices[k];
      if (j < 0 || j >= n)
        throw std::invalid_argument("fragments_of: neighbour index " + std::to_string(j) + " of particle " +
                                    std::to_string(i) + " is outside [0, " + std::to_string(n) + ")");
      if (j > i) sets.unite(i, j);
    }
  Fragments f;
  f.label.assign(n, -1);
  std::vector<int> label_of_root(n, -1);
  for (int i = 0; i < n; ++i) {
    int& root_label = label_of_root[sets.find(i)];
    if (root_label < 0) {
      root_label = f.count();
      f.sizes.push_back(0);
    }
    f.label[i] = root_label;
    ++f.sizes[root_label];
  }
  return f;
}

Fragments find_fragments(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, double radius) {
  check_length(radius, "find_fragments: bond radius");
  if (!positions.allFinite()) throw std::invalid_argument("find_fragments: positions contain NaN or inf");
  const Eigen::Index n = positions.cols();
  if (n == 0) return {};
  ParticleSet<2> set;
  set.x = positions.transpose();
  // Volumes feed only find_neighbours' memory estimate: the area per point of the bounding box, each side at least
  // the radius (so points along a line are estimated by their line density).
  const Eigen::Vector2d extent =
      (positions.rowwise().maxCoeff() - positions.rowwise().minCoeff()).cwiseMax(Eigen::Vector2d::Constant(radius));
  set.volume = Eigen::VectorXd::Constant(n, extent.x() * extent.y() / static_cast<double>(n));
  set.role.assign(n, Role::Free);
  return fragments_of(find_neighbours(set, radius));
}

}  // namespace sphstab
