#pragma once
// The options of a run of the Swegle study (CLI flags of main.cpp) and the detection limit derived from them: the
// slowest growth that reaches the KE onset of the growth window within t_end (growth/growth_fit.hpp,
// growth/stability_verdict.hpp's detection_floor).

#include <limits>
#include <string>
#include <vector>

#include "sphstab/growth/growth_fit.hpp"

namespace swegle_study {

using namespace sphstab;

inline const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Options of a run of the study (CLI) and the derived detection limit.
struct Config {
  std::string out = "results/swegle";
  double t_end = 45, t_end_1d = 400;
  std::vector<double> xis{0.96, 0.98, 0.99, 1.00, 1.01, 1.02, 1.04};
  std::vector<std::string> only;
  long energy_steps = 10000;
  int record_every = 5;
  double onset = GrowthWindowOptions{}.onset_factor;
  double detect = 0;  ///< slowest growth that reaches the onset within t_end: log(onset) / (2 t_end)
};

/// --quick: a small case of every phase (the study's ctest reference); options given on the command line win.
template <class App>
void apply_quick(Config& c, const App& app) {
  if (app.count("--t-end") == 0) c.t_end = 5;
  if (app.count("--t-end-1d") == 0) c.t_end_1d = 100;
  if (app.count("--xi") == 0) c.xis = {0.98, 1.00, 1.02};
  if (app.count("--forms") == 0) c.only = {"sph", "tl", "conservative"};
  if (app.count("--energy-steps") == 0) c.energy_steps = 500;
}

}  // namespace swegle_study
