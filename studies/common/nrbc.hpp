#pragma once
/// \file nrbc.hpp
/// What the 2D non-reflecting boundary studies (studies/nrbc-2d, nrbc-plane-wave, nrbc-impact) share
/// [Powell2012, ch. 2 §3]: Powell's steel and grid, the boundaries they compare under the one name each has in their
/// tables and files, the scheme's absorbing particles of a boundary (forms/absorbing_boundary.hpp), and Powell's run
/// (the leap-frog with XSPH, which studies/nrbc-1d runs too).
#include <Eigen/Core>
#include <string>

#include "sphstab/core/named_values.hpp"
#include "sphstab/forms/absorbing_boundary.hpp"
#include "sphstab/integrate/rate_form_run.hpp"
#include "sphstab/models/elastic_material.hpp"

namespace sphstab::study::nrbc {

/// Powell's 2D tests in his units (g, cm, us; stress in Mbar): steel, rho 7.8, E 2.1, nu 0.3 (plane strain), on a
/// grid of dx = 0.02 cm.
inline const ElasticMaterial kSteel = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);
constexpr double kDx = 0.02;

/// The boundaries the studies compare. Without absorbing particles: Periodic (no boundary: nothing to absorb),
/// Reference (the same particles inside a domain whose own boundary is not heard before the end), Free (traction
/// free). Absorbing (absorbs()): P and M, Powell (2.42) and (2.45); H-Powell and H-Higdon, P with c_p, c_s times k.n or
/// divided by it, k the a-priori direction of the waves; Traction, the LS-DYNA viscous traction (2.75) on the outer
/// layer, momentum kept.
enum class Boundary { Periodic, Reference, Free, P, M, HPowell, HHigdon, Traction };
constexpr NamedValue<Boundary> kBoundaryNames[] = {{Boundary::Periodic, "periodic"},
                                                   {Boundary::Reference, "reference"},
                                                   {Boundary::Free, "free"},
                                                   {Boundary::P, "P"},
                                                   {Boundary::M, "M"},
                                                   {Boundary::HPowell, "H-Powell"},
                                                   {Boundary::HHigdon, "H-Higdon"},
                                                   {Boundary::Traction, "traction"}};
inline std::string boundary_name(Boundary b) { return name_of(b, kBoundaryNames); }

inline bool absorbs(Boundary b) { return b != Boundary::Periodic && b != Boundary::Reference && b != Boundary::Free; }

/// The library's condition of an absorbing boundary: M is Sochaki's (2.45), the traction (2.75) its own, P and both
/// H variants Clayton-Engquist's (2.42) (H only scales its speeds, speed_scale()).
inline AbsorbingCondition absorbing_condition(Boundary b) {
  return b == Boundary::M          ? AbsorbingCondition::Sochaki
         : b == Boundary::Traction ? AbsorbingCondition::ViscousTraction
                                   : AbsorbingCondition::ClaytonEngquist;
}

/// The factor on c_p and c_s at an absorbing particle whose outward normal n makes k.n = kn with the waves' a-priori
/// direction k: kn for H-Powell, 1 / kn for H-Higdon (Higdon's first-order factor), 1 for the others.
inline double speed_scale(Boundary b, double kn) {
  return b == Boundary::HPowell ? kn : b == Boundary::HHigdon ? 1 / kn : 1.0;
}

/// The absorbing particles of boundary b (absorbs(b)), none added yet: its condition, the traction's depth dx (the
/// volume per unit face area on a lattice of spacing dx) and, when `normalised` and b is not the traction (which
/// takes no velocity gradient), the NCSPH-normalised velocity gradient at the particles.
inline AbsorbingParticles<2> absorbing_particles(Boundary b, double dx, bool normalised) {
  return {
      .condition = absorbing_condition(b), .traction_depth = dx, .normalised = normalised && b != Boundary::Traction};
}

/// Adds particle i with unit outward normal n to the absorbing particles `a` of boundary b, with the speed scale of
/// an H variant at k.n = kn (the others keep speed_scale empty: 1 at every particle).
inline void add_absorbing(AbsorbingParticles<2>& a, Boundary b, int i, const Eigen::Vector2d& n, double kn = 1) {
  a.particles.push_back(i), a.normals.push_back(n);
  if (b == Boundary::HPowell || b == Boundary::HHigdon) a.speed_scale.push_back(speed_scale(b, kn));
}

/// Powell's run of the NRBC tests: his leap-frog (algorithm 2.3) at dt to t_end with XSPH's epsilon `xsph` (2.71;
/// Powell 0.1, 0: off), stopped once the kinetic energy exceeds 100 KE0 (a boundary that feeds energy in). The
/// caller adds the observer and the absorbing particles' timing.
inline RateFormRunOptions powell_leapfrog(double dt, double t_end, double xsph = 0.1) {
  return {.dt = dt,
          .t_end = t_end,
          .energy_growth = 100,
          .integrator = RateFormIntegrator::Leapfrog,
          .leapfrog_xsph = xsph};
}

}  // namespace sphstab::study::nrbc
