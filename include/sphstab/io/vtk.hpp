#pragma once
/// \file vtk.hpp
/// VTK XML PolyData (.vtp, ASCII) particle snapshots and a ParaView collection (.pvd) for time series.
///
/// A snapshot holds N points (one per particle) with one vertex cell each (so ParaView renders them without a
/// filter) and any number of point-data arrays. Points are written with 3 coordinates (1D/2D padded with 0);
/// a point-data field with 2 components is padded to 3 so that ParaView treats it as a vector (glyphs,
/// "Warp By Vector"). Values are written with 17 significant digits (exact double round trip).
///
/// \code{.cpp}
/// Eigen::MatrixXd x = ...;                       // N x Dim current positions
/// std::vector<sphstab::VtkField> fields = {{"displacement", 2, u}, {"velocity", 2, v}};  // interleaved
/// sphstab::write_vtp("snap_000010.vtp", x, fields);
/// sphstab::write_pvd("run.pvd", {{0.0, "snap_000000.vtp"}, {0.1, "snap_000010.vtp"}});
/// \endcode
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace sphstab {

/// A point-data array: `values` holds N * components numbers, interleaved (point i, component c at
/// i * components + c). components = 1..3 (1: scalar, 2 or 3: vector, written with 3 components).
struct VtkField {
  std::string name;
  int components = 1;
  Eigen::VectorXd values;
};

/// Writes an ASCII .vtp file. `points` is N x d with d = 1, 2 or 3. Throws std::invalid_argument for a field
/// whose size is not N * components, a bad component count or d outside 1..3, and std::runtime_error if the
/// file cannot be written.
void write_vtp(const std::string& path, const Eigen::MatrixXd& points, const std::vector<VtkField>& fields);

/// A .vtp file read back: points (N x 3) and point-data arrays with the component counts stored in the file.
struct VtpData {
  Eigen::MatrixXd points;
  std::vector<VtkField> fields;
  /// The field with this name; throws std::invalid_argument if absent.
  const VtkField& field(const std::string& name) const;
};

/// Parses an ASCII PolyData file as written by write_vtp (XML structure checked: VTKFile/PolyData/Piece,
/// NumberOfPoints, Points and PointData arrays, matching end tags). Throws std::runtime_error with the reason
/// if the file is malformed.
VtpData read_vtp(const std::string& path);

/// Writes a ParaView collection: entries are (time, file name relative to the .pvd).
void write_pvd(const std::string& path, const std::vector<std::pair<double, std::string>>& entries);

}  // namespace sphstab
