#pragma once
/// \file evaluation.hpp
/// Internal to src/forms: one evaluation of RateFormScheme::rate (rate_form.hpp). It unpacks the state into
/// per-particle fields, computes what each particle needs before the pair sums (volumes, bulk viscosity, stress,
/// artificial stress) and writes each particle's rates from its sums (finish); the loops between (plain_rows.hpp,
/// corrected_rows.hpp, pair_loop.hpp) sum the pairs. The terms themselves are one file each beside this one.
///
/// Every loop runs the same operations in the same order for any thread count: threads own whole rows and sum them in
/// the serial order (core/threads.hpp); the pair loop's threads own whole chunks of particles (pair_loop.hpp).
#include <Eigen/Core>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "artificial_stress.hpp"
#include "bulk_viscosity.hpp"
#include "continuity.hpp"
#include "equation_of_state.hpp"
#include "jaumann.hpp"
#include "kernel_rows.hpp"
#include "sphstab/core/threads.hpp"
#include "sphstab/forms/rate_form.hpp"

namespace sphstab::rate_form_detail {

/// r_ij = x_i - x_j with the minimum image decided on the real part, and |r_ij|^2 = sum_a r_a^2 (|r_ij| =
/// sqrt(|r_ij|^2)). Small, copied by value into the loops.
template <int Dim, class Scalar>
struct Separation {
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  const Vec* xs = nullptr;
  Vec box;
  std::array<double, Dim> half_box;  // +-L/2 of a periodic axis; +inf otherwise (never crossed)
  SPHSTAB_ALWAYS_INLINE void operator()(int i, int j, Vec& r, Scalar& r2) const {
    r = xs[i] - xs[j];
    for (int a = 0; a < Dim; ++a) {
      const double dr = detail::re(r[a]);
      if (dr > half_box[a])
        r[a] -= box[a];
      else if (dr < -half_box[a])
        r[a] += box[a];
    }
    r2 = Scalar(0);
    for (int a = 0; a < Dim; ++a) r2 += r[a] * r[a];
  }
};

/// One call of rate(): the scheme's data, the workspace (scratch kept by the scheme between calls) and the output.
template <int Dim, class Scalar>
struct Evaluation {
  using Scheme = RateFormScheme<Dim>;
  static constexpr int kStress = Scheme::kStress;
  using Vec = Eigen::Matrix<Scalar, Dim, 1>;
  using Mat = Eigen::Matrix<Scalar, Dim, Dim>;
  using Stress = Eigen::Matrix<Scalar, kStress, 1>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Workspace = typename Scheme::template Workspace<Scalar>;

  /// Unpacks y (fixed particles at their initial positions at rest; frozen ones at the initial rho and S) and the
  /// volumes V_i = m_i / rho_i; with unpack_rows = false the caller unpacks each particle (unpack(i)) in its own
  /// parallel region (the pair loop: one region less per evaluation).
  Evaluation(const Scheme& scheme, const Vector& y, Vector& dydt, bool unpack_rows = true);

  const Scheme& scheme;
  const Discretisation<Dim>& d;
  const ParticleSet<Dim>& p;
  const NeighbourList& nl;
  const Kernel<Dim>& kernel;
  const RateFormOptions& o;
  const int n;
  const double h, rho0, K, mu;
  const double c0, eta2;  // sound speed of the viscosity; eta^2 = 0.01 h^2
  const int threads;
  /// The particles whose rates are computed: a partition's, for real states (set_row_partition).
  const bool partial;
  const int first, last;
  const bool bulk;  // MCM's bulk viscosity acts

  // The scheme's data (rate_form.hpp, private members).
  const std::vector<int>&x_off, &rho_off;  // per particle: offset of x (free only) and of rho (or -1)
  const Eigen::VectorXd& mass;
  const std::vector<long>&upper, &transpose;
  const Eigen::VectorXd& counts;
  const Eigen::VectorXd& shepard_sum;
  const std::vector<Eigen::Matrix<double, Dim, 1>>& shepard_grad;
  const std::vector<char>& in_support;
  const std::vector<bool>& excluded;

