#include "sphstab/particles/particle_set.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sphstab/numerics/instantiation.hpp"

namespace sphstab {

template <int Dim>
ParticleSet<Dim> ParticleSet<Dim>::free_grid(int n, double dp) {
  double volume = 1;
  for (int a = 0; a < Dim; ++a) volume *= dp;
  ParticleSet s;
  s.x.resize(n, Dim);
  s.volume = Eigen::VectorXd::Constant(n, volume);
  s.role.assign(n, Role::Free);
  s.depth.assign(n, 0);
  s.spacing = dp;
  return s;
}

template <int Dim>
int ParticleSet<Dim>::count(Role r) const {
  return static_cast<int>(std::count(role.begin(), role.end(), r));
}

template <int Dim>
typename ParticleSet<Dim>::Points ParticleSet<Dim>::positions(Role r) const {
  const std::vector<int> idx = indices(r);
  Points p(static_cast<Eigen::Index>(idx.size()), Dim);
  for (std::size_t k = 0; k < idx.size(); ++k) p.row(static_cast<Eigen::Index>(k)) = x.row(idx[k]);
  return p;
}

template <int Dim>
std::vector<int> ParticleSet<Dim>::indices(Role r) const {
  std::vector<int> out;
  for (int i = 0; i < size(); ++i)
    if (role[i] == r) out.push_back(i);
  return out;
}

template <int Dim>
void ParticleSet<Dim>::validate(const char* who) const {
  const std::string w(who);
  if (size() == 0) throw std::invalid_argument(w + ": empty particle set (N = 0)");
  if (volume.size() != size() || static_cast<int>(role.size()) != size() ||
      (!depth.empty() && static_cast<int>(depth.size()) != size()))
    throw std::invalid_argument(w + ": particle arrays have mismatched sizes");
  if (!x.allFinite()) throw std::invalid_argument(w + ": particle coordinates contain NaN or inf");
  if (!volume.allFinite() || (volume.array() <= 0).any())
    throw std::invalid_argument(w + ": particle volumes must be finite and > 0");
  for (int a = 0; a < Dim; ++a)
    if (periodic[a]) {
      if (!(box_hi[a] > box_lo[a])) throw std::invalid_argument(w + ": periodic box has non-positive length");
      if ((x.col(a).array() < box_lo[a]).any() || (x.col(a).array() > box_hi[a]).any())
        throw std::invalid_argument(w + ": particle outside the periodic box");
    }
}

#define SPHSTAB_INSTANTIATE(D) template struct ParticleSet<D>;
SPHSTAB_FOR_EACH_DIM(SPHSTAB_INSTANTIATE)
#undef SPHSTAB_INSTANTIATE

}  // namespace sphstab
