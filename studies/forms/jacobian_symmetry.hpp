#pragma once
// Jacobian symmetry of the four momentum forms [Powell2012, Theorem 3.8: a force derives from a potential iff its
// Jacobian is symmetric; Example 3.9: the plus form is not integrable]; the former form_asymmetry study (same
// configurations and code). Relative asymmetry of the complex-step Jacobian, kernel cubic spline, in 1D (WaveForm1D,
// load = T) and 2D (ElasticForm2D, load = pre-strain e) at the configurations of asymmetry_configs(), and in 1D
// against the displacement amplitude.
// Holds the case table, the per-case computation, the CSV writers (asymmetry.csv, asymmetry_vs_amplitude.csv) and the
// key numbers of the summary.
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "sphstab/core/format.hpp"
#include "sphstab/forms/elasticity_2d.hpp"
#include "sphstab/forms/wave_1d.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/particles/lattice.hpp"
#include "sphstab/particles/lattice_presets.hpp"

namespace forms_study {

using namespace sphstab;
using study::random_vector;
using study::sig;

/// Kernel cubic spline, h/dx = `h`; n1 particles in 1D, n2 x n2 in 2D.
struct AsymmetrySetup {
  double h;
  int n1, n2;
  ElasticMaterial material = ElasticMaterial::from_lame(1.0, 1.0, 1.0);
};

struct AsymmetryConfig {
  std::string name;
  double displacement, disorder, load;
  PreStrainKind kind;
};

inline const std::vector<AsymmetryConfig>& asymmetry_configs() {
  static const std::vector<AsymmetryConfig> configs = {
      {"equilibrium", 0.0, 0.0, 0.1, PreStrainKind::Isotropic},
      {"equilibrium-uniaxial", 0.0, 0.0, 0.1, PreStrainKind::UniaxialX},
      {"displaced-unloaded", 0.05, 0.0, 0.0, PreStrainKind::Isotropic},
      {"displaced-loaded", 0.05, 0.0, 0.1, PreStrainKind::Isotropic},
      {"displaced-small-load", 0.05, 0.0, 1e-3, PreStrainKind::Isotropic},
      {"displaced-compressed", 0.05, 0.0, -0.1, PreStrainKind::Isotropic},
      {"disordered-loaded", 0.0, 0.1, 0.1, PreStrainKind::Isotropic},
  };
  return configs;
}

struct AsymRow {
  int dim;
  std::string config, form;
  double displacement, disorder, load;
  std::string prestrain;
  double asymmetry;
};

/// Relative asymmetry of the Jacobian of `form` in configuration c, dimension dim (1 or 2).
inline double jacobian_asymmetry(const AsymmetrySetup& s, int dim, const AsymmetryConfig& c, MomentumForm form) {
  if (dim == 1) {
    Kernel<1> k(KernelType::CubicSpline);
    auto d = make_discretisation(
        make_lattice<1>(
            LatticeType::Line, s.n1,
            {.spacing = 1.0, .support_radius = k.support_radius(s.h), .perturbation = c.disorder, .seed = 5}),
        k, s.h);
    WaveForm1D f(d, form, c.load);
    return relative_asymmetry(jacobian(f, random_vector(f.dofs(), c.displacement, 9)));
  }
  Kernel<2> k(KernelType::CubicSpline);
  auto d = make_discretisation(
      make_lattice<2>(LatticeType::Square, s.n2,
                      {.spacing = 1.0, .support_radius = k.support_radius(s.h), .perturbation = c.disorder, .seed = 5}),
      k, s.h);
  ElasticForm2D f(d, s.material, form, {c.kind, c.load});
  return relative_asymmetry(jacobian(f, random_vector(f.dofs(), c.displacement, 9)));
}

/// Every configuration (the uniaxial one in 2D only) and form, 1D then 2D.
inline std::vector<AsymRow> jacobian_asymmetries(const AsymmetrySetup& s, const std::vector<MomentumForm>& forms) {
  std::vector<AsymRow> asym;
  for (int dim : {1, 2})
    for (const AsymmetryConfig& c : asymmetry_configs()) {
      if (dim == 1 && c.kind == PreStrainKind::UniaxialX) continue;
      for (MomentumForm form : forms) {
        const double a = jacobian_asymmetry(s, dim, c, form);
        asym.push_back({dim, c.name, momentum_form_name(form), c.displacement, c.disorder, c.load,
                        dim == 1 ? "tension" : (c.kind == PreStrainKind::Isotropic ? "isotropic" : "uniaxial-x"), a});
      }
    }
  return asym;
}

inline void write_asymmetry(const std::string& path, const std::vector<AsymRow>& rows) {
  std::ofstream csv(path);
  csv << "dim,config,form,displacement_dx,disorder_dx,load,prestrain,relative_asymmetry\n";
  for (const AsymRow& r : rows)
    csv << r.dim << "," << r.config << "," << r.form << "," << format_number(r.displacement, 10) << ","
        << format_number(r.disorder, 10) << "," << format_number(r.load, 10) << "," << r.prestrain << ","
        << format_number(r.asymmetry, 10) << "\n";
}

struct AmpRow {
  std::string kernel, form;
  double load, amplitude, asymmetry;
};

/// 1D asymmetry against the displacement amplitude: cubic spline and Wendland C2, load -0.1, 0, 0.1, every form.
inline std::vector<AmpRow> asymmetry_vs_amplitude(const AsymmetrySetup& s, const std::vector<MomentumForm>& forms) {
  std::vector<AmpRow> amp;
  for (KernelType type : {KernelType::CubicSpline, KernelType::WendlandC2}) {
    Kernel<1> k(type);
    auto d = make_discretisation(tension_lattice_1d(k, s.h, s.n1), k, s.h);
    for (double load : {-0.1, 0.0, 0.1})
      for (MomentumForm form : forms)
        for (double a : {1e-4, 1e-3, 1e-2, 3e-2, 1e-1}) {
          WaveForm1D f(d, form, load);
          amp.push_back({kernel_name(type), momentum_form_name(form), load, a,
                         relative_asymmetry(jacobian(f, random_vector(f.dofs(), a, 9)))});
        }
  }
  return amp;
}

inline void write_asymmetry_vs_amplitude(const std::string& path, const std::vector<AmpRow>& rows) {
  std::ofstream csv(path);
  csv << "kernel,form,load,amplitude_dx,relative_asymmetry\n";
  for (const AmpRow& r : rows)
    csv << r.kernel << "," << r.form << "," << format_number(r.load, 10) << "," << format_number(r.amplitude, 10) << ","
        << format_number(r.asymmetry, 10) << "\n";
}

/// Key numbers: the asymmetry table (one row per configuration, one column per form), the largest deviation of the
/// amplitude slope from 1 (non-conservative forms, amplitudes up to 1e-3) and the largest asymmetry of the
/// conservative form.
inline void summarise_asymmetry(study::Summary& sum, const std::vector<AsymRow>& asym, const std::vector<AmpRow>& amp) {
  std::string table;
  for (size_t i = 0; i < asym.size(); i += 4) {
    std::vector<std::string> cells = {std::to_string(asym[i].dim), asym[i].config, format_number(asym[i].load, 6)};
    for (int f = 0; f < 4; ++f) cells.push_back(sig(asym[i + f].asymmetry, 2));
    study::md_row(table, cells);
  }
  sum.set("asymmetry_table", table);
  double slope_max = 0, cons_max = 0;
  for (const AmpRow& r : amp) {
    if (r.form == "conservative") {
      cons_max = std::max(cons_max, r.asymmetry);
      continue;
    }
    for (const AmpRow& s : amp)
      if (s.kernel == r.kernel && s.form == r.form && s.load == r.load && s.amplitude == 10 * r.amplitude &&
          r.amplitude <= 1e-3 && r.asymmetry > 0)
        slope_max = std::max(slope_max, std::abs(std::log10(s.asymmetry / r.asymmetry) - 1));
  }
  sum.set("slope_deviation_max", slope_max, 2);
  sum.set("conservative_asymmetry_max", cons_max, 2);
  // The largest over both tables (asymmetry.csv and asymmetry_vs_amplitude.csv): what Theorem 3.8's check rests on.
  double cons_all = cons_max;
  for (const auto& a : asym)
    if (a.form == "conservative") cons_all = std::max(cons_all, a.asymmetry);
  sum.set("conservative_asymmetry_all", cons_all, 2);
}

}  // namespace forms_study