  Workspace& ws;
  const Vector& y;
  Vector& dydt;
  Separation<Dim, Scalar> separation;
  PairFactor pair_factor;

  bool is_driven(int i) const { return scheme.is_driven(i); }
  /// Whether particle i has rates (free, or fixed with evolving rho and S).
  bool summed(int i) const { return x_off[i] >= 0 || rho_off[i] >= 0; }

  /// x, v, rho, S and V of particle i from y (the constructor's arrays are sized).
  void unpack(int i);
  /// MCM's bulk viscosity q_i (bulk_viscosity.hpp) from d_i = sum_j (v_j - v_i) . Ghat_ij with the corrected gradient
  /// when one is given (gh, V_j included), else the plain V_j grad W_ij computed here; the self pair adds nothing.
  void bulk_pressure(const std::vector<Vec>* corrected);
  /// sigma = S - (p + q) I, sigma / rho^2 and the artificial stress R of every particle. An artificial stress refused
  /// at rho <= 0 is rethrown after the parallel loop (a run's result, not an abort in the region).
  void stresses();
  /// stresses() of particle i alone (for a loop's own parallel region: size_stresses() first). Throws
  /// std::invalid_argument for an artificial stress refused at rho <= 0.
  void stress(int i);
  void size_stresses() {
    ws.sigma.resize(n);
    ws.sigma_rho2.resize(n);
    ws.R.resize(n);
  }
  /// Writes every rate of particle i from its velocity gradient L, summed density rate and acceleration.
  void finish(int i, bool free, const Mat& L, Scalar drho, const Vec& acc);

 private:
  static Workspace& workspace(const Scheme& s) { return s.m_work.template get<Scalar>(); }
};

template <int Dim, class Scalar>
Evaluation<Dim, Scalar>::Evaluation(const Scheme& s, const Vector& state, Vector& out, bool unpack_rows)
    : scheme(s),
      d(*s.m_disc),
      p(d.particles),
      nl(d.neighbours),
      kernel(d.kernel),
      o(s.m_options),
      n(p.size()),
      h(d.h),
      rho0(s.m_material.density()),
      K(s.m_material.bulk_modulus()),
      mu(s.m_material.mu()),
      c0(s.m_material.sound_speed()),
      eta2(0.01 * h * h),
      threads(threads_for(n)),
      partial(std::is_same_v<Scalar, double> && static_cast<bool>(s.m_exchange)),
      first(partial ? s.m_first : 0),
      last(partial ? s.m_last : n),
      bulk(o.bulk_viscosity_quadratic > 0 || o.bulk_viscosity_linear > 0),
      x_off(s.m_x_off),
      rho_off(s.m_rho_off),
      mass(s.m_mass),
      upper(s.m_upper),
      transpose(s.m_transpose),
      counts(s.m_counts),
      shepard_sum(s.m_shepard_sum),
      shepard_grad(s.m_shepard_grad),
      in_support(s.m_in_support),
      excluded(s.m_excluded),
      ws(workspace(s)),
      y(state),
      dydt(out),
      pair_factor(s.m_w_dp, s.m_options.artificial_stress_exponent) {
  if (y.size() != s.m_size)
    throw std::invalid_argument("RateFormScheme::rate: state has " + std::to_string(y.size()) + " entries, expected " +
                                std::to_string(s.m_size));
  ws.x.resize(n);
  ws.v.resize(n);
  ws.vhat.resize(n);
  ws.rho.resize(n);
  ws.S.resize(n);
  ws.vol.resize(n);
  if (unpack_rows) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (int i = 0; i < n; ++i) unpack(i);
  }
  separation.xs = ws.x.data();
  for (int a = 0; a < Dim; ++a) {
    const double L = p.box_hi[a] - p.box_lo[a];
    separation.box[a] = Scalar(L);
    separation.half_box[a] = p.periodic[a] ? 0.5 * L : std::numeric_limits<double>::infinity();
  }
}

