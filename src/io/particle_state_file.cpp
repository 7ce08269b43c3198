#include "sphstab/io/particle_state_file.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/io/csv.hpp"
#include "sphstab/io/vtk.hpp"

namespace sphstab {

namespace {

enum class FileKind { Csv, Vtp };

FileKind file_kind(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".csv") return FileKind::Csv;
  if (ext == ".vtp") return FileKind::Vtp;
  throw std::invalid_argument(path + ": a particle state is read from .csv or .vtp (got '" + ext + "')");
}

bool has_column(const CsvTable& t, const std::string& name) {
  for (const auto& c : t.columns)
    if (c == name) return true;
  return false;
}

const VtkField* find_field(const VtpData& d, const std::string& name) {
  for (const auto& f : d.fields)
    if (f.name == name) return &f;
  return nullptr;
}

/// The masses: the file's, or the option's uniform value; exactly one of the two.
Eigen::VectorXd masses(const std::string& path, const Eigen::VectorXd* in_file, Eigen::Index n, double option) {
  if (in_file && !std::isnan(option))
    throw std::invalid_argument(path + ": the file has masses; the mass option would override them (leave it out)");
  if (in_file) return *in_file;
  if (std::isnan(option))
    throw std::invalid_argument(path + ": no mass column or array; give the particles' mass as an option");
  return Eigen::VectorXd::Constant(n, option);
}

template <int Dim>
ParticleState<Dim> from_csv(const std::string& path, const ParticleStateFileOptions& o) {
  constexpr int kStress = Dim == 1 ? 1 : 3;
  const CsvTable t = read_csv(path);
  const auto column = [&](const std::string& name) {
    try {
      const std::vector<double> v = t.numeric_column(name);
      return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(path + ": " + e.what());
    }
  };
  if ((Dim == 2) != has_column(t, "y"))
    throw std::invalid_argument(path + ": a column 'y' makes a 2D state; read as " + std::to_string(Dim) + "D");
  const Eigen::Index n = static_cast<Eigen::Index>(t.rows.size());
  const char* const pos[2] = {"x", "y"};
  const char* const vel[2] = {"vx", "vy"};
  const char* const dev[3] = {"s_xx", "s_yy", "s_xy"};
  ParticleState<Dim> s;
  s.x.resize(n, Dim);
  for (int a = 0; a < Dim; ++a) s.x.col(a) = column(pos[a]);
  if (has_column(t, "vx")) {
    s.v.resize(n, Dim);
    for (int a = 0; a < Dim; ++a) s.v.col(a) = column(vel[a]);
  }
  s.density = column("density");
  const Eigen::VectorXd file_mass = has_column(t, "mass") ? column("mass") : Eigen::VectorXd();
  s.mass = masses(path, has_column(t, "mass") ? &file_mass : nullptr, n, o.mass);
  if (has_column(t, "s_xx")) {
    s.deviator.resize(n, kStress);
    for (int c = 0; c < kStress; ++c) s.deviator.col(c) = column(dev[c]);
  }
  if (has_column(t, "fixed")) {
    const Eigen::VectorXd f = column("fixed");
    s.fixed.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (f[i] != 0 && f[i] != 1)
        throw std::invalid_argument(path + ": fixed must be 0 or 1 (particle " + std::to_string(i) + ": " +
                                    format_number(f[i]) + ")");
      s.fixed[i] = f[i] == 1;
    }
  }
  s.h = o.h;
  s.spacing = o.spacing;
  return s;
}

