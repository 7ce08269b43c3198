#include "sphstab/io/rate_form_vtk.hpp"

#include "sphstab/forms/rate_form_state.hpp"
#include "sphstab/models/von_mises.hpp"

namespace sphstab {

template <int Dim>
void write_rate_form_vtp(const std::string& path, const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                         const std::vector<VtkField>& extra) {
  const int n = scheme.discretisation().size();
  const Eigen::Matrix<double, Dim, Eigen::Dynamic> x = rate_form_positions(scheme, y);
  const Eigen::Matrix<double, Dim, Eigen::Dynamic> v = rate_form_velocities(scheme, y);
  const std::vector<Eigen::Matrix<double, Dim, Dim>> sigma = rate_form_stresses(scheme, y);
  const Eigen::VectorXd rho = rate_form_densities(scheme, y);
  const ElasticMaterial& m = scheme.material();
  const auto S = rate_form_deviators(scheme, y);
  Eigen::VectorXd sxx(n), syy(n), sxy(n), p(n), eq(n), fixed(n), driven(n);
  for (int i = 0; i < n; ++i) {
    sxx[i] = sigma[i](0, 0);
    syy[i] = sigma[i](Dim - 1, Dim - 1);
    sxy[i] = sigma[i](0, Dim - 1);
    p[i] = m.bulk_modulus() * (rho[i] / m.density() - 1);  // the 2D S is not traceless (plane strain S_zz)
    eq[i] = von_mises_stress<Dim>(S.col(i));
    fixed[i] = scheme.position_offset(i) < 0;
    driven[i] = scheme.is_driven(i);
  }
  std::vector<VtkField> fields = {{"velocity", Dim, Eigen::Map<const Eigen::VectorXd>(v.data(), v.size())},
                                  {"density", 1, rho},
                                  {"pressure", 1, p},
                                  {"sigma_xx", 1, sxx}};
  if (Dim == 2) fields.insert(fields.end(), {{"sigma_yy", 1, syy}, {"sigma_xy", 1, sxy}});
  fields.insert(fields.end(), {{"von_mises", 1, eq}, {"fixed", 1, fixed}, {"driven", 1, driven}});
  fields.insert(fields.end(), extra.begin(), extra.end());
  write_vtp(path, x.transpose(), fields);
}

template void write_rate_form_vtp(const std::string&, const RateFormScheme<1>&, const Eigen::VectorXd&,
                                  const std::vector<VtkField>&);
template void write_rate_form_vtp(const std::string&, const RateFormScheme<2>&, const Eigen::VectorXd&,
                                  const std::vector<VtkField>&);

}  // namespace sphstab
