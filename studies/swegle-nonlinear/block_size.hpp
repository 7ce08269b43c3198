#pragma once
// Block size: the full-state growth rate at rest of each formulation against n (same fixed layers, same h). A verdict
// of "neutral" on the n x n block of the runs can be a finite-size effect: the critical tension of a block falls
// towards the infinite lattice's (studies/dispersion-rate-form) as n grows.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "common/rate_form_swegle.hpp"
#include "common/study.hpp"
#include "kick_run.hpp"
#include "sphstab/growth/rate_form_spectrum.hpp"
#include "sphstab/io/csv.hpp"

namespace swegle_nonlinear {

/// The summary's block-size table and onsets, and the wall time of the spectra.
struct BlockSizes {
  std::string table, onsets;
  double wall_linear = 0;
};

/// Writes <out>/block_size.csv: every (formulation, xi, n) of `sizes` on the blocks of `s` resized.
inline BlockSizes block_sizes(const Setup& s, const std::vector<Formulation>& forms, const std::vector<double>& xis,
                              const std::vector<int>& sizes, study::Clock::time_point t0) {
  std::ofstream size_csv(s.o.out + "/block_size.csv");
  size_csv << "formulation,xi,n,gamma_linear,lambda_imag\n";
  BlockSizes b;
  for (const Formulation& form : forms)
    for (double xi : xis) {
      std::vector<std::string> row{"**" + form.name + "**", study::fixed(xi, 2)};
      int last_neutral = 0, first_growing = 0, growing = 0;
      for (int m : sizes) {
        SwegleOptions sm = s.block.scene.options;
        sm.n = m;
        const SwegleScene sc = make_swegle_scene(sm);
        const RateFormScheme<2> scheme(sc.discretisation, s.steel, form.options, s.steel.density() / xi);
        const auto tl = study::Clock::now();
        const RateFormSpectrum all = rate_form_spectrum(scheme, scheme.uniform_state());
        b.wall_linear += study::seconds_since(tl);
        // Growth below 1e-9 of the largest |lambda| is rounding of a neutral spectrum.
        const bool grows = all.growth_rate > 1e-9 * all.eigenvalues.cwiseAbs().maxCoeff();
        size_csv << csv_line({form.name, format_number(xi), std::to_string(m), format_number(all.growth_rate, 8),
                              format_number(std::abs(all.lambda.imag()), 8)});
        row.push_back(grows ? study::sig(all.growth_rate, 3) : "0");
        if (grows) {
          ++growing;
          if (!first_growing) first_growing = m;
        } else {
          last_neutral = m;
        }
      }
      const std::string who = "`" + form.name + "` ξ = " + study::fixed(xi, 2) + ": ";
      const auto side = [](int m) { return std::to_string(m) + " × " + std::to_string(m); };
      if (growing == static_cast<int>(sizes.size()))
        b.onsets += "- " + who + "unstable at every size\n";
      else if (growing == 0)
        b.onsets += "- " + who + "neutral at every size\n";
      else if (last_neutral < first_growing)
        b.onsets +=
            "- " + who + "neutral up to " + side(last_neutral) + ", unstable from " + side(first_growing) + "\n";
      else
        b.onsets += "- " + who + "neutral and unstable sizes interleave (" + std::to_string(growing) + " of " +
                    std::to_string(sizes.size()) + " unstable)\n";
      study::md_row(b.table, row);
      std::printf("%-12s xi %.2f block sizes done (%.0f s)\n", form.name.c_str(), xi, study::seconds_since(t0));
      std::fflush(stdout);
    }
  return b;
}

}  // namespace swegle_nonlinear
