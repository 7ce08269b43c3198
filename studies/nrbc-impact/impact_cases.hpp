#pragma once
// The cases of the surface impact [Powell2012, ch. 2 §3.2(c)] on Powell's steel and grid (common/nrbc.hpp): the
// truncations (where the absorbing particles are and which condition they carry), the probes, and the case table of
// the study.
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/nrbc.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace nrbc_impact {

using namespace sphstab;
using namespace sphstab::study::nrbc;  // Powell's steel and grid (kSteel, kDx), the boundaries (Free, P, M, Traction)

enum class Side { None, Sides, Bottom };  ///< where the absorbing particles are

struct ImpactCase {
  std::string name;  ///< narrow, shallow, reference, free-W
  int nx = 100, ny = 100;
  Side side = Side::None;
  Boundary boundary = Boundary::Free;
  double v_patch = 0.1, cfl = 0.3, t_end = 4;
  RateFormGradient gradient = RateFormGradient::Plain;
};

inline std::string tag_of(const ImpactCase& c) {
  return c.name + "_" + boundary_name(c.boundary) + "_v" + format_number(c.v_patch, 3);
}

/// Probes: surface particles (top row) at x = 0.11, 0.21, ..., 0.91 and two at depth below the centre (y = -0.31,
/// -0.51).
struct Probe {
  std::string name;
  double x, y;
};
inline std::vector<Probe> probes() {
  std::vector<Probe> p;
  for (int k = 1; k <= 9; ++k) p.push_back({"s" + std::to_string(k), 0.1 * k + 0.5 * kDx, -0.5 * kDx});
  p.push_back({"d3", 0.5 * kDx, -0.3 - 0.5 * kDx});
  p.push_back({"d5", 0.5 * kDx, -0.5 - 0.5 * kDx});
  return p;
}

/// The study's cases at the run settings of `base` (cfl, t_end, gradient); the slow reference first. --quick: the
/// slow impact's reference, narrow and shallow truncations only (no cost set, no fast impact), in smaller domains that
/// the quick case's 3 us allows: the reference 3.2 cm wide and 1.4 cm deep (at c_p its sides are heard at s9 after
/// 3.3 us and its bottom at d5 after 3.8 us; the lattice's fastest waves are earlier, by about 0.6 us at d5), the
/// narrow truncation as deep, the shallow one as wide.
inline std::vector<ImpactCase> impact_cases(const ImpactCase& base, bool quick) {
  // The reference's sides (3 cm from the centre) and bottom (2 cm) are heard at the probes only after
  // (3 - 0.3 + 3 - 0.91) / c_p = 8 us and 4 / c_p = 6.6 us.
  if (base.t_end > 6.5)
    throw std::invalid_argument("t_end " + format_number(base.t_end) +
                                " us: the reference's boundaries are heard at the probes after 6.6 us");
  std::vector<ImpactCase> cases;
  const auto with = [&](std::string name, int nx, int ny, Side side, Boundary b) {
    ImpactCase c = base;
    c.name = std::move(name), c.nx = nx, c.ny = ny, c.side = side, c.boundary = b;
    cases.push_back(c);
  };
  if (quick) {
    with("reference", 160, 70, Side::None, Boundary::Free);
    for (Boundary b : {Boundary::P, Boundary::M, Boundary::Traction}) {
      with("narrow", 100, 70, Side::Sides, b);
      with("shallow", 160, 30, Side::Bottom, b);
    }
    return cases;
  }
  with("reference", 300, 100, Side::None, Boundary::Free);
  for (Boundary b : {Boundary::P, Boundary::M, Boundary::Traction}) {
    with("narrow", 100, 100, Side::Sides, b);
    with("shallow", 200, 30, Side::Bottom, b);
  }
  // The cost of a non-reflecting boundary: absorbing truncations of growing width against free truncations of
  // growing width (the domain the absorbing boundary is to replace), all 2 cm deep.
  for (int nx : {60, 140}) with("narrow-" + std::to_string(nx), nx, 100, Side::Sides, Boundary::P);
  for (int nx : {100, 140, 200, 240}) with("free-" + std::to_string(nx), nx, 100, Side::None, Boundary::Free);
  with("free-shallow", 200, 30, Side::None, Boundary::Free);
  // Powell's fast impact (0.5 cm/us, 83 % of c_p: strongly non-linear).
  for (Boundary b : {Boundary::Free, Boundary::P, Boundary::M}) {
    with(b == Boundary::Free ? "reference" : "narrow", b == Boundary::Free ? 300 : 100, 100,
         b == Boundary::Free ? Side::None : Side::Sides, b);
    cases.back().v_patch = 0.5;
  }
  return cases;
}

}  // namespace nrbc_impact