template <int Dim, class Scalar>
void Evaluation<Dim, Scalar>::unpack(int i) {
  if (x_off[i] >= 0) {
    ws.x[i] = y.template segment<Dim>(x_off[i]);
    ws.v[i] = y.template segment<Dim>(x_off[i] + Dim);
  } else {
    ws.x[i] = p.x.row(i).transpose().template cast<Scalar>();
    ws.v[i].setZero();
  }
  if (rho_off[i] >= 0) {
    ws.rho[i] = y[rho_off[i]];
    ws.S[i] = y.template segment<kStress>(rho_off[i] + 1);
  } else {
    ws.rho[i] = Scalar(scheme.m_density);
    ws.S[i] = scheme.m_deviator.template cast<Scalar>();
  }
  ws.vol[i] = mass[i] / ws.rho[i];
}

template <int Dim, class Scalar>
void Evaluation<Dim, Scalar>::bulk_pressure(const std::vector<Vec>* corrected) {
  using std::sqrt;
  const std::vector<Vec>& v = ws.v;
  const std::vector<Scalar>&rho = ws.rho, &vol = ws.vol;
  std::vector<Scalar>& q = ws.bulk_q;
  q.assign(n, Scalar(0));
  const double q1_h = o.bulk_viscosity_quadratic * h, q2_c0 = o.bulk_viscosity_linear * c0;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) {
    Scalar div(0);
    for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
      const int j = nl.indices[k];
      if (j == i) continue;
      const Vec dv = v[j] - v[i];
      if (corrected) {
        div += dv.cwiseProduct((*corrected)[k]).sum();
      } else {
        Vec r;
        Scalar r2;
        separation(i, j, r, r2);
        const Scalar rr = sqrt(r2);
        div += (vol[j] * kernel.d1(rr, h) / rr) * dv.cwiseProduct(r).sum();
      }
    }
    if (detail::re(div) < 0) q[i] = bulk_viscosity_pressure(rho[i], h, q1_h, q2_c0, div);
  }
}

template <int Dim, class Scalar>
void Evaluation<Dim, Scalar>::stresses() {
  size_stresses();
  FirstException first_error;
#pragma omp parallel for schedule(static) num_threads(threads)
  for (int i = 0; i < n; ++i) first_error.run([&] { stress(i); });
  first_error.rethrow();
}

template <int Dim, class Scalar>
void Evaluation<Dim, Scalar>::stress(int i) {
  const Scalar rho = ws.rho[i];
  const Scalar pressure = eos_pressure(K, rho, rho0) + (bulk ? ws.bulk_q[i] : Scalar(0));
  ws.sigma[i] = cauchy_stress<Dim, Scalar>(ws.S[i], pressure);
  ws.sigma_rho2[i] = ws.sigma[i] / (rho * rho);
  if (o.artificial_stress > 0)
    ws.R[i] = particle_artificial_stress<Dim, Scalar>(ws.sigma[i], rho, o.artificial_stress);
  else
    ws.R[i].setZero();
}

template <int Dim, class Scalar>
void Evaluation<Dim, Scalar>::finish(int i, bool free, const Mat& L, Scalar drho, const Vec& acc) {
  if (o.continuity == ContinuityForm::Divergence) drho = continuity_divergence(ws.rho[i], L);
  if (free) {
    dydt.template segment<Dim>(x_off[i]) = ws.vhat[i];
    if (is_driven(i))  // the prescribed acceleration replaces the SPH force
      dydt.template segment<Dim>(x_off[i] + Dim) = scheme.m_driven_acc[scheme.m_driven_slot[i]].template cast<Scalar>();
    else
      dydt.template segment<Dim>(x_off[i] + Dim) = acc;
  }
  if (rho_off[i] < 0) return;
  dydt[rho_off[i]] = drho;
  deviator_rate<Dim, Scalar>(L, ws.S[i], mu, dydt.template segment<kStress>(rho_off[i] + 1));
}

}  // namespace sphstab::rate_form_detail
