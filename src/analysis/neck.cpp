#include "sphstab/analysis/neck.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

namespace {

void check_indices(const std::vector<int>& list, Eigen::Index n, const char* who, const char* name) {
  if (list.empty()) throw std::invalid_argument(std::string(who) + ": the " + name + " list is empty");
  for (int i : list)
    if (i < 0 || i >= n)
      throw std::invalid_argument(std::string(who) + ": " + name + " index " + std::to_string(i) + " is outside [0, " +
                                  std::to_string(n) + ")");
}

}  // namespace

NeckProfile neck_profile(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, double x_lo, double x_hi,
                         double bin_width, double particle_size) {
  const std::string who = "neck_profile: ";
  if (!positions.allFinite()) throw std::invalid_argument(who + "positions contain NaN or inf");
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi) || !(x_hi > x_lo))
    throw std::invalid_argument(who + "need finite x_lo < x_hi (got " + format_number(x_lo) + ", " +
                                format_number(x_hi) + ")");
  if (!std::isfinite(bin_width) || !(bin_width > 0))
    throw std::invalid_argument(who + "bin width " + format_number(bin_width) + " must be finite and > 0");
  if (!std::isfinite(particle_size) || !(particle_size >= 0))
    throw std::invalid_argument(who + "particle size " + format_number(particle_size) + " must be finite and >= 0");
  const double bins_wanted = std::max(1.0, std::round((x_hi - x_lo) / bin_width));
  if (!(bins_wanted <= 1e8))
    throw std::invalid_argument(who + "(x_hi - x_lo) / bin_width = " + format_number(bins_wanted) +
                                " bins, more than 1e8: use a wider bin");
  const int bins = static_cast<int>(bins_wanted);
  NeckProfile p;
  p.x_lo = x_lo;
  p.x_hi = x_hi;
  p.bin_width = (x_hi - x_lo) / bins;
  p.centre.resize(bins);
  p.count.assign(bins, 0);
  std::vector<double> y_min(bins, std::numeric_limits<double>::infinity());
  std::vector<double> y_max(bins, -std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    const double x = positions(0, i), y = positions(1, i);
    if (x < x_lo || x > x_hi) continue;
    const int k = std::clamp(static_cast<int>(std::floor((x - x_lo) / p.bin_width)), 0, bins - 1);
    ++p.count[k];
    y_min[k] = std::min(y_min[k], y);
    y_max[k] = std::max(y_max[k], y);
  }
  p.width.assign(bins, std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < bins; ++k) {
    p.centre[k] = x_lo + (k + 0.5) * p.bin_width;
    if (p.count[k] == 0) continue;
    p.width[k] = y_max[k] - y_min[k] + particle_size;
    if (p.min_bin < 0 || p.width[k] < p.min_width) {
      p.min_bin = k;
      p.min_width = p.width[k];
      p.min_x = p.centre[k];
    }
  }
  return p;
}

bool ends_separated(const Fragments& fragments, const std::vector<int>& left, const std::vector<int>& right) {
  const auto n = static_cast<Eigen::Index>(fragments.label.size());
  check_indices(left, n, "ends_separated", "left-end");
  check_indices(right, n, "ends_separated", "right-end");
  std::vector<char> holds_left(fragments.count(), 0);
  for (int i : left) holds_left[fragments.label[i]] = 1;
  for (int i : right)
    if (holds_left[fragments.label[i]]) return false;
  return true;
}

SlabNeck slab_neck(const Eigen::Ref<const Eigen::Matrix2Xd>& positions, const std::vector<int>& left_end,
                   const std::vector<int>& right_end, const SlabNeckOptions& o) {
  const std::string who = "slab_neck: ";
  if (!std::isfinite(o.bin_width) || !(o.bin_width > 0) || !std::isfinite(o.particle_size) || !(o.particle_size >= 0) ||
      !std::isfinite(o.bond_radius) || !(o.bond_radius > 0))
    throw std::invalid_argument(who + "need finite bin_width > 0, particle_size >= 0, bond_radius > 0 (got " +
                                format_number(o.bin_width) + ", " + format_number(o.particle_size) + ", " +
                                format_number(o.bond_radius) + ")");
  if (!positions.allFinite()) throw std::invalid_argument(who + "positions contain NaN or inf");
  check_indices(left_end, positions.cols(), "slab_neck", "left-end");
  check_indices(right_end, positions.cols(), "slab_neck", "right-end");
  double left_x = -std::numeric_limits<double>::infinity(), right_x = std::numeric_limits<double>::infinity();
  for (int i : left_end) left_x = std::max(left_x, positions(0, i));
  for (int i : right_end) right_x = std::min(right_x, positions(0, i));
  const double x_lo = left_x + 0.5 * o.bin_width, x_hi = right_x - 0.5 * o.bin_width;
  if (!(x_hi > x_lo))
    throw std::invalid_argument(who + "the driven ends (x <= " + format_number(left_x) +
                                " and x >= " + format_number(right_x) + ") leave no range for bins of width " +
                                format_number(o.bin_width));
  SlabNeck neck;
  neck.profile = neck_profile(positions, x_lo, x_hi, o.bin_width, o.particle_size);
  neck.fragments = find_fragments(positions, o.bond_radius);
  neck.broken = ends_separated(neck.fragments, left_end, right_end);
  return neck;
}

}  // namespace sphstab
