#include "sphstab/io/run_output.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "sphstab/io/vtk.hpp"

namespace sphstab {

DiagnosticsCsv::DiagnosticsCsv(const std::string& path, int dofs_per_particle)
    : m_csv(path, diagnostics_columns(dofs_per_particle)), m_dpp(dofs_per_particle) {}

void DiagnosticsCsv::record(const Diagnostics& d) {
  std::vector<CsvCell> row;
  row.reserve(5 + m_dpp + 2);
  row.emplace_back(d.step);
  for (double x : {d.time, d.kinetic, d.strain, d.total}) row.emplace_back(x);
  for (int a = 0; a < m_dpp; ++a) row.push_back(d.momentum[a]);
  row.push_back(d.max_abs_displacement);
  row.push_back(d.max_abs_velocity);
  m_csv.row(row);
}

void DiagnosticsCsv::finished(const std::string&) { m_csv.flush(); }

VtkSeries::VtkSeries(std::string prefix, const SecondOrderSystem& system)
    : m_prefix(std::move(prefix)), m_x0(system.reference_positions), m_dpp(system.dofs_per_particle) {
  if (m_x0.size() == 0 || m_prefix.empty())
    throw std::invalid_argument("VtkSeries: snapshots need system.reference_positions and a prefix");
}

void VtkSeries::snapshot(const StepView& s) {
  const long np = s.u.size() / m_dpp;
  Eigen::MatrixXd x(np, m_dpp);
  for (long i = 0; i < np; ++i)
    for (int a = 0; a < m_dpp; ++a) x(i, a) = m_x0[i * m_dpp + a] + s.u[i * m_dpp + a];
  char name[32];
  std::snprintf(name, sizeof(name), "_%06ld.vtp", s.step);
  const std::string path = m_prefix + name;
  const std::vector<VtkField> fields = {
      {"displacement", m_dpp, s.u}, {"velocity", m_dpp, s.v}, {"acceleration", m_dpp, s.a}};
  write_vtp(path, x, fields);
  m_pvd.emplace_back(s.time, std::filesystem::path(path).filename().string());
  write_pvd(m_prefix + ".pvd", m_pvd);
}

ProgressReport::ProgressReport(std::string label, double interval_seconds)
    : m_line(std::move(label), interval_seconds, true) {}

void ProgressReport::advanced(long n, long nsteps, double t) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), "step %ld/%ld t = %.4g", n, nsteps, t);
  m_reported = m_line.update(static_cast<double>(n), static_cast<double>(nsteps), buf) || m_reported;
}

void ProgressReport::finished(const std::string& message) {
  if (m_reported) m_line.finish(message);  // a run too short for a progress line stays quiet
}

}  // namespace sphstab
