#pragma once
/// \file artificial_stress_term.hpp
/// The artificial stress of Gray, Monaghan & Swift (2001) as an ElasticForm2D term (artificial_stress.hpp):
///   a_i += sum_{j != i} m_j (R_i + R_j) f_ij^n dW_ij/dx_i,   f_ij = W(r_ij)/W(dp),   m_j = rho V_j,
/// with R_i = -epsilon sigmabar/rho^2 on the tensile principal components of the particle's total stress sigma_i
/// (pre-stress included; tension positive) and 0 on the compressive ones (GMS 3.12, 6.1-6.9). Added to basic SPH
/// (ElasticForm2D Plus, which is GMS's sum_j m_j (sigma_i/rho^2 + sigma_j/rho^2) grad W_ij for constant rho).
///
/// \note R is a smooth function of sigma except where a principal stress crosses 0 (a switch, decided on real
///       parts); the complex-step Jacobian is that of the branch of the real point.
///
/// \code{.cpp}
/// auto force = sphstab::make_artificial_stress_sph(disc, material, sphstab::PreStrain::from_area_ratio(1.02));
/// \endcode
#include <memory>

#include "sphstab/forms/elastic_term.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/models/artificial_stress.hpp"

namespace sphstab {

class ArtificialStressTerm final : public ElasticTermT<ArtificialStressTerm> {
 public:
  /// @param[in] discretisation  2D set (volumes, kernel, h, spacing)
  /// @param[in] parameters      epsilon >= 0 (GMS: 0.3) and n >= 0 (GMS: 4)
  /// @param[in] dp              reference spacing of f = W(r)/W(dp); <= 0 uses particles.spacing
  /// Throws std::invalid_argument for a null discretisation, bad parameters, or dp <= 0 / beyond the support.
  ArtificialStressTerm(std::shared_ptr<const Discretisation<2>> discretisation,
                       const ArtificialStressParameters& parameters = {}, double dp = 0);

  std::string name() const override;
  OperatorRequest requirements() const override { return {.kernel = true, .gradient = true, .hessian = false}; }
  int dependence_radius() const override { return 2; }

  template <class Scalar>
  void add_impl(const ElasticTermContext<Scalar>& context, ParticleAccelerations<Scalar>& acc) const;

  const ArtificialStressParameters& parameters() const { return m_parameters; }
  double reference_kernel() const { return m_w_dp; }

 private:
  std::shared_ptr<const Discretisation<2>> m_disc;
  ArtificialStressParameters m_parameters;
  double m_w_dp = 0;
};

/// ElasticForm2D(Plus) + ArtificialStressTerm: basic SPH with the GMS artificial stress.
std::shared_ptr<ElasticForm2D> make_artificial_stress_sph(std::shared_ptr<const Discretisation<2>> discretisation,
                                                          const ElasticMaterial& material, const PreStrain& prestrain,
                                                          const ArtificialStressParameters& parameters = {});

}  // namespace sphstab
