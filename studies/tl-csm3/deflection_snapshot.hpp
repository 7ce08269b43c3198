#pragma once
// The snapshot of the Turek & Hron CSM3 study (snapshot.csv): the deformed positions x + u and the Cauchy stress
// sigma = P F^T / det F of every particle of the finest run of the chosen form, at the largest deflection (most
// negative u_y(A)) of the last reference period.
#include <Eigen/Core>
#include <cmath>
#include <string>

#include "common/csm3.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/problems/turek_hron_csm3.hpp"

namespace csm3_study {

using namespace sphstab;

struct DeflectionSnapshot {
  Eigen::MatrixXd x;  // finest chosen run: x + u, sigma (Cauchy) at the largest deflection of the last period
  Eigen::MatrixXd sigma;
  double t = NAN, uy = 1e300;

  /// Takes the state u at time t (u_y(A) = uy) of the run with `form` on `disc`.
  void record(double t_sample, const Eigen::VectorXd& u, double uy_sample, const study::csm3::Form& form,
              const Discretisation<2>& disc) {
    uy = uy_sample;
    t = t_sample;
    const Eigen::MatrixXd P = form.stresses(u), F = form.deformation_gradients(u);
    x.resize(disc.size(), 2);
    sigma.resize(disc.size(), 3);
    for (int i = 0; i < disc.size(); ++i) {
      const int f = disc.free_slot[i];
      x.row(i) = disc.particles.x.row(i);
      if (f >= 0) x.row(i) += Eigen::RowVector2d(u[2 * f], u[2 * f + 1]);
      Deformation<double, 2> Fi, Pi;
      Fi << F(i, 0), F(i, 1), F(i, 2), F(i, 3);
      Pi << P(i, 0), P(i, 1), P(i, 2), P(i, 3);
      const Deformation<double, 2> s = Pi * Fi.transpose() / Fi.determinant();
      sigma.row(i) << s(0, 0), s(1, 1), s(0, 1);
    }
  }

  /// Writes <out>/snapshot.csv if a state was taken; across, clamp_layers: the finest run's beam (clamp particles
  /// flagged fixed).
  void write(const std::string& out, int across, int clamp_layers) const {
    if (!x.rows()) return;
    CsvWriter scsv(out + "/snapshot.csv", {"x", "y", "sigma_xx", "sigma_yy", "sigma_xy", "fixed"});
    const auto disc_free = turek_hron_beam({.across = across, .clamp_layers = clamp_layers});
    for (int i = 0; i < x.rows(); ++i)
      scsv.row({x(i, 0), x(i, 1), sigma(i, 0), sigma(i, 1), sigma(i, 2),
                disc_free.particles.role[i] == Role::Fixed ? 1 : 0});
  }
};

}  // namespace csm3_study