template <int Dim>
ParticleState<Dim> from_vtp(const std::string& path, const ParticleStateFileOptions& o) {
  constexpr int kStress = Dim == 1 ? 1 : 3;
  const VtpData d = read_vtp(path);
  const Eigen::Index n = d.points.rows();
  const auto scalar = [&](const char* name, bool required) -> const VtkField* {
    const VtkField* f = find_field(d, name);
    if (!f && required) throw std::invalid_argument(path + ": no point-data array '" + name + "'");
    if (f && f->components != 1)
      throw std::invalid_argument(path + ": '" + name + "' must have 1 component (has " +
                                  std::to_string(f->components) + ")");
    return f;
  };
  if (Dim == 1 && d.points.col(1).cwiseAbs().maxCoeff() > 0)
    throw std::invalid_argument(path + ": points with y != 0 make a 2D state; read as 1D");
  ParticleState<Dim> s;
  s.x = d.points.leftCols(Dim);
  if (const VtkField* v = find_field(d, "velocity")) {
    if (v->components < Dim) throw std::invalid_argument(path + ": 'velocity' has fewer components than the state");
    s.v.resize(n, Dim);
    for (Eigen::Index i = 0; i < n; ++i)
      for (int a = 0; a < Dim; ++a) s.v(i, a) = v->values[i * v->components + a];
  }
  s.density = scalar("density", true)->values;
  const VtkField* m = scalar("mass", false);
  s.mass = masses(path, m ? &m->values : nullptr, n, o.mass);
  if (const VtkField* dv = find_field(d, "deviator")) {
    if (dv->components != kStress)
      throw std::invalid_argument(path + ": 'deviator' must have " + std::to_string(kStress) + " components");
    s.deviator = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        dv->values.data(), n, kStress);
  } else if (const VtkField* p = scalar("pressure", false)) {  // a snapshot of io/rate_form_vtk.hpp: S = sigma + p I
    const char* const names[3] = {"sigma_xx", "sigma_yy", "sigma_xy"};
    s.deviator.resize(n, kStress);
    for (int c = 0; c < kStress; ++c) s.deviator.col(c) = scalar(names[c], true)->values;
    for (int c = 0; c < std::min(kStress, 2); ++c) s.deviator.col(c) += p->values;
  }
  if (const VtkField* f = scalar("fixed", false)) {
    s.fixed.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) s.fixed[i] = f->values[i] != 0;
  }
  s.h = o.h;
  s.spacing = o.spacing;
  return s;
}

}  // namespace

int particle_state_dimension(const std::string& path) {
  if (file_kind(path) == FileKind::Csv) return has_column(read_csv(path), "y") ? 2 : 1;
  const VtpData d = read_vtp(path);
  return d.points.rows() && d.points.col(1).cwiseAbs().maxCoeff() > 0 ? 2 : 1;
}

template <int Dim>
ParticleState<Dim> read_particle_state(const std::string& path, const ParticleStateFileOptions& o) {
  return file_kind(path) == FileKind::Csv ? from_csv<Dim>(path, o) : from_vtp<Dim>(path, o);
}

template <int Dim>
void write_state_modes_vtp(const std::string& path, const ParticleState<Dim>& s, const StateStability& r) {
  const Eigen::Index n = s.x.rows();
  if (r.particles != n) throw std::invalid_argument("write_state_modes_vtp: the result is of another state");
  // Free particles in index order carry the modes' rows (the DOF order of growth/state_stability.hpp).
  const auto spread = [&](const Eigen::VectorXd& shape) {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(n * Dim);
    if (shape.size() != static_cast<Eigen::Index>(r.free) * Dim) return out;
    Eigen::Index f = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!s.fixed.empty() && s.fixed[i]) continue;
      out.segment<Dim>(i * Dim) = shape.segment<Dim>(f * Dim);
      ++f;
    }
    return out;
  };
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n * Dim), fixed = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (s.v.size()) v.segment<Dim>(i * Dim) = s.v.row(i).transpose();
    fixed[i] = !s.fixed.empty() && s.fixed[i];
  }
  write_vtp(path, s.x,
            {{"velocity", Dim, v},
             {"density", 1, s.density},
             {"mass", 1, s.mass},
             {"fixed", 1, fixed},
             {"semi_discrete_mode", Dim, spread(r.verdict.semi_discrete_mode.shape)},
             {"map_mode", Dim, spread(r.verdict.map_mode.shape)}});
}

template ParticleState<1> read_particle_state<1>(const std::string&, const ParticleStateFileOptions&);
template ParticleState<2> read_particle_state<2>(const std::string&, const ParticleStateFileOptions&);
template void write_state_modes_vtp<1>(const std::string&, const ParticleState<1>&, const StateStability&);
template void write_state_modes_vtp<2>(const std::string&, const ParticleState<2>&, const StateStability&);

}  // namespace sphstab
