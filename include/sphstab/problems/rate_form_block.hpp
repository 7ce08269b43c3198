#pragma once
/// \file rate_form_block.hpp
/// The Swegle block of the rate-form scheme [Powell2012, §4.1, Fig. 4.2] as a Scene (problems/scene.hpp): a regular
/// lattice of n free particles per side at volume strain xi = V / V0 (density rho0 / xi), with fixed layers thick
/// enough that the uniform state is an exact equilibrium of the chosen formulation (rate_form_layer_supports), or a
/// periodic lattice; the initial kick as `sphstab run` gives it. What `sphstab run` runs, and the lattice of
/// `sphstab spectrum` and `jacobian rate-form` (rate_form_block_discretisation).
///
///   block:     the free particle nearest the middle of the free block (lowest index on ties, as make_swegle_scene)
///              gets v = (V0, 0)
///   periodic:  v_x = V0 sin(k (x - x_lo)), k = 2 pi m / L_x, m = floor(L_x / (2 dx)) (wavelength 2 dx when the box
///              holds an even number of spacings: the sawtooth +-V0 in 1D)
///
/// \code{.cpp}
/// sphstab::Scene<2> s = sphstab::rate_form_block_scene<2>({.n = 21, .xi = 1.02, .kick = 1e-10});
/// const auto r = sphstab::run_rate_form(*s.scheme, s.y0, {.dt = s.time_step(0.3), .t_end = 50});
/// \endcode
#include "sphstab/forms/discretisation.hpp"
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/kernel/kernel.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/scene.hpp"

namespace sphstab {

struct RateFormBlockOptions {
  LatticeType lattice = LatticeType::Square;  ///< line (1D); square, hex, face-centred (2D)
  int n = 21;                                 ///< free particles per side, >= 1
  bool periodic = false;                      ///< periodic lattice, no fixed layers
  KernelType kernel = KernelType::CubicSpline;
  double h_over_dx = 1.3;
  double spacing = 0.01;  ///< dx
  double xi = 1.0;        ///< volume strain V / V0 > 0 (> 1 tension)
  ElasticMaterial material = ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8);  ///< steel, g-cm-us (Powell's)
  RateFormOptions scheme;
  double kick = 1e-10;  ///< V0
};

/// Thickness of the fixed layers in kernel supports that makes the uniform lattice an exact equilibrium of the
/// formulation: 1 for the plain gradient with the symmetric momentum; 2 for NCSPH, the antisymmetrised momentum and
/// C_ij, which read neighbours of neighbours; 3 for S-SPH; 4 for S-SPH with the first-step Shepard means (4.18),
/// whose sums differ from the interior's within one support of the edge.
int rate_form_layer_supports(const RateFormOptions& options);

/// The block's lattice (fixed layers of rate_form_layer_supports supports, none when periodic) and its
/// discretisation (neighbour list of radius 2h). Throws as make_lattice and make_discretisation.
template <int Dim>
std::shared_ptr<const Discretisation<Dim>> rate_form_block_discretisation(const RateFormBlockOptions& options);

/// The scene: the scheme at density rho0 / xi, y0 the uniform state with the kick. name "swegle-block" or
/// "periodic-lattice"; t_end NaN (a run chooses it); no measures. Throws as the scheme's constructor, and
/// std::invalid_argument for xi that is not finite and > 0 or a lattice of the other dimension.
template <int Dim>
Scene<Dim> rate_form_block_scene(const RateFormBlockOptions& options);

}  // namespace sphstab
