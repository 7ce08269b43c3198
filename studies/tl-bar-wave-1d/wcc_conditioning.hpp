#pragma once
// Conditioning of W_CC [Ismail2009, (2.46)] and the gain ||W_CC^-1 W_CI||_inf of the exact closure
// u_C = -W_CC^-1 W_CI u_I of the modified SPH matrix (fixed_end.hpp): for the study's constrained set (the ghosts
// within the wall's support) and, at the base resolution, for the first 1 .. all right ghost layers. W_CC is
// symmetric (equal volumes): its eigenvalues give the 2-norm condition number.
// Holds the computation of one resolution, its CSV table wcc_conditioning.csv and its Markdown tables.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "fixed_end.hpp"
#include "sphstab/io/csv.hpp"

namespace bar_wave {

/// wcc_conditioning.csv and the Markdown tables of the study set (every resolution) and of the layers (base).
struct WccTables {
  CsvWriter csv;
  std::string md_wcc, md_wcc_layers;
  explicit WccTables(const std::string& out)
      : csv(out + "/wcc_conditioning.csv",
            {"n", "layers", "study_set", "cond2", "eig_min", "eig_max", "closure_gain_inf"}) {}
  void summarise(study::Summary& summary) const {
    summary.set("wcc", md_wcc);
    summary.set("wcc_layers", md_wcc_layers);
  }
};

/// The rows of one resolution (`base`: also every number of layers).
inline void wcc_conditioning(const Bar& bar, const FixedEndOperators& ends, bool base, WccTables& tables) {
  const auto& disc = bar.disc;
  const std::vector<int>& by_distance = ends.ghosts.by_distance;
  const Eigen::MatrixXd wd(ends.wmat);
  for (int layers = 1; layers <= static_cast<int>(by_distance.size()); ++layers) {
    const bool study_set = layers == static_cast<int>(ends.ghosts.eta_targets.size());
    if (!base && !study_set) continue;
    const int m = layers;
    Eigen::MatrixXd wcc(m, m), wci(m, disc->free_count());
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) wcc(a, b) = wd(by_distance[a], by_distance[b]);
      for (int f = 0; f < disc->free_count(); ++f) wci(a, f) = wd(by_distance[a], disc->free[f]);
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(wcc);
    const Eigen::VectorXd ev = es.eigenvalues();
    const double cond = ev.cwiseAbs().maxCoeff() / ev.cwiseAbs().minCoeff();
    const double gain = (wcc.partialPivLu().solve(wci)).rowwise().lpNorm<1>().maxCoeff();
    tables.csv.row({bar.n, layers, study_set ? 1 : 0, cond, ev.minCoeff(), ev.maxCoeff(), gain});
    if (study_set)
      study::md_row(tables.md_wcc, {std::to_string(bar.n), std::to_string(layers), study::sig(cond, 4),
                                    study::sig(ev.minCoeff(), 4), study::sig(gain, 4)});
    else if (base)
      study::md_row(tables.md_wcc_layers,
                    {std::to_string(layers), study::sig(cond, 4), study::sig(ev.minCoeff(), 4), study::sig(gain, 4)});
  }
}

}  // namespace bar_wave
