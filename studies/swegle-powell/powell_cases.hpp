#pragma once
// MCM's configuration of the Swegle test [Powell2012, ch. 4 §2.2, Figs. 4.1, 4.2]: the deck's constants, the
// formulations of Fig. 4.2 in MCM's form, and the case table of the study (the h sweep, the block sizes and the two
// sensitivity sets).
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/problems/powell_impact.hpp"

namespace swegle_powell {

using namespace sphstab;

constexpr double kTssfac = 0.8;       // MCM deck, card 2: dt = TSSFAC h / c_P (the DYNA rule at rest)
constexpr double kXsph = 0.1;         // Powell (2.71)
constexpr double kOnset = 100;        // the fit window opens at 100 KE0
constexpr double kStopGrowth = 1e10;  // a run stops at 1e10 KE0 (still linear: amplitude 1e-5 dx)

/// The volume strains xi = V / V0 of the h sweep.
inline const std::vector<double> kXis = {0.96, 0.98, 0.99, 1.0, 1.01, 1.02, 1.04};

struct Formulation {
  std::string name, label;
  RateFormOptions options;
  double xsph = 0;         // Powell's XSPH eps on the leap-frog velocity
  int layer_supports = 1;  // fixed layers (in supports) the formulation needs for an exact equilibrium
};

/// Fig. 4.2's formulations in MCM's form: every one with MCM's continuity (1.32) and the bulk viscosity.
inline std::vector<Formulation> formulations() {
  // MCM's rate forms as the impact problems run them (problems/powell_impact.hpp): continuity (1.32), the deck's
  // bulk viscosity; NCSPH (1.19) in L and in the row momentum (1.36); S-SPH with Fig. 4.3's counts and (4.18).
  const RateFormOptions mcm = powell_formulation_options("sph"), ncsph = powell_formulation_options("ncsph"),
                        ssph = powell_formulation_options("ssph");
  RateFormOptions cij = mcm;
  cij.momentum = RateFormMomentum::Cij;  // (4.10), local polish (4.9), actual counts
  return {{"sph", "basic SPH", mcm},
          {"xsph", "SPH + XSPH (2.71)", mcm, kXsph},
          {"ncsph", "NCSPH (1.19), row momentum (1.36)", ncsph, 0, 2},
          {"ncxsph", "NCSPH + XSPH (2.71)", ncsph, kXsph, 2},
          {"cij", "C_ij momentum (4.10)", cij, 0, 2},
          // (4.18)'s sums differ from the interior's within one support of the outer edge, and r_i, c_j, m_i carry
          // them three supports in (c_j over N(j), m_i over N(i), the pair (i, f)): four supports of fixed layers
          // leave the free particles in exact equilibrium (three left a residual 225 times the kick's scale).
          {"ssph", "S-SPH (algorithm 4.2, Fig. 4.3 counts, first-step Shepard (4.18)) + XSPH (2.71)", ssph, kXsph, 4}};
}

/// One case: a set of the study ("main": the h sweep at the main block size; "size": other block sizes;
/// "no-bulk": without the bulk viscosity; "half-dt": TSSFAC 0.4), a formulation, h / dx, n and xi.
struct Case {
  std::string set;
  int form = 0;
  double h_over_dx = 1.3, xi = 1, tssfac = kTssfac;
  int n = 21;
  bool bulk = true;
};

/// The sweeps: h / dx of the main set, the other block sizes, the main block size; quick: h = 1.1 (the cheapest S-SPH
/// verdicts), no block sizes and no sensitivity sets.
struct Sweeps {
  std::vector<double> hs;
  std::vector<int> sizes;
  int n = 21;
  bool quick = false;
};

inline Sweeps sweeps(int n, bool quick) {
  return {quick ? std::vector<double>{1.1} : std::vector<double>{1.1, 1.2, 1.3, 1.4, 1.5},
          quick ? std::vector<int>{} : std::vector<int>{11, 31}, n, quick};
}

/// The cases: the h sweep of every formulation and xi (main), then the block sizes at h = 1.3 (xi 0.98, 1.02), then
/// without the bulk viscosity and at TSSFAC 0.4 (xi 0.98, 1, 1.02).
inline std::vector<Case> powell_cases(std::size_t forms, const Sweeps& sw) {
  std::vector<Case> cases;
  for (double h : sw.hs)
    for (std::size_t f = 0; f < forms; ++f)
      for (double xi : kXis) cases.push_back({"main", static_cast<int>(f), h, xi, kTssfac, sw.n, true});
  for (int size : sw.sizes)
    for (std::size_t f = 0; f < forms; ++f)
      for (double xi : {0.98, 1.02}) cases.push_back({"size", static_cast<int>(f), 1.3, xi, kTssfac, size, true});
  if (!sw.quick)
    for (std::size_t f = 0; f < forms; ++f)
      for (double xi : {0.98, 1.0, 1.02}) {
        cases.push_back({"no-bulk", static_cast<int>(f), 1.3, xi, kTssfac, sw.n, false});
        cases.push_back({"half-dt", static_cast<int>(f), 1.3, xi, kTssfac / 2, sw.n, true});
      }
  return cases;
}

}  // namespace swegle_powell
