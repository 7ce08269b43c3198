#pragma once
// The shape of a displacement field of the Swegle block (a run's displacement in the linear regime, or a linear
// mode): its dominant wavevector k dx / pi (spectral/dominant_wavevector.hpp, structure-factor peak) with the share
// of its squared norm in the x component, and the VTP snapshot of the field (modes/*.vtp).

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "sphstab/io/vtk.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/problems/swegle.hpp"
#include "sphstab/spectral/dominant_wavevector.hpp"
#include "swegle_options.hpp"

namespace swegle_study {

using namespace sphstab;

/// Dominant wavevector of a displacement field (dominant_wavevector.hpp, structure-factor peak) and the share of its
/// squared norm in the x component.
struct ModeK {
  double kx = kNaN, ky = kNaN, peak = kNaN, x_share = kNaN;
  std::string component() const { return std::isnan(x_share) ? "-" : (x_share >= 0.5 ? "x" : "y"); }
};

inline ModeK mode_k(const Eigen::VectorXd& field, const SwegleScene& s) {
  ModeK m;
  if (!field.size() || !(field.cwiseAbs().maxCoeff() > 0)) return m;
  const WavevectorEstimate e = dominant_wavevector(field, Eigen::MatrixX2d(s.discretisation->free_positions()),
                                                   bravais_lattice_2d(LatticeType::Square, s.options.spacing));
  m.kx = e.kx_over_pi;
  m.ky = e.ky_over_pi;
  m.peak = e.peak_fraction;
  double sx = 0;
  for (Eigen::Index p = 0; 2 * p < field.size(); ++p) sx += field[2 * p] * field[2 * p];
  m.x_share = sx / field.squaredNorm();
  return m;
}

/// VTP snapshot of a field on the free particles, scaled to max |component| = 1, with its magnitude per particle.
inline void write_mode_vtp(const std::string& path, const SwegleScene& s, const Eigen::VectorXd& field,
                           const char* name) {
  const Eigen::MatrixX2d x = Eigen::MatrixX2d(s.discretisation->free_positions());
  Eigen::VectorXd f = field;
  const double m = f.cwiseAbs().maxCoeff();
  if (m > 0) f /= m;
  Eigen::VectorXd mag(x.rows());
  for (Eigen::Index p = 0; p < x.rows(); ++p) mag[p] = std::hypot(f[2 * p], f[2 * p + 1]);
  write_vtp(path, Eigen::MatrixXd(x), {{name, 2, f}, {"magnitude", 1, mag}});
}

}  // namespace swegle_study
