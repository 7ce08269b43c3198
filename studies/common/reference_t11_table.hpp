#pragma once
// The analytic T11/mu of the compressible Neo-Hookean material under uniaxial stretch, [Ismail2009, (5.5)] (plotted in
// Figs. 5.1 and 5.2 of the thesis, not tabulated there): reference_t11_table.csv, tabulated for this project to 4
// decimals: studies/tl-neo-hookean-1d/ and -2d/ each keep the rows they compare with (1D strain; nu = 0.3 in 2D) in a
// reference_t11_table.csv beside their driver, read here as rows (nu, lambda2, lambda1, T11/mu); lines starting with
// '#' are comments. One reader for both studies.
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sphstab::study {

struct TableRow {
  double nu, lambda2, lambda1, t11;
};

inline std::vector<TableRow> read_table(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read " + path);
  std::vector<TableRow> rows;
  std::string line;
  bool header = true;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::stringstream s(line);
    std::string nu, l2, l1, t;
    std::getline(s, nu, ',');
    std::getline(s, l2, ',');
    std::getline(s, l1, ',');
    std::getline(s, t, ',');
    rows.push_back({std::stod(nu), std::stod(l2), std::stod(l1), std::stod(t)});
  }
  return rows;
}

/// T11/mu of the table at (nu, lambda2, lambda1); NaN if absent (the last match if repeated).
inline double thesis_t11(const std::vector<TableRow>& table, double nu, double lambda2, double lambda1) {
  double thesis = std::nan("");
  for (const TableRow& row : table)
    if (row.nu == nu && row.lambda2 == lambda2 && row.lambda1 == lambda1) thesis = row.t11;
  return thesis;
}

}  // namespace sphstab::study
