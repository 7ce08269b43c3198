#pragma once
// The cases of the plate-with-hole study (issue 11, [Ismail2009, §5.4.4]): the quarter plate of hole radius a = 1
// (the thesis gives no dimensions), h = 1.3 dx, and the table of runs:
//   - linear (Hooke, S/E = 1e-3) against Kirsch's factor 3: resolution a/dx = 4, 8, ... --finest at W/a = 5, the width
//     W/a = 10, 20 at a/dx = 8, and the lumped edge load at a/dx = 8, W/a = 5;
//   - Ismail's case E = 70 MPa, nu = 0.49, S = 5 MPa at a/dx = 4, 8, 16: Hooke beside Neo-Hookean (2 load steps);
//   - the suddenly applied load of Ismail's case (dynamic_load.hpp).
#include <algorithm>
#include <string>
#include <vector>

namespace plate_hole {

constexpr double kA = 1, kHOverDx = 1.3;

struct Run {
  std::string tag, model;
  double a_over_dx = 0, w_over_a = 0, nu = 0, youngs = 0, traction = 0;
  int steps = 1;
  bool lumped = false;  ///< edge load S x edge length on the last column instead of the consistent load
};

/// The static runs, in the order of cases.csv; finest: the finest a/dx of the resolution study.
inline std::vector<Run> static_runs(int finest) {
  std::vector<Run> runs;
  for (int n = 4; n <= finest; n *= 2)
    runs.push_back({"linear-n" + std::to_string(n) + "-w5", "hooke", double(n), 5, 0.3, 70, 70e-3, 1});
  for (int w : {10, 20}) runs.push_back({"linear-n8-w" + std::to_string(w), "hooke", 8, double(w), 0.3, 70, 70e-3, 1});
  runs.push_back({"linear-n8-w5-lumped", "hooke", 8, 5, 0.3, 70, 70e-3, 1, true});
  for (int n = 4; n <= std::min(finest, 16); n *= 2) {
    runs.push_back({"ismail-hooke-n" + std::to_string(n), "hooke", double(n), 5, 0.49, 70, 5, 1});
    runs.push_back({"ismail-nh-n" + std::to_string(n), "neo-hookean", double(n), 5, 0.49, 70, 5, 2});
  }
  return runs;
}

/// The static runs of --quick, in the same order: the resolution study at a/dx = 4, 8, the width W/a = 10, the lumped
/// edge load and Ismail's case (Hooke and Neo-Hookean) at a/dx = 4.
inline std::vector<Run> quick_static_runs() {
  return {{"linear-n4-w5", "hooke", 4, 5, 0.3, 70, 70e-3, 1},
          {"linear-n8-w5", "hooke", 8, 5, 0.3, 70, 70e-3, 1},
          {"linear-n4-w10", "hooke", 4, 10, 0.3, 70, 70e-3, 1},
          {"linear-n4-w5-lumped", "hooke", 4, 5, 0.3, 70, 70e-3, 1, true},
          {"ismail-hooke-n4", "hooke", 4, 5, 0.49, 70, 5, 1},
          {"ismail-nh-n4", "neo-hookean", 4, 5, 0.49, 70, 5, 2}};
}

/// Ismail's case suddenly loaded (Neo-Hookean, W/a = 5) at a/dx = n.
inline Run dynamic_run(int n) {
  return {"ismail-nh-n" + std::to_string(n), "neo-hookean", double(n), 5, 0.49, 70, 5, 1};
}

}  // namespace plate_hole
