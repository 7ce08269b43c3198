#include "sphstab/problems/rate_form_block.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "sphstab/core/format.hpp"

namespace sphstab {

int rate_form_layer_supports(const RateFormOptions& o) {
  // (4.18)'s first-step sums differ from the interior's within one support of the edge; c_j, m_i and the pair (i, f)
  // carry them three supports in.
  if (o.momentum == RateFormMomentum::StabilisedSph) return o.first_step_shepard ? 4 : 3;
  if (o.gradient == RateFormGradient::Ncsph || o.momentum != RateFormMomentum::Symmetric) return 2;
  return 1;
}

template <int Dim>
std::shared_ptr<const Discretisation<Dim>> rate_form_block_discretisation(const RateFormBlockOptions& o) {
  if ((Dim == 1) != (o.lattice == LatticeType::Line) || o.lattice == LatticeType::Cubic)
    throw std::invalid_argument("rate_form_block: lattice " + lattice_name(o.lattice) + " does not exist in " +
                                std::to_string(Dim) + "D");
  const Kernel<Dim> kernel(o.kernel);
  const double h = o.h_over_dx * o.spacing;
  const ParticleSet<Dim> set =
      make_lattice<Dim>(o.lattice, o.n,
                        {.spacing = o.spacing,
                         .support_radius = rate_form_layer_supports(o.scheme) * kernel.support_radius(h),
                         .periodic = o.periodic});
  return make_discretisation(set, kernel, h);
}

template <int Dim>
Scene<Dim> rate_form_block_scene(const RateFormBlockOptions& o) {
  if (!(o.xi > 0) || !std::isfinite(o.xi))
    throw std::invalid_argument("rate_form_block: xi must be finite and > 0 (got " + format_number(o.xi) + ")");
  Scene<Dim> s;
  s.name = o.periodic ? "periodic-lattice" : "swegle-block";
  s.spacing = o.spacing;
  s.t_end = std::numeric_limits<double>::quiet_NaN();
  s.scheme = std::make_shared<RateFormScheme<Dim>>(rate_form_block_discretisation<Dim>(o), o.material, o.scheme,
                                                   o.material.density() / o.xi);
  const RateFormScheme<Dim>& scheme = *s.scheme;
  s.y0 = scheme.uniform_state();
  const Discretisation<Dim>& d = scheme.discretisation();
  const ParticleSet<Dim>& p = d.particles;
  Eigen::Matrix<double, Dim, 1> v = Eigen::Matrix<double, Dim, 1>::Zero();
  if (o.periodic) {
    const double L = p.box_hi[0] - p.box_lo[0];
    const double m = std::max(1.0, std::floor(L / (2 * p.spacing) + 1e-9));
    for (int i : d.free) {
      v[0] = o.kick * std::sin(2 * M_PI * m / L * (p.x(i, 0) - p.box_lo[0]));
      scheme.set_velocity(s.y0, i, v);
    }
    return s;
  }
  const Eigen::MatrixXd x = d.free_positions();
  const Eigen::RowVectorXd centre = 0.5 * (x.colwise().minCoeff() + x.colwise().maxCoeff());
  int best = 0;
  for (int f = 1; f < d.free_count(); ++f)
    if ((x.row(f) - centre).norm() < (x.row(best) - centre).norm() - 1e-12 * p.spacing) best = f;
  v[0] = o.kick;
  scheme.set_velocity(s.y0, d.free[best], v);
  return s;
}

template std::shared_ptr<const Discretisation<1>> rate_form_block_discretisation<1>(const RateFormBlockOptions&);
template std::shared_ptr<const Discretisation<2>> rate_form_block_discretisation<2>(const RateFormBlockOptions&);
template Scene<1> rate_form_block_scene<1>(const RateFormBlockOptions&);
template Scene<2> rate_form_block_scene<2>(const RateFormBlockOptions&);

}  // namespace sphstab
