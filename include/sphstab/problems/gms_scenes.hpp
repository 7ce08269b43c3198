#pragma once
/// \file gms_scenes.hpp
/// The test cases of Gray, Monaghan & Swift [GMS2001, §7] as Scenes (problems/scene.hpp), with GMS's scheme: the
/// cantilever plate (§7.1), the colliding rings (§7.2) and the plastic slab (§7.3). The geometry is that of
/// cantilever_plate.hpp, colliding_rings.hpp and plastic_slab.hpp; this file adds the scheme, the initial state, the
/// run length and the measures. Units: whatever the material and geometry are given in (GMS units: rho0 = K = 1).
#include "sphstab/forms/rate_form.hpp"
#include "sphstab/problems/cantilever_plate.hpp"
#include "sphstab/problems/colliding_rings.hpp"
#include "sphstab/problems/plastic_slab.hpp"
#include "sphstab/problems/scene.hpp"

namespace sphstab {

/// The scheme of [GMS2001, §3-6]: continuity -rho tr L, XSPH eps_x = 1/2, artificial stress eps (n = 4) and
/// Monaghan's viscosity with the compression switch. GMS give no viscosity coefficients: alpha = 1, beta = 2 are
/// Monaghan's (gms-plate's summary shows the MCM deck's 0.06 / 1.5 disorders the plate); alpha = beta = 0: off.
/// The pair loop (PairLoop::Pairs: each pair once, the row loop's rates to rounding at about half its cost,
/// tests/forms/rate_form_pair_loop_test.cpp): the plain gradient with symmetric momentum is where it applies.
RateFormOptions gms_scheme_options(double eps, double alpha = 1, double beta = 2);

/// What the three scenes share: material, scheme and smoothing length h = h_over_spacing dp (cubic spline).
struct GmsSceneOptions {
  ElasticMaterial material = ElasticMaterial::from_bulk_shear(1, 0.22, 1);  ///< GMS §7.2; Table 1 row 1
  RateFormOptions scheme = gms_scheme_options(0.3);
  double h_over_spacing = 1.5;
};

/// §7.1: the plate of make_cantilever_plate, its free particles started with the first clamped-free mode's velocity of
/// tip speed `tip_speed` ((7.3)-(7.4), cantilever_mode_velocity). Integrator "pc1" (one rate evaluation per step:
/// results/gms-pc1). Run length 1.25 thin-plate periods. Measure
/// "tip_deflection": the mean y displacement of the particles within dp of the tip.
Scene<2> gms_plate_scene(const CantileverPlateOptions& plate, double tip_speed, const GmsSceneOptions& options = {});

/// The run lengths of GMS's rings (§7.2) and slab (§7.3), GMS units.
inline constexpr double kGmsRingsRunLength = 100, kGmsSlabRunLength = 200;

/// §7.2: the rings of make_colliding_rings at their speeds. Integrator "pc1" (results/gms-pc1). Run length
/// kGmsRingsRunLength. Measure "ring_fragments":
/// the larger of the two rings' fragment counts (bond-graph fragments, bonds < 1.5 dp; analysis/fragments.hpp).
Scene<2> gms_rings_scene(const CollidingRingsOptions& rings, const GmsSceneOptions& options = {});

/// §7.3: the slab of make_plastic_slab with its end zones driven at +-acceleration (RateFormScheme::set_driven), von
/// Mises yield stress `yield_stress` (GMS 0.03). Run length kGmsSlabRunLength. Measure "min_width": the narrowest width
/// of the slab between the driven zones (analysis/neck.hpp, bins of 2 dp).
Scene<2> gms_slab_scene(const PlasticSlabOptions& slab, double yield_stress = 0.03,
                        const GmsSceneOptions& options = {});

}  // namespace sphstab
