#pragma once
// The objectivity check of the Turek & Hron (2006) CSM3 study (rotation.csv and its Markdown table): the largest Green
// strain of FiniteStrainTotalLagrangian's F under a rigid rotation of the beam, with the plain and the NCSPH reference
// gradient, at every resolution and theta = 0.1, 0.3.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/forms/correction_gradient.hpp"
#include "sphstab/forms/finite_strain_total_lagrangian.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace csm3_study {

using namespace sphstab;

/// Writes <out>/rotation.csv for the beams of `across` (clamp_layers wide, h = h_over_dx dx) and returns its Markdown
/// table.
inline std::string rigid_rotation(const std::string& out, const std::vector<int>& across, int clamp_layers,
                                  const Kernel<2>& kernel, double h_over_dx,
                                  const std::shared_ptr<const HyperelasticModel<2>>& svk) {
  // objectivity: a rigid rotation u = (R - I) X of every particle (free and clamp) gives F = R exactly for a
  // first-order consistent gradient (NCSPH), so the Green strain E = (F^T F - I) / 2 must vanish; the plain gradient
  // gives F = I + M (R - I) with the moment matrix M != I at the free surfaces: spurious strain
  CsvWriter rotcsv(out + "/rotation.csv", {"across", "gradient", "theta", "max_green_strain_all",
                                           "max_green_strain_surface_row", "max_green_strain_interior"});
  std::string md_rot;
  for (int n : across)
    for (const std::string g : {"plain", "ncsph"})
      for (double theta : {0.1, 0.3}) {
        const TurekHronBeam beam = turek_hron_beam({.across = n, .clamp_layers = clamp_layers});
        const auto disc = make_discretisation(beam.particles, kernel, h_over_dx * beam.dx);
        FiniteStrainOptions<2> opt;
        if (g == "ncsph") opt.gradient = make_gradient_provider<2>(Correction::Ncsph);
        FiniteStrainTotalLagrangian<2> tl(disc, svk, TurekHronCsm3::density, opt);
        Eigen::Matrix2d R;
        R << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
        Eigen::VectorXd u(tl.dofs()), d(2 * (disc->size() - disc->free_count()));
        for (int i = 0, k = 0; i < disc->size(); ++i) {
          const Eigen::Vector2d X = disc->particles.x.row(i).transpose();
          const Eigen::Vector2d w = (R - Eigen::Matrix2d::Identity()) * X;
          const int f = disc->free_slot[i];
          if (f >= 0)
            u.segment<2>(2 * f) = w;
          else
            d.segment<2>(2 * k++) = w;
        }
        tl.set_fixed_displacement(d);
        const Eigen::MatrixXd F = tl.deformation_gradients(u);
        double all = 0, surface = 0, interior = -1;  // -1: no particle 3 layers deep
        for (int f = 0; f < disc->free_count(); ++f) {
          const int i = disc->free[f];
          Eigen::Matrix2d Fi;
          Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
          const double e = (0.5 * (Fi.transpose() * Fi - Eigen::Matrix2d::Identity())).cwiseAbs().maxCoeff();
          all = std::max(all, e);
          if (beam.particles.depth[i] == 0) surface = std::max(surface, e);
          if (beam.particles.depth[i] >= 3) interior = std::max(interior, e);
        }
        if (interior < 0) interior = NAN;
        rotcsv.row({n, g, theta, all, surface, interior});
        study::md_row(md_rot, {std::to_string(n), g, study::fixed(theta, 1), study::sig(all, 3), study::sig(surface, 3),
                               study::sig(interior, 3)});
      }
  return md_rot;
}

}  // namespace csm3_study
