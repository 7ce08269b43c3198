#pragma once
// The CSV format of the mean-polishing study: numbers with 10 significant digits (format_number), integers and
// text as they are, one line per call (tcrit.csv, momentum.csv, locality.csv, thin_layers.csv).
#include <fstream>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

#include "sphstab/core/format.hpp"

namespace mean_polishing {

using namespace sphstab;

/// A number with 10 significant digits.
inline std::string num(double v) { return format_number(v, 10); }

/// A CSV cell: a number with 10 significant digits (num), an integer or text as it is.
template <class T>
std::string cell(const T& v) {
  if constexpr (std::is_floating_point_v<T>)
    return num(v);
  else if constexpr (std::is_integral_v<T>)
    return std::to_string(v);
  else
    return std::string(v);
}

/// One CSV line: the cells, comma separated, and the line break.
template <class... T>
void csv_line(std::ostream& o, const T&... v) {
  const char* sep = "";
  ((o << sep << cell(v), sep = ","), ...);
  o << "\n";
}

/// The file `path`: the header Row::kCsvHeader, then one line per row (Row::csv, with csv_line).
template <class Row>
void write_csv(const std::string& path, const std::vector<Row>& rows) {
  std::ofstream file(path);
  file << Row::kCsvHeader << "\n";
  for (const Row& r : rows) r.csv(file);
}

}  // namespace mean_polishing
