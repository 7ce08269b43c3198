#include "sphstab/integrate/diagnostics.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sphstab {

void SecondOrderSystem::validate(long ndof, const char* who) const {
  const std::string w(who);
  if (!acceleration) throw std::invalid_argument(w + ": the system has no acceleration callable");
  if (dofs_per_particle < 1 || dofs_per_particle > 3)
    throw std::invalid_argument(w + ": dofs_per_particle must be 1..3 (got " + std::to_string(dofs_per_particle) + ")");
  if (ndof < 1) throw std::invalid_argument(w + ": the system has no degrees of freedom");
  if (ndof % dofs_per_particle != 0)
    throw std::invalid_argument(w + ": " + std::to_string(ndof) + " DOFs is not a multiple of dofs_per_particle " +
                                std::to_string(dofs_per_particle));
  const long np = ndof / dofs_per_particle;
  if (mass.size() && mass.size() != np)
    throw std::invalid_argument(w + ": mass has " + std::to_string(mass.size()) + " entries for " + std::to_string(np) +
                                " particles");
  if (mass.size() && !(mass.array() > 0).all()) throw std::invalid_argument(w + ": masses must be > 0");
  if (reference_positions.size() && reference_positions.size() != ndof)
    throw std::invalid_argument(w + ": reference_positions has " + std::to_string(reference_positions.size()) +
                                " entries for " + std::to_string(ndof) + " DOFs");
}

Diagnostics compute_diagnostics(const SecondOrderSystem& s, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                long step, double time) {
  Diagnostics d;
  d.step = step;
  d.time = time;
  const int dpp = s.dofs_per_particle;
  double ke = 0;
  for (long k = 0; k < v.size(); ++k) {
    const double m = s.dof_mass(k);
    ke += m * v[k] * v[k];
    d.momentum[k % dpp] += m * v[k];
  }
  d.kinetic = 0.5 * ke;
  d.strain = s.strain_energy ? s.strain_energy(u) : std::numeric_limits<double>::quiet_NaN();
  d.total = std::isnan(d.strain) && !s.strain_energy ? d.kinetic : d.kinetic + d.strain;
  d.max_abs_displacement = u.size() ? u.cwiseAbs().maxCoeff() : 0.0;
  d.max_abs_velocity = v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
  return d;
}

std::vector<std::string> diagnostics_columns(int dofs_per_particle) {
  std::vector<std::string> c = {"step", "t", "kinetic", "strain", "total"};
  const char* axis[3] = {"x", "y", "z"};
  for (int a = 0; a < dofs_per_particle; ++a) c.push_back(std::string("momentum_") + axis[a]);
  c.push_back("max_abs_u");
  c.push_back("max_abs_v");
  return c;
}

}  // namespace sphstab
