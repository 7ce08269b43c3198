#include "sphstab/growth/rate_form_spectrum.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "sphstab/core/format.hpp"
#include "sphstab/core/memory_budget.hpp"
#include "sphstab/growth/system_spectrum.hpp"
#include "sphstab/integrate/xsph.hpp"
#include "sphstab/jacobian/complex_step_jacobian.hpp"
#include "sphstab/linalg/dense_general_eigen.hpp"

namespace sphstab {

namespace {

/// Rows `rows`, columns `cols` of a row-major sparse J, dense.
Eigen::MatrixXd block(const SparseMatrix<>& J, const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> where(J.cols(), -1);
  for (std::size_t c = 0; c < cols.size(); ++c) where[cols[c]] = static_cast<int>(c);
  Eigen::MatrixXd b =
      Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (SparseMatrix<>::InnerIterator it(J, rows[r]); it; ++it)
      if (where[it.col()] >= 0) b(static_cast<Eigen::Index>(r), where[it.col()]) = it.value();
  return b;
}

/// The predictor-corrector's one-step map on (s, r), v = Q s, p = Q W r (rate_form_spectrum.hpp), from the blocks
/// already restricted to the class: X, Jvx, K = Jvq Jqv, Jvv (m x m) and W (m x r, orthonormal).
Eigen::MatrixXd reduced_predictor_corrector_map(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Jvx,
                                                const Eigen::MatrixXd& K, const Eigen::MatrixXd& Jvv,
                                                const Eigen::MatrixXd& W, double dt, PositionUpdate positions) {
  const Eigen::Index m = X.rows(), r = W.cols();
  // Each quantity as a matrix acting on z = (s, r).
  Eigen::MatrixXd sel = Eigen::MatrixXd::Zero(m, m + r);  // v
  sel.leftCols(m).setIdentity();
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(m, m + r);  // p
  p.rightCols(r) = W;
  const Eigen::MatrixXd B = Jvx * X + K;
  const Eigen::MatrixXd a0 = p + Jvv * sel;
  const Eigen::MatrixXd vp = sel + dt * a0;
  const Eigen::MatrixXd pp = p + dt * B * sel;  // p at the predictor without its dt^2/2 Jvx a0 part (added below)
  const Eigen::MatrixXd a1 = pp + 0.5 * dt * dt * Jvx * a0 + Jvv * vp;
  const Eigen::MatrixXd C = positions == PositionUpdate::Gms ? Eigen::MatrixXd(Jvx) : Eigen::MatrixXd(Jvx * X);
  const Eigen::MatrixXd p1 = pp + 0.5 * dt * dt * (C + K) * a0;
  Eigen::MatrixXd M(m + r, m + r);
  M.topRows(m) = vp + 0.5 * dt * (a1 - a0);
  M.bottomRows(r) = W.transpose() * p1;  // p1 lies in the range of W: the map is closed on (s, r)
  return M;
}

/// The state indices of the at-rest reduction: free positions x, velocities v, densities and stresses q.
struct AtRestIndices {
  std::vector<int> ix, iv, iq;
};

template <int Dim>
AtRestIndices at_rest_indices(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y) {
  AtRestIndices out;
  std::vector<int>&ix = out.ix, &iv = out.iv, &iq = out.iq;
  for (int i = 0; i < scheme.discretisation().size(); ++i) {
    for (int a = 0; a < Dim && scheme.position_offset(i) >= 0; ++a) {
      ix.push_back(scheme.position_offset(i) + a);
      iv.push_back(scheme.velocity_offset(i) + a);
      if (y[iv.back()] != 0.0)
        throw std::invalid_argument("rate_form_spectrum: the state is not at rest (particle " + std::to_string(i) +
                                    " moves): the reduction needs v = 0");
    }
    for (int c = 0; c < 1 + RateFormScheme<Dim>::kStress && scheme.density_offset(i) >= 0; ++c)
      iq.push_back(scheme.density_offset(i) + c);
  }
  return out;
}

void check_map_options(const RateFormSpectrumOptions& options) {
  if (!(options.map_leapfrog_xsph >= 0) || !std::isfinite(options.map_leapfrog_xsph) ||
      (options.map_leapfrog_xsph > 0 &&
       (options.map_dt <= 0 || options.map_integrator != RateFormIntegrator::Leapfrog)))
    throw std::invalid_argument(
        "rate_form_spectrum: map_leapfrog_xsph must be finite and >= 0, and > 0 only with the "
        "leap-frog map (map_dt > 0; got " +
        format_number(options.map_leapfrog_xsph) + ")");
  if (!(options.map_dt >= 0) || !std::isfinite(options.map_dt))
    throw std::invalid_argument("rate_form_spectrum: map_dt must be finite and >= 0 (got " +
                                format_number(options.map_dt) + ")");
}

/// The one-step map's largest |z| (1 for the fixed directions) from its eigen-decomposition, its mode (the first
/// `head` entries of the eigenvector, mapped back by Q when a class basis is given) and growth ln|z| / dt.
void set_map_result(RateFormSpectrum& out, const DenseGeneralEigen& me, long head, const Eigen::MatrixXd& Q,
                    double dt) {
  Eigen::Index k = 0;
  me.values.cwiseAbs().maxCoeff(&k);
  out.map_spectral_radius = 1;  // the fixed directions (v = 0, p = 0)
  out.map_eigenvalue = 1;
  if (std::abs(me.values[k]) > 1) {
    out.map_spectral_radius = std::abs(me.values[k]);
    out.map_eigenvalue = me.values[k];
    Eigen::VectorXcd v = me.vectors.col(k).head(head);
    if (Q.size()) v = Q.cast<std::complex<double>>() * v;
    out.map_mode = real_mode_shape(v);
  }
  out.map_growth = std::log(out.map_spectral_radius) / dt;
}

/// The predictor-corrector's one-step map (rate_form_spectrum.hpp), reduced on the free velocities and the range of
/// p = [Jvx Jvq] (x, q), restricted to the class Q if given. false: dgeev failed (out says so).
bool predictor_corrector_map(RateFormSpectrum& out, const Eigen::MatrixXd& Xv, const Eigen::MatrixXd& Jvx,
                             const Eigen::MatrixXd& Jvq, const Eigen::MatrixXd& K, const Eigen::MatrixXd& Jvv,
                             const Eigen::MatrixXd& Q, const RateFormSpectrumOptions& options) {
  const long nv = Jvx.rows();
  const auto restrict = [&](const Eigen::MatrixXd& A) { return Q.size() ? Eigen::MatrixXd(Q.transpose() * A * Q) : A; };
  Eigen::MatrixXd P(nv, Jvx.cols() + Jvq.cols());  // p = [Jvx Jvq] (x, q)
  P << Jvx, Jvq;
  if (Q.size()) P = Q.transpose() * P;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(P);
  qr.setThreshold(1e-12);
  const Eigen::MatrixXd W = Eigen::MatrixXd(qr.householderQ()).leftCols(qr.rank());
  const Eigen::MatrixXd Mr = reduced_predictor_corrector_map(restrict(Xv), restrict(Jvx), restrict(K), restrict(Jvv), W,
                                                             options.map_dt, options.map_positions);
  out.map_reduced = static_cast<int>(Mr.rows());
  DenseGeneralEigen me = general_eigen(Mr, true);
  if (me.status != Status::Successful) {
    out.status = me.status;
    out.reason = "dgeev failed on the reduced one-step map (info " + std::to_string(me.lapack_info) + ")";
    return false;
  }
  set_map_result(out, me, Q.size() ? Q.cols() : nv, Q, options.map_dt);
  return true;
}

/// Powell's leap-frog with XSPH (2.71) at rest: w_{n+1} = (I + P + dt^2 B P) w_n - P w_{n-1} (rate_form_spectrum.hpp),
/// P the XSPH smoothing on the free velocity DOFs. false: dgeev failed (out says so).
template <int Dim>
bool leapfrog_xsph_map(RateFormSpectrum& out, const RateFormScheme<Dim>& scheme, const Eigen::MatrixXd& B,
                       const Eigen::MatrixXd& Q, const RateFormSpectrumOptions& options) {
  const long m = B.rows(), nv = Q.size() ? Q.rows() : m;
  // Powell's XSPH: w_{n+1} = (I + P + dt^2 B P) w_n - P w_{n-1} (see the header), P on the free velocity DOFs.
  const double dt = options.map_dt;
  const SparseMatrix<> S =
      xsph_smoothing_matrix(scheme.discretisation(), {.epsilon = options.map_leapfrog_xsph, .include_fixed = true});
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(nv, nv);
  for (int k = 0; k < S.outerSize(); ++k)
    for (SparseMatrix<>::InnerIterator it(S, k); it; ++it)
      for (int a = 0; a < Dim; ++a) P(Dim * it.row() + a, Dim * it.col() + a) = it.value();
  if (Q.size()) P = Q.transpose() * P * Q;
  const Eigen::MatrixXd BP = B * P;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  C.topLeftCorner(m, m) = P + dt * dt * BP;
  C.topLeftCorner(m, m).diagonal().array() += 1.0;
  C.topRightCorner(m, m) = -P;
  C.bottomLeftCorner(m, m).setIdentity();
  const DenseGeneralEigen ce = general_eigen(C, true);
  if (ce.status != Status::Successful) {
    out.status = ce.status;
    out.reason = "dgeev failed on the leap-frog map with XSPH (info " + std::to_string(ce.lapack_info) + ")";
    return false;
  }
  out.map_reduced = static_cast<int>(C.rows());
  set_map_result(out, ce, m, Q, dt);
  return true;
}

/// The leap-frog's map without velocity-dependent rates: z^2 - (2 + dt^2 mu) z + 1 = 0 for each mu in eig(B) (e), the
/// larger root.
void leapfrog_map_of(RateFormSpectrum& out, const DenseGeneralEigen& e, const Eigen::MatrixXd& Q, double dt) {
  const long m = e.values.size();
  out.map_spectral_radius = 1;
  out.map_eigenvalue = 1;
  out.map_reduced = static_cast<int>(m);
  long arg = -1;
  for (long k = 0; k < m; ++k) {
    const std::complex<double> b = 2.0 + dt * dt * e.values[k], d = std::sqrt(b * b - 4.0);
    for (const std::complex<double> z : {(b + d) / 2.0, (b - d) / 2.0})
      if (std::abs(z) > out.map_spectral_radius) out.map_spectral_radius = std::abs(z), out.map_eigenvalue = z, arg = k;
  }
  out.map_growth = std::log(out.map_spectral_radius) / dt;
  if (arg >= 0) {
    Eigen::VectorXcd v = e.vectors.size() ? Eigen::VectorXcd(e.vectors.col(arg)) : Eigen::VectorXcd();
    if (v.size() && Q.size()) v = Q.cast<std::complex<double>>() * v;
    if (v.size()) out.map_mode = real_mode_shape(v);
  }
}

}  // namespace

template <int Dim>
RateFormSpectrum rate_form_spectrum(const RateFormScheme<Dim>& scheme, const Eigen::VectorXd& y,
                                    const RateFormSpectrumOptions& options) {
  const bool want_mode = options.want_mode;
  if (y.size() != scheme.size())
    throw std::invalid_argument("rate_form_spectrum: state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(scheme.size()));
  check_map_options(options);
  const AtRestIndices at_rest = at_rest_indices(scheme, y);
  const std::vector<int>&ix = at_rest.ix, &iv = at_rest.iv, &iq = at_rest.iq;
  const long nv = static_cast<long>(iv.size());
  require_dense_memory(nv, 8, "rate_form_spectrum");
  RateFormSpectrum out;
  out.states = scheme.size();
  ComplexStepJacobian jac(scheme);
  const SparseMatrix<> J = jac.compute(y);
  if (jac.info() != Status::Successful || !J.coeffs().allFinite()) {
    out.status = Status::NumericalIssue;
    out.reason = "non-finite Jacobian";
    return out;
  }
  const double scale = std::max(J.nonZeros() ? J.coeffs().cwiseAbs().maxCoeff() : 0.0, 1e-300);
  double zero = 0;
  for (const auto& [r, c] : {std::pair{&ix, &ix}, {&ix, &iq}, {&iq, &ix}, {&iq, &iq}})
    if (!r->empty() && !c->empty()) zero = std::max(zero, block(J, *r, *c).cwiseAbs().maxCoeff());
  out.structure_residual = zero / scale;
  if (out.structure_residual > 1e-10) {
    out.status = Status::NumericalIssue;
    out.reason = "J does not have the at-rest block structure (zero blocks " + format_number(out.structure_residual) +
                 " relative)";
    return out;
  }
  const Eigen::MatrixXd Xv = block(J, ix, iv), Jvx = block(J, iv, ix);
  Eigen::MatrixXd Jvv = block(J, iv, iv);
  const Eigen::MatrixXd Jvq = iq.empty() ? Eigen::MatrixXd(nv, 0) : block(J, iv, iq);
  const Eigen::MatrixXd K =
      iq.empty() ? Eigen::MatrixXd(Eigen::MatrixXd::Zero(nv, nv)) : Eigen::MatrixXd(Jvq * block(J, iq, iv));
  Eigen::MatrixXd B = Jvx * Xv + K;
  const double rate = scheme.material().p_wave_speed() / scheme.discretisation().h;  // c_P / h: the scale of lambda
  if (B.cwiseAbs().maxCoeff() <= 1e-10 * rate * rate && Jvv.cwiseAbs().maxCoeff() <= 1e-10 * rate) {
    // Every particle's motion is decoupled from every other's and from its own displacement: no pair lies inside
    // the kernel support (2h <= the spacing; at 2h = dx exactly, the rounding of the lattice positions leaves
    // couplings ~1e-30 of c_P^2/h^2, while a real neighbour at 0.98 of the support already gives ~1e-3), so the
    // "spectrum" is zeros for no physical reason (the same rule as the critical-load routes: NaN, numerical-issue).
    out.status = Status::NumericalIssue;
    out.lambda = {std::nan(""), std::nan("")};
    out.reason = "no particle interacts with another: no neighbour inside the kernel support (2h = " +
                 format_number(scheme.discretisation().kernel.support_radius(scheme.discretisation().h)) + ")";
    return out;
  }
  const Eigen::MatrixXd& Q = options.basis;
  if (Q.size() && Q.rows() != nv)
    throw std::invalid_argument("rate_form_spectrum: basis has " + std::to_string(Q.rows()) + " rows, expected " +
                                std::to_string(nv) + " (free velocity DOFs)");
  const bool leapfrog_map = options.map_dt > 0 && options.map_integrator == RateFormIntegrator::Leapfrog;
  if (options.map_dt > 0 && !leapfrog_map)  // the predictor-corrector's map, before B and Jvv are restricted below
    if (!predictor_corrector_map(out, Xv, Jvx, Jvq, K, Jvv, Q, options)) return out;
  if (Q.size()) {  // restrict to the invariant subspace
    const Eigen::MatrixXd BQ = B * Q, Bc = Q.transpose() * BQ;
    const double norm = std::max(B.norm(), 1e-300);
    out.invariance_residual = (BQ - Q * Bc).norm() / norm;
    B = Bc;
    Jvv = Q.transpose() * Jvv * Q;
  }
  const long m = B.rows();
  const bool damped = Jvv.size() > 0 && Jvv.cwiseAbs().maxCoeff() > 0;
  if (leapfrog_map && damped)
    out.map_reason = "the leap-frog map is reduced only without velocity-dependent rates at rest (Jvv = 0)";
  Eigen::MatrixXd M;
  if (damped) {
    M = Eigen::MatrixXd::Zero(2 * m, 2 * m);
    M.topRightCorner(m, m).setIdentity();
    M.bottomLeftCorner(m, m) = B;
    M.bottomRightCorner(m, m) = Jvv;
  } else {
    M = B;
  }
  out.reduced = static_cast<int>(M.rows());
  const DenseGeneralEigen e = general_eigen(M, want_mode || options.mode_targets.size() > 0 || leapfrog_map);
  if (e.status != Status::Successful) {
    out.status = e.status;
    out.reason = "dgeev failed (info " + std::to_string(e.lapack_info) + ")";
    return out;
  }
  // Eigenvalues of J: the companion's directly, or +-sqrt(mu).
  out.eigenvalues.resize(2 * m);
  for (long k = 0; k < M.rows(); ++k) {
    if (damped) {
      out.eigenvalues[k] = e.values[k];
    } else {
      const std::complex<double> s = std::sqrt(e.values[k]);
      out.eigenvalues[2 * k] = s;
      out.eigenvalues[2 * k + 1] = -s;
    }
  }
  if (leapfrog_map && !damped && options.map_leapfrog_xsph > 0) {
    if (!leapfrog_xsph_map(out, scheme, B, Q, options)) return out;
  } else if (leapfrog_map && !damped) {
    leapfrog_map_of(out, e, Q, options.map_dt);
  }
  long best = 0;
  for (long k = 1; k < out.eigenvalues.size(); ++k)
    if (out.eigenvalues[k].real() > out.eigenvalues[best].real()) best = k;
  out.lambda = out.eigenvalues[best];
  out.growth_rate = out.lambda.real();
  auto shape = [&](long k) {  // k indexes out.eigenvalues
    const long col = damped ? k : k / 2;
    Eigen::VectorXcd v = e.vectors.col(col).head(m);  // companion: the top half is v
    if (Q.size()) v = Q.cast<std::complex<double>>() * v;
    return real_mode_shape(v);
  };
  if (want_mode) out.mode = shape(best);
  const long targets = options.mode_targets.size();
  if (targets > 0) {
    out.modes.resize(Q.size() ? Q.rows() : m, targets);
    out.mode_eigenvalues.resize(targets);
    for (long t = 0; t < targets; ++t) {
      long near = 0;
      for (long k = 1; k < out.eigenvalues.size(); ++k)
        if (std::abs(out.eigenvalues[k] - options.mode_targets[t]) <
            std::abs(out.eigenvalues[near] - options.mode_targets[t]))
          near = k;
      out.mode_eigenvalues[t] = out.eigenvalues[near];
      out.modes.col(t) = shape(near);
    }
  }
  out.status = Status::Successful;
  out.reason = std::string(damped ? "companion [[0, I], [B, Jvv]]" : "lambda = +-sqrt(eig(B))") +
               (Q.size() ? " in the given class" : "") + ", " + std::to_string(out.reduced) + " x " +
               std::to_string(out.reduced) + " from " + std::to_string(out.states) + " states";
  return out;
}

template RateFormSpectrum rate_form_spectrum<1>(const RateFormScheme<1>&, const Eigen::VectorXd&,
                                                const RateFormSpectrumOptions&);
template RateFormSpectrum rate_form_spectrum<2>(const RateFormScheme<2>&, const Eigen::VectorXd&,
                                                const RateFormSpectrumOptions&);

}  // namespace sphstab
