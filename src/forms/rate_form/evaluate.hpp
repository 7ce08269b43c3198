#pragma once
/// \file evaluate.hpp
/// Internal to src/forms: RateFormScheme::rate (rate_form.hpp) as one Evaluation (evaluation.hpp) and the loop that
/// sums its pairs: the pair loop (PairLoop::Pairs, real states, pair_loop.hpp), the plain row loop (plain_rows.hpp) or
/// the corrected-gradient and local-means loop (corrected_rows.hpp); then the absorbing particles' condition. Included
/// by the translation units that instantiate rate() (rate_form_rate_*.cpp), one dimension and scalar each, so that
/// they compile side by side.
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <complex>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "corrected_rows.hpp"
#include "dispatch.hpp"
#include "evaluation.hpp"
#include "pair_loop.hpp"
#include "plain_rows.hpp"

namespace sphstab {

namespace rate_form_detail {

/// PairLoop::Pairs: each pair once (pair_loop.hpp), then each particle's rates from its sums. `deferred`: e has not
/// unpacked the state (the pair loop's region does, particle by particle).
template <int Dim>
void run_pairs(Evaluation<Dim, double>& e, bool deferred) {
  auto& ws = e.ws;
  const int n = e.n;
  const RateFormOptions& o = e.o;
  if (e.bulk) e.bulk_pressure(nullptr);  // every q before the stresses
  e.size_stresses();
  e.dydt.resize(e.scheme.size());
  ws.acc.resize(n);
  ws.L.resize(n);
  ws.drho.resize(n);
  ws.xsph_moves.resize(n);
  const double support = e.kernel.support_radius(e.h);
  PairLoopArrays<Dim> A{.n = n,
                        .offsets = e.nl.offsets.data(),
                        .upper = e.upper.data(),
                        .indices = e.nl.indices.data(),
                        .x = ws.x.data(),
                        .v = ws.v.data(),
                        .rho = ws.rho.data(),
                        .vol = ws.vol.data(),
                        .mass = e.mass.data(),
                        .sigma_rho2 = ws.sigma_rho2.data(),
                        .R = ws.R.data(),
                        .xsph_moves = ws.xsph_moves.data(),
                        .half_box = e.separation.half_box,
                        .support2 = support * support,
                        .h = e.h,
                        .eta2 = e.eta2,
                        .alpha_c0 = -o.viscosity_alpha * e.c0,
                        .beta = o.viscosity_beta,
                        .xsph = o.xsph,
                        .summation = o.continuity == ContinuityForm::Summation,
                        .vhat = ws.vhat.data(),
                        .acc = ws.acc.data(),
                        .L = ws.L.data(),
                        .drho = ws.drho.data()};
  for (int a = 0; a < Dim; ++a) A.box[a] = e.p.box_hi[a] - e.p.box_lo[a];
  if (!ws.pair_loop) ws.pair_loop = std::make_shared<PairLoopScratch<Dim>>();
  auto& scratch = *static_cast<PairLoopScratch<Dim>*>(ws.pair_loop.get());
  // In the pair loop's parallel region (one region from the stresses to the rates; a refused artificial stress is
  // rethrown after it): each particle's stresses and whether it moves with XSPH before the sweeps, each chunk's rates
  // once its sums are complete.
  const auto prepare = [&](int i) {
    if (deferred) e.unpack(i);
    e.stress(i);
    ws.xsph_moves[i] = e.x_off[i] >= 0 && !e.is_driven(i);
  };
  const auto done = [&](int a, int b) {
    for (int i = a; i < b; ++i)
      if (e.summed(i)) e.finish(i, e.x_off[i] >= 0, ws.L[i], ws.drho[i], ws.acc[i]);
  };
  with_kernel_functions(e.kernel, e.h, [&](const auto& kf) {
    with_term_tags(o.viscosity, o.artificial_stress > 0, [&](auto viscosity_tag, auto stress_tag) {
      constexpr ViscositySwitch kV = decltype(viscosity_tag)::value;
      constexpr bool kS = decltype(stress_tag)::value;
      if (o.xsph > 0)
        pair_loop<Dim, kV, kS, true>(A, kf, e.pair_factor, scratch, e.threads, 0, prepare, done);
      else
        pair_loop<Dim, kV, kS, false>(A, kf, e.pair_factor, scratch, e.threads, 0, prepare, done);
    });
  });
}

}  // namespace rate_form_detail

template <int Dim>
template <class Scalar>
void RateFormScheme<Dim>::evaluate(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y,
                                   Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const {
  // The pair loop unpacks the state in its own region, unless the bulk viscosity needs every velocity first.
  const bool pairs = std::is_same_v<Scalar, double> && m_options.pair_loop == PairLoop::Pairs && !m_exchange;
  const bool bulk = m_options.bulk_viscosity_quadratic > 0 || m_options.bulk_viscosity_linear > 0;
  rate_form_detail::Evaluation<Dim, Scalar> e(*this, y, dydt, !pairs || bulk);
  if constexpr (std::is_same_v<Scalar, double>) {
    if (pairs) return rate_form_detail::run_pairs(e, !bulk);
  }
  if (m_options.gradient == RateFormGradient::Plain && !rate_form_detail::uses_local_means(m_options.momentum)) {
    if (e.bulk) e.bulk_pressure(nullptr);
    e.stresses();
    dydt.resize(m_size);
    rate_form_detail::plain_rows(e);
  } else {
    rate_form_detail::corrected_rows(e);
  }
}

template <int Dim>
template <class Scalar>
void RateFormScheme<Dim>::absorb(const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y,
                                 Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& dydt) const {
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  using std::sqrt;
  const Discretisation<Dim>& d = *m_disc;
  const ParticleSet<Dim>& p = d.particles;
  const NeighbourList& nl = d.neighbours;
  const Kernel<Dim>& kernel = d.kernel;
  const double h = d.h;
  const bool ncsph = m_options.gradient == RateFormGradient::Ncsph || m_absorbing.normalised;
  const double c_p = m_material.p_wave_speed(), c_s = std::sqrt(m_material.mu() / m_material.density());
  const auto position = [&](int j) -> Vec {
    return m_x_off[j] >= 0 ? Vec(y.template segment<Dim>(m_x_off[j]))
                           : Vec(p.x.row(j).transpose().template cast<Scalar>());
  };
  const auto velocity = [&](int j) -> Vec {
    return m_x_off[j] >= 0 ? Vec(y.template segment<Dim>(m_x_off[j] + Dim)) : Vec::Zero();
  };
  const auto volume = [&](int j) -> Scalar {
    return m_mass[j] / (m_rho_off[j] >= 0 ? y[m_rho_off[j]] : Scalar(m_density));
  };
  std::vector<int> js;
  std::vector<Vec> rs, gs;
  std::vector<Scalar> ws;
  for (std::size_t q = 0; q < m_absorbing.particles.size(); ++q) {
    const int i = m_absorbing.particles[q];
    const Eigen::Matrix<double, Dim, 1>& normal = m_absorbing.normals[q];
    const double scale = m_absorbing.speed_scale.empty() ? 1.0 : m_absorbing.speed_scale[q];
    const Vec xi = position(i), vi = velocity(i);
    if (m_absorbing.condition == AbsorbingCondition::ViscousTraction) {  // (2.75): adds to the momentum equation
      dydt.template segment<Dim>(m_x_off[i] + Dim) +=
          viscous_traction_acceleration<Scalar, Dim>(scale * c_p, scale * c_s, normal, vi, m_absorbing.traction_depth);
      continue;
    }
    // The neighbours used, r = x_i - x_j (minimum image), V_j grad_i W_ij and V_j W_ij.
    js.clear(), rs.clear(), gs.clear(), ws.clear();
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      Vec r = xi - position(j);
      for (int a = 0; a < Dim; ++a) {
        if (!p.periodic[a]) continue;
        const double L = p.box_hi[a] - p.box_lo[a], dr = detail::re(r[a]);
        if (dr > 0.5 * L) r[a] -= L;
        if (dr < -0.5 * L) r[a] += L;
      }
      // Upwind (2.67): only the interior side, (x_j - x_i) . n <= 0.
      Scalar along(0);
      for (int a = 0; a < Dim; ++a) along -= r[a] * normal[a];
      if (m_absorbing.upwind && j != i && detail::re(along) > 1e-9 * h) continue;
      const Scalar r2 = (r.array() * r.array()).sum(), rr = sqrt(r2), vj = volume(j);  // not squaredNorm: |r_a|^2
      js.push_back(j);
      rs.push_back(r);
      gs.push_back(j == i ? Vec(Vec::Zero()) : Vec((vj * kernel.d1(rr, h) / rr) * r));
      ws.push_back(vj * (j == i ? Scalar(kernel.value(0.0, h)) : kernel.value(rr, h)));
    }
    if (ncsph) {
      // Powell (1.19) over the neighbours used: Shepard gradient, then the inverse moment matrix.
      Scalar shep(0);
      Vec g = Vec::Zero();
      for (std::size_t t = 0; t < js.size(); ++t) shep += ws[t], g += gs[t];
      Mat M = Mat::Zero();
      for (std::size_t t = 0; t < js.size(); ++t) {
        gs[t] = (gs[t] * shep - ws[t] * g) / (shep * shep);
        M -= rs[t] * gs[t].transpose();
      }
      const Eigen::Matrix<double, Dim, Dim> Mr = M.unaryExpr([](const Scalar& z) { return detail::re(z); });
      const Eigen::JacobiSVD<Eigen::Matrix<double, Dim, Dim>> svd(Mr);
      if (!Mr.allFinite() || !(svd.singularValues()(Dim - 1) > 1e-12 * svd.singularValues()(0)))
        throw std::domain_error("RateFormScheme: NCSPH moment matrix of absorbing particle " + std::to_string(i) +
                                " is singular or not finite" + (m_absorbing.upwind ? " (upwind neighbours)" : ""));
      const Mat Minv_t = M.inverse().transpose();
      for (Vec& gt : gs) gt = Minv_t * gt;
    }
    Mat L = Mat::Zero();  // Powell (1.33) with the sign of rate_form.hpp: L^ab = sum_j (v_j^a - v_i^a) Ghat_ij^b
    for (std::size_t t = 0; t < js.size(); ++t) L += (velocity(js[t]) - vi) * gs[t].transpose();
    Vec a;
    if constexpr (Dim == 1) {
      a[0] = absorbing_acceleration_1d(scale * c_p, normal[0], L(0, 0), vi[0], m_absorbing.convective);
    } else {
      a = absorbing_acceleration<Scalar>(m_absorbing.condition, scale * c_p, scale * c_s, normal, L, vi,
                                         m_absorbing.convective);
    }
    dydt.template segment<Dim>(m_x_off[i] + Dim) = a;
  }
}

template <int Dim>
void RateFormScheme<Dim>::rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) const {
  evaluate(y, dydt);
  if (!m_absorbing.empty()) absorb(y, dydt);
  if (m_exchange) m_exchange(dydt);
}

template <int Dim>
void RateFormScheme<Dim>::rate(const Eigen::VectorXcd& y, Eigen::VectorXcd& dydt) const {
  evaluate(y, dydt);
  if (!m_absorbing.empty()) absorb(y, dydt);
}

}  // namespace sphstab
