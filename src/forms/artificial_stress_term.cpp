#include "sphstab/forms/artificial_stress_term.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sphstab {

ArtificialStressTerm::ArtificialStressTerm(std::shared_ptr<const Discretisation<2>> discretisation,
                                           const ArtificialStressParameters& parameters, double dp)
    : m_disc(std::move(discretisation)), m_parameters(parameters) {
  if (!m_disc) throw std::invalid_argument("ArtificialStressTerm: discretisation is null");
  if (!(parameters.epsilon >= 0) || !std::isfinite(parameters.epsilon))
    throw std::invalid_argument("ArtificialStressTerm: epsilon must be finite and >= 0 (got " +
                                std::to_string(parameters.epsilon) + ")");
  if (!(parameters.exponent >= 0) || !std::isfinite(parameters.exponent))
    throw std::invalid_argument("ArtificialStressTerm: exponent n must be finite and >= 0 (got " +
                                std::to_string(parameters.exponent) + ")");
  if (dp <= 0) dp = m_disc->particles.spacing;
  m_w_dp = artificial_stress_reference_kernel(m_disc->kernel, m_disc->h, dp);
}

std::string ArtificialStressTerm::name() const {
  std::ostringstream s;
  s << "gms(eps=" << m_parameters.epsilon << ",n=" << m_parameters.exponent << ")";
  return s.str();
}

template <class Scalar>
void ArtificialStressTerm::add_impl(const ElasticTermContext<Scalar>& c, ParticleAccelerations<Scalar>& acc) const {
  const Discretisation<2>& d = *m_disc;
  const double rho = c.material.density();
  const Eigen::Matrix<Scalar, Eigen::Dynamic, 1> density =
      Eigen::Matrix<Scalar, Eigen::Dynamic, 1>::Constant(d.size(), Scalar(rho));
  const TensorField2<Scalar> R =
      artificial_stress<Scalar>(TensorField2<Scalar>(c.stress), density, m_parameters.epsilon);
  const Eigen::VectorXd mass = rho * d.particles.volume;
  acc +=
      artificial_stress_acceleration<Scalar>(c.operators, mass, d.particles.volume, R, m_w_dp, m_parameters.exponent);
}

template void ArtificialStressTerm::add_impl<double>(const ElasticTermContext<double>&,
                                                     ParticleAccelerations<double>&) const;
template void ArtificialStressTerm::add_impl<std::complex<double>>(const ElasticTermContext<std::complex<double>>&,
                                                                   ParticleAccelerations<std::complex<double>>&) const;

std::shared_ptr<ElasticForm2D> make_artificial_stress_sph(std::shared_ptr<const Discretisation<2>> discretisation,
                                                          const ElasticMaterial& material, const PreStrain& prestrain,
                                                          const ArtificialStressParameters& parameters) {
  auto force = std::make_shared<ElasticForm2D>(discretisation, material, MomentumForm::Plus, prestrain);
  force->add_term(std::make_shared<ArtificialStressTerm>(discretisation, parameters));
  return force;
}

}  // namespace sphstab
