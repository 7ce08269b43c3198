#include "sphstab/forms/rate_form_state.hpp"

#include <stdexcept>
#include <string>

namespace sphstab {

namespace {

template <int Dim>
void check_size(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y, const char* who) {
  if (y.size() != s.size())
    throw std::invalid_argument(std::string(who) + ": state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(s.size()));
}

}  // namespace

template <int Dim>
Eigen::Matrix<double, Dim, Eigen::Dynamic> rate_form_positions(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y) {
  check_size(s, y, "rate_form_positions");
  const ParticleSet<Dim>& p = s.discretisation().particles;
  Eigen::Matrix<double, Dim, Eigen::Dynamic> x(Dim, p.size());
  for (int i = 0; i < p.size(); ++i)
    x.col(i) = s.position_offset(i) >= 0 ? Eigen::Matrix<double, Dim, 1>(y.template segment<Dim>(s.position_offset(i)))
                                         : Eigen::Matrix<double, Dim, 1>(p.x.row(i).transpose());
  return x;
}

template <int Dim>
Eigen::Matrix<double, Dim, Eigen::Dynamic> rate_form_velocities(const RateFormScheme<Dim>& s,
                                                                const Eigen::VectorXd& y) {
  check_size(s, y, "rate_form_velocities");
  const int n = s.discretisation().size();
  Eigen::Matrix<double, Dim, Eigen::Dynamic> v = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, n);
  for (int i = 0; i < n; ++i)
    if (s.velocity_offset(i) >= 0) v.col(i) = y.template segment<Dim>(s.velocity_offset(i));
  return v;
}

template <int Dim>
Eigen::VectorXd rate_form_densities(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y) {
  check_size(s, y, "rate_form_densities");
  const int n = s.discretisation().size();
  Eigen::VectorXd rho(n);
  for (int i = 0; i < n; ++i) rho[i] = s.density_offset(i) >= 0 ? y[s.density_offset(i)] : s.initial_density();
  return rho;
}

template <int Dim>
Eigen::MatrixXd rate_form_deviators(const RateFormScheme<Dim>& s, const Eigen::VectorXd& y) {
  check_size(s, y, "rate_form_deviators");
  constexpr int kS = RateFormScheme<Dim>::kStress;
  const int n = s.discretisation().size();
  Eigen::MatrixXd S(kS, n);
  for (int i = 0; i < n; ++i)
    S.col(i) = s.stress_offset(i) >= 0 ? Eigen::Matrix<double, kS, 1>(y.template segment<kS>(s.stress_offset(i)))
                                       : Eigen::Matrix<double, kS, 1>(s.initial_deviator());
  return S;
}

template <int Dim>
std::vector<Eigen::Matrix<double, Dim, Dim>> rate_form_stresses(const RateFormScheme<Dim>& s,
                                                                const Eigen::VectorXd& y) {
  check_size(s, y, "rate_form_stresses");
  const ElasticMaterial& m = s.material();
  const Eigen::VectorXd rho = rate_form_densities(s, y);
  const auto S = rate_form_deviators(s, y);
  std::vector<Eigen::Matrix<double, Dim, Dim>> sigma(rho.size());
  for (int i = 0; i < rho.size(); ++i) {
    const double p = m.bulk_modulus() * (rho[i] / m.density() - 1);
    if constexpr (Dim == 1)
      sigma[i](0, 0) = S(0, i) - p;
    else
      sigma[i] << S(0, i) - p, S(2, i), S(2, i), S(1, i) - p;
  }
  return sigma;
}

#define SPHSTAB_RATE_FORM_STATE(D)                                                                 \
  template Eigen::Matrix<double, D, Eigen::Dynamic> rate_form_positions(const RateFormScheme<D>&,  \
                                                                        const Eigen::VectorXd&);   \
  template Eigen::Matrix<double, D, Eigen::Dynamic> rate_form_velocities(const RateFormScheme<D>&, \
                                                                         const Eigen::VectorXd&);  \
  template Eigen::VectorXd rate_form_densities(const RateFormScheme<D>&, const Eigen::VectorXd&);  \
  template std::vector<Eigen::Matrix<double, D, D>> rate_form_stresses(const RateFormScheme<D>&,   \
                                                                       const Eigen::VectorXd&);
SPHSTAB_RATE_FORM_STATE(1)
SPHSTAB_RATE_FORM_STATE(2)
#undef SPHSTAB_RATE_FORM_STATE

}  // namespace sphstab
