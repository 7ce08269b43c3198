#include "sphstab/problems/gms_scenes.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "sphstab/analysis/fragments.hpp"
#include "sphstab/analysis/neck.hpp"
#include "sphstab/kernel/kernel.hpp"

namespace sphstab {

RateFormOptions gms_scheme_options(double eps, double alpha, double beta) {
  return {.continuity = ContinuityForm::Divergence,
          .xsph = 0.5,
          .viscosity = alpha > 0 || beta > 0 ? ViscositySwitch::Compression : ViscositySwitch::Off,
          .viscosity_alpha = alpha,
          .viscosity_beta = beta,
          .artificial_stress = eps,
          .pair_loop = PairLoop::Pairs};
}

namespace {

// One rate evaluation per step for the elastic scenes: at the rate evaluations of GMS's two-rate step it is the more
// accurate, and it completes at the default step (results/gms-pc1, the study's decision rule). The slab keeps "pc":
// its radial return changes S after the corrector's evaluation, which then is not the next step's rate.
constexpr const char* kGmsElasticIntegrator = "pc1";

/// The scheme on `particles` at rest with uniform density and no stress (RateFormScheme::uniform_state).
Scene<2> at_rest(std::string name, ParticleSet<2> particles, const GmsSceneOptions& o) {
  Scene<2> s;
  s.name = std::move(name);
  s.spacing = particles.spacing;
  const Kernel<2> kernel(KernelType::CubicSpline);
  s.scheme = std::make_shared<RateFormScheme<2>>(
      make_discretisation(std::move(particles), kernel, o.h_over_spacing * s.spacing), o.material, o.scheme);
  s.y0 = s.scheme->uniform_state();
  s.neighbour_skin = 0.5 * s.spacing;  // bodies that bend, collide or neck move by many h: a Verlet list
  return s;
}

}  // namespace

Scene<2> gms_plate_scene(const CantileverPlateOptions& plate, double tip_speed, const GmsSceneOptions& o) {
  Scene<2> s = at_rest("plate", make_cantilever_plate(plate), o);
  const ParticleSet<2>& p = s.scheme->discretisation().particles;
  std::vector<int> tip;
  for (int i = 0; i < p.size(); ++i) {
    if (p.role[i] == Role::Free)  // [GMS2001, (7.3)-(7.4)]
      s.scheme->set_velocity(s.y0, i, Eigen::Vector2d(0, cantilever_mode_velocity(p.x(i, 0), plate.length, tip_speed)));
    if (p.x(i, 0) > plate.length - s.spacing) tip.push_back(i);
  }
  const IsotropicModuli m = isotropic_moduli(o.material.bulk_modulus(), o.material.mu());
  s.t_end = 1.25 * thin_plate_period(m.youngs, m.poisson, o.material.density(), plate.thickness, plate.length);
  s.integrator = kGmsElasticIntegrator;
  s.measures.push_back(
      {"tip_deflection", [tip, y_ref = p.x.col(1).eval()](const Eigen::Matrix2Xd& x, const Eigen::VectorXd&) {
         double u = 0;
         for (int i : tip) u += x(1, i) - y_ref[i];
         return u / static_cast<double>(tip.size());
       }});
  return s;
}

Scene<2> gms_rings_scene(const CollidingRingsOptions& rings, const GmsSceneOptions& o) {
  const CollidingRings r = make_colliding_rings(rings);
  Scene<2> s = at_rest("rings", r.particles, o);
  for (int i = 0; i < r.size(); ++i) s.scheme->set_velocity(s.y0, i, r.velocity.col(i));
  s.t_end = kGmsRingsRunLength;
  s.integrator = kGmsElasticIntegrator;
  const int n = r.per_ring;
  s.measures.push_back(
      {"ring_fragments", [n, bond = 1.5 * s.spacing](const Eigen::Matrix2Xd& x, const Eigen::VectorXd&) {
         return static_cast<double>(
             std::max(find_fragments(x.leftCols(n), bond).count(), find_fragments(x.rightCols(n), bond).count()));
       }});
  return s;
}

Scene<2> gms_slab_scene(const PlasticSlabOptions& slab_options, double yield_stress, const GmsSceneOptions& o) {
  const PlasticSlab slab = make_plastic_slab(slab_options);
  Scene<2> s = at_rest("slab", slab.particles, o);
  std::vector<Eigen::Vector2d> acc;
  for (Eigen::Index k = 0; k < slab.driven_acceleration.cols(); ++k) acc.emplace_back(slab.driven_acceleration.col(k));
  s.scheme->set_driven(slab.driven, acc);
  s.yield_stress = yield_stress;
  s.t_end = kGmsSlabRunLength;
  const double dp = s.spacing;
  s.measures.push_back({"min_width", [slab, dp](const Eigen::Matrix2Xd& x, const Eigen::VectorXd&) {
                          const SlabNeck neck =
                              slab_neck(x, slab.left_end, slab.right_end,
                                        {.bin_width = 2 * dp, .particle_size = dp, .bond_radius = 1.5 * dp});
                          double w = std::numeric_limits<double>::infinity();
                          for (double v : neck.profile.width) w = std::min(w, v);
                          return w;
                        }});
  return s;
}

}  // namespace sphstab
