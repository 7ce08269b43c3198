#include "sphstab/system/force_function.hpp"

#include <stdexcept>

namespace sphstab {

AccelerationFunction acceleration_function(std::shared_ptr<const ForceFunction> force) {
  if (!force) throw std::invalid_argument("acceleration_function: force function is null");
  return [force = std::move(force)](const Eigen::VectorXd& u, Eigen::VectorXd& a) { force->acceleration(u, a); };
}

double total_energy(const ForceFunction& force, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  if (v.size() != force.dofs())
    throw std::invalid_argument("total_energy: velocity has " + std::to_string(v.size()) + " entries, expected " +
                                std::to_string(force.dofs()));
  const Eigen::VectorXd m = force.dof_mass();
  return 0.5 * (m.array() * v.array().square()).sum() + force.strain_energy(u);
}

}  // namespace sphstab
