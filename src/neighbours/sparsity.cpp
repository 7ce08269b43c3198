#include "sphstab/neighbours/sparsity.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sphstab {

SparsityPattern SparsityPattern::transpose() const {
  SparsityPattern t;
  t.rows = cols;
  t.cols = rows;
  t.offsets.assign(cols + 1, 0);
  for (int c : indices) ++t.offsets[c + 1];
  for (int c = 0; c < cols; ++c) t.offsets[c + 1] += t.offsets[c];
  t.indices.resize(indices.size());
  std::vector<long> next(t.offsets.begin(), t.offsets.end() - 1);
  for (int r = 0; r < rows; ++r)  // rows visited in order, so each transposed row comes out sorted
    for (long k = offsets[r]; k < offsets[r + 1]; ++k) t.indices[next[indices[k]]++] = r;
  return t;
}

SparsityPattern coupling_pattern(const NeighbourList& nl, const std::vector<int>& free_slot, int dim, int radius) {
  const int n = nl.size();
  if (static_cast<int>(free_slot.size()) != n)
    throw std::invalid_argument("coupling_pattern: free_slot has " + std::to_string(free_slot.size()) +
                                " entries but the neighbour list has " + std::to_string(n) + " rows");
  if (dim < 1) throw std::invalid_argument("coupling_pattern: dim must be >= 1 (got " + std::to_string(dim) + ")");
  if (radius < 0)
    throw std::invalid_argument("coupling_pattern: radius must be >= 0 (got " + std::to_string(radius) + ")");
  int nfree = 0;
  for (int s : free_slot) nfree = std::max(nfree, s + 1);

  SparsityPattern p;
  p.rows = p.cols = nfree * dim;
  p.offsets.assign(1, 0);
  std::vector<int> mark(n, -1), frontier, next, reached;
  // free particles in slot order
  std::vector<int> particle_of_slot(nfree, -1);
  for (int i = 0; i < n; ++i)
    if (free_slot[i] >= 0) particle_of_slot[free_slot[i]] = i;
  for (int f = 0; f < nfree; ++f) {
    const int i = particle_of_slot[f];
    if (i < 0) throw std::invalid_argument("coupling_pattern: free slots are not contiguous");
    // breadth-first search up to `radius` hops
    reached.assign(1, i);
    mark[i] = f;
    frontier.assign(1, i);
    for (int hop = 0; hop < radius && !frontier.empty(); ++hop) {
      next.clear();
      for (int v : frontier)
        for (long k = nl.offsets[v]; k < nl.offsets[v + 1]; ++k) {
          const int w = nl.indices[k];
          if (mark[w] != f) {
            mark[w] = f;
            next.push_back(w);
            reached.push_back(w);
          }
        }
      frontier.swap(next);
    }
    std::vector<int> slots;
    slots.reserve(reached.size());
    for (int v : reached)
      if (free_slot[v] >= 0) slots.push_back(free_slot[v]);
    std::sort(slots.begin(), slots.end());
    for (int a = 0; a < dim; ++a) {
      for (int s : slots)
        for (int b = 0; b < dim; ++b) p.indices.push_back(s * dim + b);
      p.offsets.push_back(static_cast<long>(p.indices.size()));
    }
  }
  return p;
}

std::vector<int> colour_columns(const SparsityPattern& p) {
  const SparsityPattern t = p.transpose();  // t row c = rows of column c
  std::vector<int> colour(p.cols, -1);
  std::vector<int> forbidden;  // forbidden[k] == c: colour k is used by a column conflicting with c
  for (int c = 0; c < p.cols; ++c) {
    for (long k = t.offsets[c]; k < t.offsets[c + 1]; ++k) {
      const int r = t.indices[k];
      for (long m = p.offsets[r]; m < p.offsets[r + 1]; ++m) {
        const int other = colour[p.indices[m]];
        if (other >= 0) {
          if (other >= static_cast<int>(forbidden.size())) forbidden.resize(other + 1, -1);
          forbidden[other] = c;
        }
      }
    }
    int k = 0;
    while (k < static_cast<int>(forbidden.size()) && forbidden[k] == c) ++k;
    colour[c] = k;
  }
  return colour;
}

int colour_count(const std::vector<int>& colours) {
  int m = -1;
  for (int c : colours) m = std::max(m, c);
  return m + 1;
}

bool is_valid_column_colouring(const SparsityPattern& p, const std::vector<int>& colours) {
  if (static_cast<int>(colours.size()) != p.cols) return false;
  std::vector<int> seen(colour_count(colours), -1);
  for (int r = 0; r < p.rows; ++r)
    for (long k = p.offsets[r]; k < p.offsets[r + 1]; ++k) {
      const int c = colours[p.indices[k]];
      if (c < 0) return false;
      if (seen[c] == r) return false;
      seen[c] = r;
    }
  return true;
}

}  // namespace sphstab
