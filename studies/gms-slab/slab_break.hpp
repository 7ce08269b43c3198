#pragma once
// A break of the gms-slab study [GMS2001, §7.3]: where the bonds between the two driven ends gave way. The cracks
// bounding each end's fragment (the last bond that held it to the rest), the break (one crack, or two when a middle
// piece comes free), and the words and numbers the summary gives for them (at a junction, in the middle, ...).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/study.hpp"
#include "slab_case.hpp"
#include "sphstab/analysis/fragments.hpp"

namespace gslab {

/// One crack of a break: the midpoint of the closest pair of particles between an end's fragment and all the other
/// particles (the last bond that held that end), its distance from that end's junction (the inner edge of its driven
/// zone), its position between the junctions (0 left, 1 right) and the width of the strip there one record before.
struct Crack {
  double x = kNaN, y = kNaN, junction_distance = kNaN, position = kNaN, width_before = kNaN;
};

/// A detected break: time and the cracks bounding the left end's fragment and the right end's (the same crack when
/// the slab breaks in two; two cracks when a middle piece comes free, as the symmetric slab tends to do).
struct Break {
  double t = kNaN;
  Crack left, right;
  bool one_crack = true;                              ///< the two cracks are within 2h of each other
  double x_narrowest = kNaN, width_narrowest = kNaN;  ///< the narrowest bin of the whole profile one record before
  double junction_distance() const { return std::min(left.junction_distance, right.junction_distance); }
  double width_before() const { return std::fmin(left.width_before, right.width_before); }
  int cracks() const { return std::isnan(t) ? 0 : one_crack ? 1 : 2; }
};

/// The fragment holding most of `particles` (an end zone may shed a corner particle).
inline int majority_label(const Fragments& f, const std::vector<int>& particles) {
  std::vector<int> votes(f.count(), 0);
  for (int i : particles) ++votes[f.label[i]];
  return static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
}

/// The last bond that held fragment `label` to the rest: the midpoint of the closest pair of particles between the
/// fragment and all the other particles.
inline Eigen::Vector2d closest_to_rest(const Eigen::Matrix2Xd& x, const Fragments& f, int label) {
  std::vector<int> in, out;
  for (int i = 0; i < static_cast<int>(f.label.size()); ++i) (f.label[i] == label ? in : out).push_back(i);
  double best = kInf;
  Eigen::Vector2d mid(kNaN, kNaN);
  for (int i : in)
    for (int j : out) {
      const double d = (x.col(i) - x.col(j)).squaredNorm();
      if (d < best) best = d, mid = 0.5 * (x.col(i) + x.col(j));
    }
  return mid;
}

/// Where a crack is, in words: at a junction (within 2h = 3 dp of a driven zone's inner edge), in the middle (the
/// middle fifth between the junctions) or between the two.
inline std::string place(const Crack& c, double dp) {
  char buf[160];
  const char* what = c.junction_distance <= 3 * dp       ? "at the forced/free junction"
                     : std::abs(c.position - 0.5) <= 0.1 ? "in the middle"
                                                         : "between the middle and a junction";
  std::snprintf(buf, sizeof buf, "%s (x = %.3f, %.3g = %.3g dp from its end's junction)", what, c.x,
                c.junction_distance, c.junction_distance / dp);
  return buf;
}

/// Where a break is, in words: its crack, or its two cracks.
inline std::string where(const Break& b, double dp) {
  if (std::isnan(b.t)) return "no break";
  if (b.one_crack) return "one crack " + place(b.left, dp);
  return "two cracks, one " + place(b.left, dp) + " and one " + place(b.right, dp);
}

/// The x of the crack(s): "x" or "x_left / x_right".
inline std::string crack_x(const Break& b) {
  if (std::isnan(b.t)) return "-";
  return b.one_crack ? study::fixed(b.left.x, 3) : study::fixed(b.left.x, 3) + " / " + study::fixed(b.right.x, 3);
}

}  // namespace gslab
