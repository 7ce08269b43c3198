#include "sphstab/integrate/linear_step_map.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "sphstab/core/format.hpp"

namespace sphstab {

void StateLayout::validate(const std::string& who) const {
  if (size < 0) throw std::invalid_argument(who + ": layout size must be >= 0");
  if (position.size() != velocity.size())
    throw std::invalid_argument(who + ": layout has " + std::to_string(position.size()) + " positions and " +
                                std::to_string(velocity.size()) + " velocities");
  std::vector<char> used(static_cast<std::size_t>(size), 0);
  for (const auto* list : {&position, &velocity})
    for (int k : *list) {
      if (k < 0 || k >= size)
        throw std::invalid_argument(who + ": layout offset " + std::to_string(k) + " outside [0, " +
                                    std::to_string(size) + ")");
      if (used[k]++) throw std::invalid_argument(who + ": layout offset " + std::to_string(k) + " repeated");
    }
}

template <int Dim>
StateLayout state_layout(const RateFormScheme<Dim>& scheme) {
  const Discretisation<Dim>& d = scheme.discretisation();
  StateLayout s{.size = scheme.size(), .position = {}, .velocity = {}};
  s.position.reserve(d.dofs());
  s.velocity.reserve(d.dofs());
  for (int f = 0; f < d.free_count(); ++f)  // free velocity DOF k = f Dim + a (conventions §1)
    for (int a = 0; a < Dim; ++a) {
      s.position.push_back(scheme.position_offset(d.free[f]) + a);
      s.velocity.push_back(scheme.velocity_offset(d.free[f]) + a);
    }
  return s;
}

template StateLayout state_layout<1>(const RateFormScheme<1>&);
template StateLayout state_layout<2>(const RateFormScheme<2>&);

namespace {

void check(const Eigen::MatrixXd& J, const StateLayout& s, double dt, const std::string& who) {
  s.validate(who);
  if (J.rows() != s.size || J.cols() != s.size)
    throw std::invalid_argument(who + ": J is " + std::to_string(J.rows()) + " x " + std::to_string(J.cols()) +
                                ", the layout needs " + std::to_string(s.size) + " x " + std::to_string(s.size));
  if (!J.allFinite()) throw std::invalid_argument(who + ": J has non-finite entries");
  if (!(dt > 0) || !std::isfinite(dt))
    throw std::invalid_argument(who + ": dt must be finite and > 0 (got " + format_number(dt) + ")");
}

/// The matrices of the notation (linear_step_map.hpp) of a map's layout, once J, the layout and dt are checked (errors
/// name `who`): P (projector on positions), S (velocity slot -> position slot), V (nv x n velocity selection), X
/// (position selection) and I; n the size of y.
struct Slots {
  Eigen::Index n = 0;
  Eigen::MatrixXd P, S, V, X, I;
  Slots(const Eigen::MatrixXd& J, const StateLayout& s, double dt, const std::string& who) {
    check(J, s, dt, who);
    n = s.size;
    const Eigen::Index nv = static_cast<Eigen::Index>(s.velocity.size());
    P = Eigen::MatrixXd::Zero(n, n), S = Eigen::MatrixXd::Zero(n, n);
    V = Eigen::MatrixXd::Zero(nv, n), X = Eigen::MatrixXd::Zero(nv, n);
    for (Eigen::Index k = 0; k < nv; ++k) {
      P(s.position[k], s.position[k]) = 1;
      S(s.position[k], s.velocity[k]) = 1;
      V(k, s.velocity[k]) = 1;
      X(k, s.position[k]) = 1;
    }
    I = Eigen::MatrixXd::Identity(n, n);
  }
};

}  // namespace

Eigen::MatrixXd predictor_corrector_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt,
                                        PositionUpdate positions) {
  const Slots m(J, layout, dt, "predictor_corrector_map");
  const Eigen::MatrixXd Q = m.I - m.P;
  // GMS (6.14), (6.15): y_p = A y, the positions with dt^2/2 a0 (S J y puts a0 into the position slots).
  const Eigen::MatrixXd A = m.I + dt * J + 0.5 * dt * dt * m.S * J;
  // GMS (6.16)-(6.18): the corrector dt/2 (f1 - f0) = dt/2 J (A - I) y on everything but the positions.
  const Eigen::MatrixXd corr = 0.5 * dt * J * (A - m.I);
  if (positions == PositionUpdate::Gms) return A + Q * corr;  // x = x_p, "not corrected"
  // Trapezoid: x = x0 + dt/2 (f0 + f1) on the positions.
  return Q * A + Q * corr + m.P * (m.I + 0.5 * dt * J + 0.5 * dt * J * A);
}

