#pragma once
// What a run of the gms-rings study measured, from its series [GMS2001, §7.2]: the contact (ring distance below 2h)
// and touch (below dp) windows, the rebound (centre-of-mass velocities and restitution once the rings have
// separated), the fragments and lost particles of the rings, the kinetic energy and the largest sigma_xx; whether a
// ring breaks (more than kBreakShare of its particles torn off), and the outcome in a few words.
#include <algorithm>
#include <cmath>
#include <string>

#include "ring_case.hpp"
#include "ring_run.hpp"

namespace grings {

/// A ring "breaks" when more of its particles than this share of the ring leave its largest fragment at some record;
/// fewer are torn-off particles ("sheds"), not a fracture. 1 %: a torn-off particle or two at the contact (the
/// reference integrator at dt/2 loses 2 of 2196 at eps = 0.3) stays below it, a fracture through the ring wall
/// (eps = 0: more than 1000) is far above it. summary.md shows the counts, so the reader can apply any other line.
constexpr double kBreakShare = 0.01;

/// What a run measured, from its series.
struct RingMeasures {
  double contact_first = kNaN, contact_last = kNaN;  ///< records with ring distance < 2h
  double touch_first = kNaN, touch_last = kNaN;      ///< records with ring distance < dp
  bool separated = false;  ///< the last record has the rings' bodies out of contact (body distance >= 2h)
  double vx0_after = kNaN, vx1_after = kNaN, restitution = kNaN;
  int frag_all_end = 0, frag_all_max = 0, frag_ring_end = 0, frag_ring_max = 0, lost_end = 0, lost_max = 0;
  double ring_break_time = kNaN;  ///< first record with a ring in more than one fragment
  double ke_end_over_ke0 = kNaN, sxx_max = kNaN;
};

inline RingMeasures measure(const RingRun& r) {
  RingMeasures m;
  const double two_h = 2 * r.h / r.u.length, dp = r.c.dp / r.u.length;
  for (std::size_t k = 0; k < r.t.size(); ++k) {
    if (r.dmin[k] < two_h) {
      if (std::isnan(m.contact_first)) m.contact_first = r.t[k];
      m.contact_last = r.t[k];
    }
    if (r.dmin[k] < dp) {
      if (std::isnan(m.touch_first)) m.touch_first = r.t[k];
      m.touch_last = r.t[k];
    }
    const int fr = std::max(r.frag0[k], r.frag1[k]);
    if (fr > 1 && std::isnan(m.ring_break_time)) m.ring_break_time = r.t[k];
    m.frag_all_max = std::max(m.frag_all_max, r.frag_all[k]);
    m.frag_ring_max = std::max(m.frag_ring_max, fr);
    m.lost_max = std::max(m.lost_max, std::max(r.lost0[k], r.lost1[k]));
  }
  if (r.t.empty()) return m;
  // Separated: out of each other's support at the end. For intact rings (at most kBreakShare torn off) the distance
  // of their bodies, the largest fragments, so that a torn-off particle left between them does not hold them
  // together; for a broken ring every particle counts (its largest fragment is only part of it, the rest may be
  // fused with the other ring).
  const bool broken = m.lost_max > kBreakShare * r.per_ring;
  m.separated = (broken ? r.dmin.back() : r.dbody.back()) >= two_h && !std::isnan(m.contact_last);
  if (m.separated) {  // no force between the rings after the last contact: the COM velocities are constant
    m.vx0_after = r.vx0.back();
    m.vx1_after = r.vx1.back();
    m.restitution = (m.vx1_after - m.vx0_after) / (r.vx0.front() - r.vx1.front());
  }
  m.frag_all_end = r.frag_all.back();
  m.frag_ring_end = std::max(r.frag0.back(), r.frag1.back());
  m.lost_end = std::max(r.lost0.back(), r.lost1.back());
  m.ke_end_over_ke0 = r.ke.back() / r.ke.front();
  m.sxx_max = *std::max_element(r.sxx_max.begin(), r.sxx_max.end());
  return m;
}

inline bool breaks(const RingMeasures& m, int per_ring) { return m.lost_max > kBreakShare * per_ring; }

/// The outcome in a few words (a table cell): a ring breaks, or intact (shedding a few particles or not) and
/// separated or not.
inline std::string outcome(const RingMeasures& m, int per_ring) {
  if (breaks(m, per_ring)) return "a ring breaks (" + std::to_string(m.lost_end) + " particles lost)";
  const std::string shed = m.lost_max > 0 ? " (sheds " + std::to_string(m.lost_max) + ")" : "";
  return (m.separated ? "intact" + shed + ", separated" : "intact" + shed + ", not separated by t_end");
}

}  // namespace grings
