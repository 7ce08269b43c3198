#include "sphstab/growth/swegle_run.hpp"

#include <stdexcept>
#include <utility>

namespace sphstab {

GrowthRun run_swegle(const SwegleScene& scene, std::shared_ptr<const ForceFunction> force, const SwegleRunOptions& o,
                     const Eigen::VectorXd& u0) {
  if (!(o.t_end > 0) || !(o.courant > 0) || !(o.displacement_limit > 0) || !(o.linear_limit > 0))
    throw std::invalid_argument("run_swegle: need t_end, courant, displacement_limit and linear_limit > 0");
  GrowthRunOptions r = o.run;
  const double dx = scene.options.spacing;
  r.dt = o.courant * scene.h / scene.wave_speed;
  r.t_end = o.t_end;
  r.displacement_limit = o.displacement_limit * dx;
  r.linear_limit = o.linear_limit * dx;
  return run_growth_test<2>(scene.discretisation, std::move(force), u0, scene.v0, r);
}

}  // namespace sphstab