Eigen::MatrixXd predictor_corrector_reuse_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt,
                                              PositionUpdate positions) {
  const Slots m(J, layout, dt, "predictor_corrector_reuse_map");
  const Eigen::Index n = m.n;
  const Eigen::MatrixXd Q = m.I - m.P;
  const Eigen::MatrixXd B = dt * m.I + 0.5 * dt * dt * m.S;  // y_p = y + B g: GMS (6.14), (6.15) with f0 = g
  // Blocks over (y, g): y_p = [I, B], f1 = J y_p = [J, J B].
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  const Eigen::MatrixXd JB = J * B;
  // y1 = y_p + dt/2 Q (f1 - g) (+ the trapezoid's position rows).
  M.topLeftCorner(n, n) = m.I + 0.5 * dt * Q * J;
  M.topRightCorner(n, n) = B + 0.5 * dt * Q * (JB - m.I);
  if (positions == PositionUpdate::Trapezoid) {  // P rows: y + dt/2 (g + f1)
    M.topLeftCorner(n, n) = Q * M.topLeftCorner(n, n) + m.P * (m.I + 0.5 * dt * J);
    M.topRightCorner(n, n) = Q * M.topRightCorner(n, n) + m.P * (0.5 * dt * (m.I + JB));
  }
  // g1 = f1: the corrector's evaluation is the next step's F^0.
  M.bottomLeftCorner(n, n) = J;
  M.bottomRightCorner(n, n) = JB;
  return M;
}

Eigen::MatrixXd staggered_leapfrog_map(const Eigen::MatrixXd& J, const StateLayout& layout, double dt) {
  const Slots m(J, layout, dt, "staggered_leapfrog_map");
  const Eigen::Index n = m.n, nv = m.V.rows();
  const Eigen::MatrixXd keep = m.I - m.V.transpose() * m.V;  // I - V^T V: every slot but the velocities
  // Step 2 (alg. 1.1 "Calculate <D>^{n-1/2}"): y_h over (y, vh, a), the a block is zero.
  //   y_h = keep (I + dt/2 J) y + X^T dt/2 (vh - V y) + V^T vh
  const Eigen::MatrixXd Hy = keep * (m.I + 0.5 * dt * J) - 0.5 * dt * m.X.transpose() * m.V;
  const Eigen::MatrixXd Hv = 0.5 * dt * m.X.transpose() + m.V.transpose();
  // Steps 3, 4: y' = keep (y + dt J y_h) + V^T (vh + dt/2 a)   ("Update density", "Update stress", positions)
  const Eigen::MatrixXd KJ = dt * keep * J;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + 2 * nv, n + 2 * nv);
  M.block(0, 0, n, n) = keep + KJ * Hy;
  M.block(0, n, n, nv) = KJ * Hv + m.V.transpose();
  M.block(0, n + nv, n, nv) = 0.5 * dt * m.V.transpose();
  // Step 4: a' = V J y' ("Calculate a_i^n", (1.36)); step 5: vh' = vh + dt a'.
  const Eigen::MatrixXd VJ = m.V * J;
  M.block(n + nv, 0, nv, n + 2 * nv) = VJ * M.topRows(n);
  M.block(n, 0, nv, n + 2 * nv) = dt * M.block(n + nv, 0, nv, n + 2 * nv);
  M.block(n, n, nv, nv) += Eigen::MatrixXd::Identity(nv, nv);
  return M;
}

Eigen::MatrixXd linear_step_map(const Eigen::MatrixXd& J, const StateLayout& layout, const RateFormRunOptions& o) {
  const char* who = "linear_step_map";
  if (o.leapfrog_xsph != 0 || o.absorbing_half_step || std::isfinite(o.yield_stress))
    throw std::invalid_argument(std::string(who) +
                                ": Powell's XSPH, absorbing_half_step and a yield stress act outside F (use "
                                "rate_form_step_matrix)");
  if (o.reuse_corrector_rate && o.integrator != RateFormIntegrator::PredictorCorrector)
    throw std::invalid_argument(std::string(who) + ": reuse_corrector_rate needs the predictor-corrector integrator");
  if (o.integrator == RateFormIntegrator::Leapfrog) return staggered_leapfrog_map(J, layout, o.dt);
  if (o.reuse_corrector_rate) return predictor_corrector_reuse_map(J, layout, o.dt, o.positions);
  return predictor_corrector_map(J, layout, o.dt, o.positions);
}

void select_rate_form_integrator(RateFormRunOptions& o, const std::string& name) {
  if (name != "pc" && name != "predictor-corrector" && name != "pc1" && name != "leapfrog")
    throw std::invalid_argument("unknown integrator '" + name + "' (valid: pc, pc1, leapfrog)");
  o.integrator = name == "leapfrog" ? RateFormIntegrator::Leapfrog : RateFormIntegrator::PredictorCorrector;
  o.reuse_corrector_rate = name == "pc1";
}

std::string rate_form_integrator_name(const RateFormRunOptions& o) {
  if (o.integrator == RateFormIntegrator::Leapfrog) return "leapfrog";
  const std::string base = o.reuse_corrector_rate ? "pc1" : "pc";
  return o.positions == PositionUpdate::Trapezoid ? base + "-trapezoid" : base;
}

}  // namespace sphstab
