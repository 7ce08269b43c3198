// Speed of one rate-form SPH right-hand side y' = F(y) (RateFormScheme<2>::rate, plain SPH: continuity by
// summation, no XSPH, viscosity or artificial stress) on periodic 2D square lattices, N = 1e4, 99 856, 1e6,
// h = 1.3 and 1.5 dx, cubic spline, steel at volume strain 1.02. The library (route Fused) keeps its scratch between
// calls (a mutable workspace) and, for these plain forms, no per-pair arrays: one neighbour row at a time it gathers
// r, |r|^2 into short row arrays, computes |r| and grad W over the row (the cubic spline written out, two pairs at a
// time), then sums the row on unpacked per-particle arrays (sigma / rho^2 once per particle). Against it:
//   - FusedPrealloc: the reference copy of the library's OLD algorithm (before commit 01c0a1c: per-pair arrays r,
//     grad W, W, r^2 for every stored pair in a first pass, then the pair loop), with its buffers kept between calls
//     (the old library allocated them on every call). Fused vs FusedPrealloc is what dropping the per-pair arrays
//     gained, both without per-call allocation; the old library's allocation cost is in the committed run before
//     that commit (results/rate-form-speed/benchmark_before.json);
//   - FusedOnePass: one pass, grad W computed where it is used, no per-pair arrays and no W, the particle data
//     packed into one 64 B record per particle with sigma / rho^2 precomputed;
//   - FusedOnePassCubic: the same with the cubic spline's gradient written out (no Kernel::d1 family switch);
//   - FusedHalfPairs: the same visiting each unordered pair once and scattering to both particles;
//   - Operator: the operator-matrix route: G^a re-assembled at the current positions into fixed storage
//     (assemble_operators_into), then two sparse x dense products and pointwise work;
//   - OperatorSpMV: the products alone on an assembled G (the cost left if G were not re-assembled);
// plus the neighbour rebuild (find_neighbours) and a STREAM triad in the same run as the bandwidth reference.
// The library before and after its row-pipeline change, in the same run (one evaluation per particle, on the same
// state; LibraryBefore is bitwise checked against the library before timing):
//   - LibraryBefore: the reference copy of RateFormScheme<2>::evaluate as it was before that change, for the plain
//     gradient with symmetric momentum on free particles (W and grad W recomputed in every pass that reads them,
//     sigma_j / rho_j^2 per pair, f^n and the per-particle artificial stress through models/artificial_stress);
//     plain SPH as Fused;
//   - Gms, GmsBefore: the library and LibraryBefore in the full Gray-Monaghan-Swift configuration of the plate, rings
//     and slab scenes (divergence continuity, XSPH 0.5, viscosity on compression alpha 0.06 beta 1.5, artificial
//     stress 0.3 with n = 4), rho0 = K = 1, mu = 0.22 at volume strain 1.02 (tension), h = 1.5 dx only.
//
//   build/bin/rate_form_step_benchmark [--self-check] [--max-side N] [google-benchmark flags]
//   (results/rate-form-speed: --benchmark_out=.../benchmark.json --benchmark_out_format=json, then
//    benchmarks/rate_form_step_report.py writes benchmark.md; the whole run takes ~3 min on 2 cores)
//
// Every route is checked against RateFormScheme::rate on a perturbed state (both continuity forms) before it is
// timed; a difference above 1e-12 (relative, per state block) skips the benchmark with an error. --self-check runs
// the same checks on small lattices and exits 0 / 1. Counters: particles, h_over_dx, pairs (ordered i != j),
// nl_bytes (index structure read per step: neighbour list and CSR indices) and model_bytes (all data read or
// written per step, each array once per pass that touches it); bytes_per_second = model_bytes / time; page_faults
// and system_s (getrusage minor faults and system CPU seconds per step, the cost of fresh allocations).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "sphstab/forms/rate_form.hpp"
#include "sphstab/models/artificial_stress.hpp"
#include "sphstab/neighbours/neighbour_list.hpp"
#include "sphstab/operators/operators.hpp"
#include "sphstab/particles/lattice.hpp"
#include "stream_triad.hpp"

namespace {

using namespace sphstab;
using Vec2 = Eigen::Vector2d;
using Mat2 = Eigen::Matrix2d;
using Scheme = RateFormScheme<2>;

constexpr double kXi = 1.02;       // volume strain: a pressurised lattice, so the stress terms are not trivial
constexpr double kTol = 1e-12;     // relative agreement demanded of every route
constexpr double kPerturb = 1e-2;  // relative size of the random state perturbation

ElasticMaterial steel() { return ElasticMaterial::from_young_poisson(2.1, 0.3, 7.8); }

/// The Gray-Monaghan-Swift configuration of the plate, rings and slab scenes, and their material.
RateFormOptions gms_options() {
  return {.continuity = ContinuityForm::Divergence,
          .xsph = 0.5,
          .viscosity = ViscositySwitch::Compression,
          .viscosity_alpha = 0.06,
          .viscosity_beta = 1.5,
          .artificial_stress = 0.3,
          .artificial_stress_exponent = 4};
}
ElasticMaterial gms_material() { return ElasticMaterial::from_bulk_shear(1.0, 0.22, 1.0); }

/// The routes below implement only the plain subset on an all-free (periodic) set without driven particles.
void require_subset(const Scheme& s, const char* who) {
  const RateFormOptions& o = s.options();
  const Discretisation<2>& d = s.discretisation();
  const bool plain_pairing = o.momentum == RateFormMomentum::Symmetric || o.momentum == RateFormMomentum::Antisymmetric;
  if (o.xsph != 0 || o.viscosity != ViscositySwitch::Off || o.artificial_stress != 0 ||
      o.gradient != RateFormGradient::Plain || !plain_pairing || d.free_count() != d.size() ||
      !s.driven_particles().empty())
    throw std::invalid_argument(std::string(who) + ": plain SPH on free, undriven particles only");
}

/// sigma = S - p I of the particle whose (rho, Sxx, Syy, Sxy) start at offset ro.
Mat2 sigma_at(const Scheme& s, const Eigen::VectorXd& y, int ro) {
  const ElasticMaterial& m = s.material();
  const double pressure = m.bulk_modulus() * (y[ro] / m.density() - 1.0);
  Mat2 sig;
  sig << y[ro + 1] - pressure, y[ro + 3], y[ro + 3], y[ro + 2] - pressure;
  return sig;
}

/// Jaumann rate of the stored deviator (3 x 3 with D_zz = 0, as the library), written at dydt[ro + 1 ..].
void write_jaumann(const Scheme& s, const Eigen::VectorXd& y, int ro, const Mat2& L, Eigen::VectorXd& dydt) {
  const double mu = s.material().mu();
  const Mat2 D = 0.5 * (L + L.transpose()), W = 0.5 * (L - L.transpose());
  Mat2 dev;
  dev << y[ro + 1], y[ro + 3], y[ro + 3], y[ro + 2];
  const double tr = D.trace();
  const Mat2 ds = 2.0 * mu * (D - (tr / 3.0) * Mat2::Identity()) + W * dev - dev * W;
  dydt[ro + 1] = ds(0, 0);
  dydt[ro + 2] = ds(1, 1);
  dydt[ro + 3] = ds(0, 1);
}

/// The per-particle arrays of the routes that read the state into arrays first (FusedPrealloc, LibraryBefore), kept
/// between calls: the state's positions, velocities, densities and stored deviators, and the work arrays; and the
/// write-out of the rates.
struct ParticleArrays {
  std::vector<Vec2> m_x, m_v, m_vhat;
  std::vector<double> m_rho, m_vol;
  std::vector<Eigen::Vector3d> m_S;
  std::vector<Mat2> m_sigma, m_R;

  void resize(long n) {
    m_x.resize(n), m_v.resize(n), m_vhat.resize(n), m_rho.resize(n), m_vol.resize(n), m_S.resize(n);
    m_sigma.resize(n), m_R.resize(n);
  }

  /// m_x, m_v, m_rho, m_S of the state y (the layout of s).
  void unpack(const Scheme& s, const Eigen::VectorXd& y) {
    for (int i = 0; i < static_cast<int>(m_x.size()); ++i) {
      const int xo = s.position_offset(i), ro = s.density_offset(i);
      m_x[i] = y.segment<2>(xo);
      m_v[i] = y.segment<2>(xo + 2);
      m_rho[i] = y[ro];
      m_S[i] = y.segment<3>(ro + 1);
    }
  }

  /// Particle i's rates into dydt: position m_vhat[i], velocity acc, density drho, stored deviator (Jaumann, from L).
  void write_rates(const Scheme& s, const Eigen::VectorXd& y, int i, const Vec2& acc, double drho, const Mat2& L,
                   Eigen::VectorXd& dydt) const {
    const int xo = s.position_offset(i), ro = s.density_offset(i);
    dydt.segment<2>(xo) = m_vhat[i];
    dydt.segment<2>(xo + 2) = acc;
    dydt[ro] = drho;
    write_jaumann(s, y, ro, L, dydt);
  }
};

/// The library's OLD algorithm for the plain subset (RateFormScheme::evaluate, double, Dim 2, before commit 01c0a1c):
/// per-pair arrays r, grad W, W, r^2 filled for every stored pair, then the pair loop reading grad W back. Kept as
/// the reference copy of that algorithm, with its buffers kept between calls (the old library allocated them on
/// every call); the library itself no longer materialises per-pair arrays for these forms.
class FusedPrealloc : ParticleArrays {
 public:
  explicit FusedPrealloc(const Scheme& s) : m_s(s) {
    require_subset(s, "FusedPrealloc");
    const long n = s.discretisation().size(), nnz = s.discretisation().neighbours.nonzeros();
    resize(n);
    m_rij.resize(nnz), m_grad.resize(nnz), m_w.resize(nnz), m_r2s.resize(nnz);
  }

  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    const Discretisation<2>& d = m_s.discretisation();
    const ParticleSet<2>& p = d.particles;
    const NeighbourList& nl = d.neighbours;
    const int n = p.size();
    const double h = d.h, rho0 = m_s.material().density(), K = m_s.material().bulk_modulus();
    const Eigen::VectorXd& mass = m_s.mass();
    unpack(m_s, y);
    Vec2 box;
    for (int a = 0; a < 2; ++a) box[a] = p.box_hi[a] - p.box_lo[a];
    for (int i = 0; i < n; ++i)
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) {
          m_rij[k].setZero();
          m_grad[k].setZero();
          m_w[k] = d.kernel.value(0.0, h);
          m_r2s[k] = 0;
          continue;
        }
        Vec2 r = m_x[i] - m_x[j];
        for (int a = 0; a < 2; ++a)
          if (p.periodic[a]) {
            if (r[a] > 0.5 * box[a])
              r[a] -= box[a];
            else if (r[a] < -0.5 * box[a])
              r[a] += box[a];
          }
        const double r2 = r[0] * r[0] + r[1] * r[1], rr = std::sqrt(r2);
        m_rij[k] = r;
        m_r2s[k] = r2;
        m_w[k] = d.kernel.value(rr, h);
        m_grad[k] = (d.kernel.d1(rr, h) / rr) * r;
      }
    for (int i = 0; i < n; ++i) m_vol[i] = mass[i] / m_rho[i];
    for (int i = 0; i < n; ++i) m_vhat[i] = m_v[i];
    for (int i = 0; i < n; ++i) {
      const double pressure = K * (m_rho[i] / rho0 - 1.0);
      Mat2 s;
      s << m_S[i][0], m_S[i][2], m_S[i][2], m_S[i][1];
      m_sigma[i] = s - pressure * Mat2::Identity();
      m_R[i].setZero();
    }
    dydt.setZero(m_s.size());
    const bool summation = m_s.options().continuity == ContinuityForm::Summation;
    for (int i = 0; i < n; ++i) {
      Mat2 L = Mat2::Zero();
      double drho = 0;
      Vec2 acc = Vec2::Zero();
      const Mat2 si = m_sigma[i] / (m_rho[i] * m_rho[i]);
      for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        const Vec2 dv = m_vhat[j] - m_vhat[i];
        L += (m_vol[j] * dv) * m_grad[k].transpose();
        if (summation) drho -= mass[j] * dv.cwiseProduct(m_grad[k]).sum();
        const Mat2 sj = m_sigma[j] / (m_rho[j] * m_rho[j]);
        acc += mass[j] * ((si + sj) * m_grad[k]);  // the library adds a zero pair matrix: exact
      }
      if (!summation) drho = -m_rho[i] * L.trace();
      write_rates(m_s, y, i, acc, drho, L, dydt);
    }
  }

 private:
  const Scheme& m_s;
  std::vector<Vec2> m_rij, m_grad;
  std::vector<double> m_w, m_r2s;
};

/// RateFormScheme<2>::evaluate (double) before the row-pipeline change, for the plain gradient with symmetric (or
/// antisymmetric, the same for the plain gradient) momentum on free particles, every other option as the library ran
/// it: the reference copy of that code (its scratch kept between calls, as the library kept it). Per pair it computed
/// |r_ij| and W_ij in the XSPH pass, then again |r_ij|, grad W_ij (and W_ij for the artificial stress) in the row
/// pass, sigma_j / rho_j^2 and f_ij^n (through artificial_stress_pair_factor) per pair, and R_i through
/// artificial_stress() (with its principal angle).
class LibraryBefore : ParticleArrays {
 public:
  explicit LibraryBefore(const Scheme& s) : m_s(s) {
    const RateFormOptions& o = s.options();
    const Discretisation<2>& d = s.discretisation();
    const bool pairing = o.momentum == RateFormMomentum::Symmetric || o.momentum == RateFormMomentum::Antisymmetric;
    // Without driven particles the library's rates are those of the code copied here (driven particles came later).
    if (o.gradient != RateFormGradient::Plain || !pairing || d.free_count() != d.size() ||
        !s.driven_particles().empty())
      throw std::invalid_argument("LibraryBefore: plain gradient, symmetric pairing, free undriven particles only");
    if (o.artificial_stress > 0) m_w_dp = d.kernel.value(d.particles.spacing, d.h);
    const int n = d.size();
    resize(n);
  }

  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    const Discretisation<2>& d = m_s.discretisation();
    const ParticleSet<2>& p = d.particles;
    const NeighbourList& nl = d.neighbours;
    const Kernel<2>& kernel = d.kernel;
    const int n = p.size();
    const double h = d.h, rho0 = m_s.material().density(), K = m_s.material().bulk_modulus();
    const RateFormOptions& o = m_s.options();
    const Eigen::VectorXd& mass = m_s.mass();
    unpack(m_s, y);
    Vec2 box;
    for (int a = 0; a < 2; ++a) box[a] = p.box_hi[a] - p.box_lo[a];
    const auto geometry = [&](int i, int j, Vec2& r, double& r2, double& rr) {
      r = m_x[i] - m_x[j];
      for (int a = 0; a < 2; ++a)
        if (p.periodic[a]) {
          const double L = p.box_hi[a] - p.box_lo[a], dr = r[a];
          if (dr > 0.5 * L)
            r[a] -= box[a];
          else if (dr < -0.5 * L)
            r[a] += box[a];
        }
      r2 = 0;
      for (int a = 0; a < 2; ++a) r2 += r[a] * r[a];
      rr = std::sqrt(r2);
    };
    for (int i = 0; i < n; ++i) m_vol[i] = mass[i] / m_rho[i];
    for (int i = 0; i < n; ++i) {  // XSPH
      m_vhat[i] = m_v[i];
      if (o.xsph > 0)
        for (long k = nl.offsets[i]; k < nl.offsets[i + 1]; ++k) {
          const int j = nl.indices[k];
          if (j == i) continue;
          Vec2 r;
          double r2, rr;
          geometry(i, j, r, r2, rr);
          const double wk = kernel.value(rr, h);
          m_vhat[i] += (o.xsph * mass[j] * wk / (0.5 * (m_rho[i] + m_rho[j]))) * (m_v[j] - m_v[i]);
        }
    }
    for (int i = 0; i < n; ++i) {  // stress, artificial stress
      const double pressure = K * (m_rho[i] / rho0 - 1.0);
      Mat2 st;
      st << m_S[i][0], m_S[i][2], m_S[i][2], m_S[i][1];
      m_sigma[i] = st - pressure * Mat2::Identity();
      m_R[i].setZero();
      if (o.artificial_stress > 0) {
        const SymmetricTensor2<double> t{m_sigma[i](0, 0), m_sigma[i](1, 1), m_sigma[i](0, 1)};
        const SymmetricTensor2<double> r = artificial_stress(t, m_rho[i], o.artificial_stress);
        m_R[i] << r.xx, r.xy, r.xy, r.yy;
      }
    }
    dydt.setZero(m_s.size());
    const bool viscous = o.viscosity != ViscositySwitch::Off;
    const double c0 = m_s.material().sound_speed(), eta2 = 0.01 * h * h;
    for (int i = 0; i < n; ++i) {
      Mat2 L = Mat2::Zero();
      double drho = 0;
      Vec2 acc = Vec2::Zero();
      const Mat2 si = m_sigma[i] / (m_rho[i] * m_rho[i]);
      const long k0 = nl.offsets[i], k1 = nl.offsets[i + 1];
      const std::size_t len = static_cast<std::size_t>(k1 - k0);
      if (m_row_grad.size() < len)
        m_row_grad.resize(len), m_row_r.resize(len), m_row_r2.resize(len), m_row_w.resize(len);
      for (long k = k0; k < k1; ++k) {  // grad W (and r, r^2, W) of the row
        const int j = nl.indices[k];
        if (j == i) continue;
        Vec2 r;
        double r2, rr;
        geometry(i, j, r, r2, rr);
        m_row_grad[k - k0] = (kernel.d1(rr, h) / rr) * r;
        if (viscous) {
          m_row_r[k - k0] = r;
          m_row_r2[k - k0] = r2;
        }
        if (o.artificial_stress > 0) m_row_w[k - k0] = kernel.value(rr, h);
      }
      for (long k = k0; k < k1; ++k) {
        const int j = nl.indices[k];
        if (j == i) continue;
        const Vec2& gk = m_row_grad[k - k0];
        const Vec2 dv = m_vhat[j] - m_vhat[i];
        L += (m_vol[j] * dv) * gk.transpose();
        if (o.continuity == ContinuityForm::Summation) drho -= mass[j] * dv.cwiseProduct(gk).sum();
        Mat2 pair = Mat2::Zero();
        if (viscous) {
          const Vec2 vij = m_v[i] - m_v[j];
          const double vr = vij.cwiseProduct(m_row_r[k - k0]).sum();
          if (o.viscosity == ViscositySwitch::Always || vr < 0) {
            const double mu_ij = h * vr / (m_row_r2[k - k0] + eta2), rho_bar = 0.5 * (m_rho[i] + m_rho[j]);
            double pi = -o.viscosity_alpha * c0 * mu_ij;
            if (o.viscosity == ViscositySwitch::Compression) pi += o.viscosity_beta * mu_ij * mu_ij;
            pair -= (pi / rho_bar) * Mat2::Identity();
          }
        }
        if (o.artificial_stress > 0) {
          const double f = artificial_stress_pair_factor<double>(m_row_w[k - k0], m_w_dp, o.artificial_stress_exponent);
          pair += f * (m_R[i] + m_R[j]);
        }
        const Mat2 sj = m_sigma[j] / (m_rho[j] * m_rho[j]);
        acc += mass[j] * ((si + sj + pair) * gk);
      }
      if (o.continuity == ContinuityForm::Divergence) drho = -m_rho[i] * L.trace();
      write_rates(m_s, y, i, acc, drho, L, dydt);
    }
  }

 private:
  const Scheme& m_s;
  double m_w_dp = 1;
  std::vector<Vec2> m_row_grad, m_row_r;
  std::vector<double> m_row_r2, m_row_w;
};

/// Values of a and b whose bits differ (a different size counts every value).
long differing_values(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return std::max(a.size(), b.size());
  long d = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k) d += std::memcmp(&a[k], &b[k], sizeof(double)) != 0;
  return d;
}

/// (dW/dr) / r of the cubic spline (support 2h) written out: no kernel-family switch, and in the inner zone
/// f'(s)/s = -3 + 9/4 s needs no division.
class CubicGradientFactor {
 public:
  CubicGradientFactor(const Kernel<2>& k, double h) : m_h(h), m_c(k.normalisation() / (h * h * h * h)) {}
  double operator()(double r) const {
    const double s = r / m_h, t = 2.0 - s;
    return s < 1.0 ? m_c * (-3.0 + 2.25 * s) : (s < 2.0 ? m_c * (-0.75 * t * t / s) : 0.0);
  }

 private:
  double m_h, m_c;
};

/// One pass over the pairs: grad W where it is used, no per-pair storage and no W (unused by the plain subset).
/// Cubic: the written-out kernel gradient instead of Kernel::d1. Half: each unordered pair once (from the smaller
/// index; the list is symmetric), its contributions scattered to both particles (g_ji = -g_ij).
template <bool Cubic, bool Half>
class FusedOnePass {
 public:
  explicit FusedOnePass(const Scheme& s)
      : m_s(s),
        m_part(s.discretisation().size()),
        m_acc(Half ? s.discretisation().size() : 0),
        m_factor(s.discretisation().kernel, s.discretisation().h) {
    require_subset(s, "FusedOnePass");
    const Kernel<2>& k = s.discretisation().kernel;
    if ((Cubic || Half) && (k.type() != KernelType::CubicSpline || k.scaling() != KernelScaling::Support2h))
      throw std::invalid_argument("FusedOnePass: the written-out gradient is the cubic spline with support 2h");
  }

  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    const Discretisation<2>& d = m_s.discretisation();
    const ParticleSet<2>& p = d.particles;
    const NeighbourList& nl = d.neighbours;
    const int n = p.size();
    const double h = d.h;
    const Eigen::VectorXd& mass = m_s.mass();
    for (int i = 0; i < n; ++i) {
      const int xo = m_s.position_offset(i), ro = m_s.density_offset(i);
      const Mat2 st = sigma_at(m_s, y, ro) / (y[ro] * y[ro]);
      m_part[i] = {{y[xo], y[xo + 1], y[xo + 2], y[xo + 3], st(0, 0), st(1, 1), st(0, 1), mass[i] / y[ro]}};
    }
    double box[2], half[2];
    for (int a = 0; a < 2; ++a) {
      box[a] = p.box_hi[a] - p.box_lo[a];
      half[a] = p.periodic[a] ? 0.5 * box[a] : INFINITY;
    }
    const bool summation = m_s.options().continuity == ContinuityForm::Summation;
    if constexpr (Half) std::fill(m_acc.begin(), m_acc.end(), Acc{});
    for (int i = 0; i < n; ++i) {
      const Particle& a = m_part[i];
      Acc ai{};
      const long k0 =
          Half ? std::upper_bound(nl.indices.begin() + nl.offsets[i], nl.indices.begin() + nl.offsets[i + 1], i) -
                     nl.indices.begin()
               : nl.offsets[i];
      for (long k = k0; k < nl.offsets[i + 1]; ++k) {
        const int j = nl.indices[k];
        if (!Half && j == i) continue;
        const Particle& b = m_part[j];
        double rx = a.f[0] - b.f[0], ry = a.f[1] - b.f[1];
        rx += rx > half[0] ? -box[0] : (rx < -half[0] ? box[0] : 0.0);
        ry += ry > half[1] ? -box[1] : (ry < -half[1] ? box[1] : 0.0);
        const double rr = std::sqrt(rx * rx + ry * ry);
        double f;
        if constexpr (Cubic)
          f = m_factor(rr);
        else
          f = d.kernel.d1(rr, h) / rr;
        const double gx = f * rx, gy = f * ry, dvx = b.f[2] - a.f[2], dvy = b.f[3] - a.f[3];
        const double sxx = a.f[4] + b.f[4], syy = a.f[5] + b.f[5], sxy = a.f[6] + b.f[6];
        const double dvg = dvx * gx + dvy * gy, fx = sxx * gx + sxy * gy, fy = sxy * gx + syy * gy;
        const double vj = b.f[7], mj = mass[j];
        ai.f[0] += vj * dvx * gx, ai.f[1] += vj * dvx * gy, ai.f[2] += vj * dvy * gx, ai.f[3] += vj * dvy * gy;
        ai.f[4] -= mj * dvg;
        ai.f[5] += mj * fx, ai.f[6] += mj * fy;
        if constexpr (Half) {  // dv_ji g_ji^T = dv_ij g_ij^T, dv_ji . g_ji = dv_ij . g_ij, force reversed
          Acc& aj = m_acc[j];
          const double vi = a.f[7], mi = mass[i];
          aj.f[0] += vi * dvx * gx, aj.f[1] += vi * dvx * gy, aj.f[2] += vi * dvy * gx, aj.f[3] += vi * dvy * gy;
          aj.f[4] -= mi * dvg;
          aj.f[5] -= mi * fx, aj.f[6] -= mi * fy;
        }
      }
      if constexpr (Half) {
        for (int c = 0; c < 7; ++c) m_acc[i].f[c] += ai.f[c];  // every pair (j < i) has already been scattered
        ai = m_acc[i];
      }
      const int xo = m_s.position_offset(i), ro = m_s.density_offset(i);
      Mat2 L;
      L << ai.f[0], ai.f[1], ai.f[2], ai.f[3];
      dydt[xo] = a.f[2], dydt[xo + 1] = a.f[3], dydt[xo + 2] = ai.f[5], dydt[xo + 3] = ai.f[6];
      dydt[ro] = summation ? ai.f[4] : -y[ro] * L.trace();
      write_jaumann(m_s, y, ro, L, dydt);
    }
  }

 private:
  struct alignas(64) Particle {
    double f[8];  // x, y, vx, vy, (sigma / rho^2) xx, yy, xy, V = m / rho: one cache line per gathered neighbour
  };
  struct alignas(64) Acc {
    double f[8] = {};  // L (xx, xy, yx, yy), drho, acc x, y
  };
  const Scheme& m_s;
  std::vector<Particle> m_part;
  std::vector<Acc> m_acc;
  CubicGradientFactor m_factor;
};

/// The operator-matrix route. G^a_ij = dW/dx_i^a V_j carries the REFERENCE volume V_j, so the weights m_j / rho_j
/// and m_j enter through the vectors multiplied: with q_j = m_j / (rho_j V_j), p_j = m_j / V_j, s = sigma / rho^2,
///   L^ab_i   = (G^b (q v^a))_i - v^a_i (G^b q)_i
///   a^a_i    = sum_b (G^b (p s^ab))_i + s^ab_i (G^b p)_i
///   drho_i   = -sum_b (G^b (p v^b))_i - v^b_i (G^b p)_i   (summation)   or   -rho_i tr L_i (divergence)
/// i.e. per axis b one product of G^b with N x 7 columns (row-major, so a neighbour's row is one contiguous gather).
class OperatorRoute {
 public:
  static constexpr int kCols = 7;
  using Block = Eigen::Matrix<double, Eigen::Dynamic, kCols, Eigen::RowMajor>;

  explicit OperatorRoute(const Scheme& s) : m_s(s) {
    require_subset(s, "OperatorRoute");
    const int n = s.discretisation().size();
    m_x.resize(n, 2);
    for (int b = 0; b < 2; ++b) m_in[b].resize(n, kCols), m_out[b].resize(n, kCols);
    assemble(s.uniform_state());
  }

  void assemble(const Eigen::VectorXd& y) {
    const Discretisation<2>& d = m_s.discretisation();
    for (int i = 0; i < d.size(); ++i) m_x.row(i) = y.segment<2>(m_s.position_offset(i)).transpose();
    assemble_operators_into<2, double>(m_ops, d.particles, d.neighbours, d.kernel, d.h,
                                       {.kernel = false, .gradient = true, .hessian = false}, &m_x);
  }

  void products(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    const Discretisation<2>& d = m_s.discretisation();
    const int n = d.size();
    const Eigen::VectorXd &mass = m_s.mass(), &V = d.particles.volume;
    for (int j = 0; j < n; ++j) {
      const int xo = m_s.position_offset(j), ro = m_s.density_offset(j);
      const double rho = y[ro], vx = y[xo + 2], vy = y[xo + 3], q = mass[j] / (rho * V[j]), pm = mass[j] / V[j];
      const Mat2 st = sigma_at(m_s, y, ro) / (rho * rho);
      m_in[0].row(j) << q * vx, q * vy, q, pm * st(0, 0), pm * st(1, 0), pm, pm * vx;
      m_in[1].row(j) << q * vx, q * vy, q, pm * st(0, 1), pm * st(1, 1), pm, pm * vy;
    }
    for (int b = 0; b < 2; ++b) m_out[b].noalias() = m_ops.G[b] * m_in[b];
    if (dydt.size() != m_s.size()) dydt.resize(m_s.size());
    const bool summation = m_s.options().continuity == ContinuityForm::Summation;
    for (int i = 0; i < n; ++i) {
      const int xo = m_s.position_offset(i), ro = m_s.density_offset(i);
      const double rho = y[ro];
      const Vec2 v = y.segment<2>(xo + 2);
      const Mat2 st = sigma_at(m_s, y, ro) / (rho * rho);
      Mat2 L;
      Vec2 acc = Vec2::Zero();
      double drho = 0;
      for (int b = 0; b < 2; ++b) {
        const auto o = m_out[b].row(i);
        for (int a = 0; a < 2; ++a) {
          L(a, b) = o[a] - v[a] * o[2];
          acc[a] += o[3 + a] + st(a, b) * o[5];
        }
        drho -= o[6] - v[b] * o[5];
      }
      if (!summation) drho = -rho * L.trace();
      dydt.segment<2>(xo) = v;
      dydt.segment<2>(xo + 2) = acc;
      dydt[ro] = drho;
      write_jaumann(m_s, y, ro, L, dydt);
    }
  }

  void rate(const Eigen::VectorXd& y, Eigen::VectorXd& dydt) {
    assemble(y);
    products(y, dydt);
  }

 private:
  const Scheme& m_s;
  Operators<2> m_ops;
  Positions<2> m_x;
  Block m_in[2], m_out[2];
};

/// Max over the state blocks (x', v', rho', S') of |a - b|_inf / |b|_inf.
double relative_difference(const Scheme& s, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  double diff[4] = {0, 0, 0, 0}, ref[4] = {0, 0, 0, 0};
  auto take = [&](int blk, int off, int len) {
    for (int c = 0; c < len; ++c) {
      diff[blk] = std::max(diff[blk], std::abs(a[off + c] - b[off + c]));
      ref[blk] = std::max(ref[blk], std::abs(b[off + c]));
    }
  };
  for (int i = 0; i < s.discretisation().size(); ++i) {
    take(0, s.position_offset(i), 2);
    take(1, s.velocity_offset(i), 2);
    take(2, s.density_offset(i), 1);
    take(3, s.stress_offset(i), 3);
  }
  double worst = 0;
  for (int blk = 0; blk < 4; ++blk) worst = std::max(worst, ref[blk] > 0 ? diff[blk] / ref[blk] : diff[blk]);
  return a.size() == b.size() && std::isfinite(worst) ? worst : INFINITY;
}

/// The uniform state with random displacements (kPerturb dx), velocities (kPerturb c0), densities (kPerturb rho)
/// and deviators (kPerturb K).
Eigen::VectorXd perturbed_state(const Scheme& s, unsigned seed) {
  Eigen::VectorXd y = s.uniform_state();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-kPerturb, kPerturb);
  const double dx = s.discretisation().particles.spacing, c0 = s.material().sound_speed(),
               K = s.material().bulk_modulus();
  for (int i = 0; i < s.discretisation().size(); ++i) {
    for (int a = 0; a < 2; ++a) y[s.position_offset(i) + a] += u(rng) * dx;
    for (int a = 0; a < 2; ++a) y[s.velocity_offset(i) + a] = u(rng) * c0;
    y[s.density_offset(i)] *= 1 + u(rng);
    for (int c = 0; c < 3; ++c) y[s.stress_offset(i) + c] += u(rng) * K;
  }
  return y;
}

std::shared_ptr<const Discretisation<2>> lattice(int side, double h_over_dx) {
  const Kernel<2> k(KernelType::CubicSpline);
  return make_discretisation(make_lattice<2>(LatticeType::Square, side, {.spacing = 1.0, .periodic = true}), k,
                             h_over_dx);
}

struct Checks {
  double prealloc = 0, one_pass = 0, cubic = 0, half = 0, op = 0;  // worst over both continuity forms
  // LibraryBefore against the library: values whose bits differ, plain SPH and the GMS configuration (both
  // continuity forms each), and the values compared.
  long before_plain = 0, before_gms = 0, compared = 0;
  bool all_within(double tol) const {
    return prealloc <= tol && one_pass <= tol && cubic <= tol && half <= tol && op <= tol && before_plain == 0 &&
           before_gms == 0;
  }
};

/// Every route against RateFormScheme::rate on a perturbed state, both continuity forms.
Checks check_routes(const std::shared_ptr<const Discretisation<2>>& disc, unsigned seed) {
  Checks c;
  for (ContinuityForm form : {ContinuityForm::Summation, ContinuityForm::Divergence}) {
    const Scheme s(disc, steel(), {.continuity = form}, steel().density() / kXi);
    const Eigen::VectorXd y = perturbed_state(s, seed);
    Eigen::VectorXd ref, f = Eigen::VectorXd::Zero(s.size());
    s.rate(y, ref);
    FusedPrealloc(s).rate(y, f);
    c.prealloc = std::max(c.prealloc, relative_difference(s, f, ref));
    f.setZero();
    FusedOnePass<false, false>(s).rate(y, f);
    c.one_pass = std::max(c.one_pass, relative_difference(s, f, ref));
    f.setZero();
    FusedOnePass<true, false>(s).rate(y, f);
    c.cubic = std::max(c.cubic, relative_difference(s, f, ref));
    f.setZero();
    FusedOnePass<true, true>(s).rate(y, f);
    c.half = std::max(c.half, relative_difference(s, f, ref));
    f.setZero();
    OperatorRoute(s).rate(y, f);
    c.op = std::max(c.op, relative_difference(s, f, ref));
    f.setZero();
    LibraryBefore(s).rate(y, f);
    c.before_plain += differing_values(f, ref);
    c.compared += ref.size();
    RateFormOptions go = gms_options();
    go.continuity = form;
    const Scheme g(disc, gms_material(), go, gms_material().density() / kXi);
    const Eigen::VectorXd yg = perturbed_state(g, seed + 1);
    g.rate(yg, ref);
    LibraryBefore(g).rate(yg, f);
    c.before_gms += differing_values(f, ref);
    c.compared += ref.size();
  }
  return c;
}

enum class Route {
  Fused,
  FusedPrealloc,
  FusedOnePass,
  FusedOnePassCubic,
  FusedHalfPairs,
  Operator,
  OperatorSpMV,
  Rebuild,
  LibraryBefore,
  Gms,
  GmsBefore
};
constexpr Route kRoutes[] = {Route::Fused,
                             Route::LibraryBefore,
                             Route::Gms,
                             Route::GmsBefore,
                             Route::FusedPrealloc,
                             Route::FusedOnePass,
                             Route::FusedOnePassCubic,
                             Route::FusedHalfPairs,
                             Route::Operator,
                             Route::OperatorSpMV,
                             Route::Rebuild};
/// The GMS configuration is timed at h = 1.5 dx only (the scenes' smoothing length).
bool gms_route(Route r) { return r == Route::Gms || r == Route::GmsBefore; }

const char* route_name(Route r) {
  switch (r) {
    case Route::Fused:
      return "Fused";
    case Route::FusedPrealloc:
      return "FusedPrealloc";
    case Route::FusedOnePass:
      return "FusedOnePass";
    case Route::FusedOnePassCubic:
      return "FusedOnePassCubic";
    case Route::FusedHalfPairs:
      return "FusedHalfPairs";
    case Route::Operator:
      return "Operator";
    case Route::OperatorSpMV:
      return "OperatorSpMV";
    case Route::Rebuild:
      return "Rebuild";
    case Route::LibraryBefore:
      return "LibraryBefore";
    case Route::Gms:
      return "Gms";
    case Route::GmsBefore:
      return "GmsBefore";
  }
  return "?";
}

struct Problem {
  int side = 0;
  double h_over_dx = 0;
  std::shared_ptr<const Discretisation<2>> disc;
  std::unique_ptr<Scheme> scheme;  // the benchmarked configuration: continuity by summation
  Eigen::VectorXd y;
  std::unique_ptr<Scheme> gms;  // the GMS configuration (made when a GMS route first needs it)
  Eigen::VectorXd y_gms;
  Checks checks;
};

std::unique_ptr<Problem> g_problem;  // one lattice at a time (memory)

Problem& problem(int side, double h_over_dx) {
  if (g_problem && g_problem->side == side && g_problem->h_over_dx == h_over_dx) return *g_problem;
  g_problem.reset();
  auto P = std::make_unique<Problem>();
  P->side = side;
  P->h_over_dx = h_over_dx;
  P->disc = lattice(side, h_over_dx);
  P->scheme = std::make_unique<Scheme>(P->disc, steel(), RateFormOptions{}, steel().density() / kXi);
  P->y = perturbed_state(*P->scheme, 7);
  P->checks = check_routes(P->disc, 7);
  g_problem = std::move(P);
  return *g_problem;
}

/// Data read or written per step by each route (bytes; N particles, E stored pairs incl. self). Each array
/// is counted once per pass that touches it; gathered neighbour data is assumed cached (lattice order keeps the
/// neighbours of a row within +-3 lattice rows). index: the part of it that is neighbour/CSR index structure.
struct Traffic {
  double index = 0, total = 0;
};

Traffic traffic(Route r, double N, double E) {
  const double nl = 8 * N + 4 * E;  // offsets (long) + indices (int)
  // Per particle in both fused library algorithms: y read, x, v, vhat, rho, vol, S, sigma, R written and re-read,
  // dydt zeroed and written (the library now writes and re-reads sigma / rho^2, 32 B, and no longer zeroes dydt:
  // the same bytes).
  const double unpacked = (64 + 2 * (48 + 16 + 24 + 64) + 2 * 64) * N;
  switch (r) {
    case Route::Fused:
      // The library: one pass over the list (a row's indices are read again by its sums, from cache); r, |r|^2,
      // |r|, grad W of one row go to row arrays of at most ~25 entries that stay in cache, so no per-pair traffic.
      return {nl, nl + unpacked};
    case Route::FusedPrealloc:
      // The old algorithm: two passes over the list; rij, grad (16 B), W, r^2 (8 B) written, grad read back.
      return {2 * nl, 2 * nl + 64 * E + unpacked};
    case Route::FusedOnePass:
    case Route::FusedOnePassCubic:
      return {nl, nl + (64 + 2 * 64 + 64) * N};  // y read, 64 B record written and read, dydt written
    case Route::FusedHalfPairs:
      return {nl, nl + (64 + 2 * 64 + 3 * 64 + 64) * N};  // + 64 B accumulators zeroed, updated, read
    case Route::Operator:
      // assemble: list read, set_pattern compares list and both G patterns (8N + 4N + 8E each), 2 x 8E values
      // written; then the products (OperatorSpMV).
      return {nl + 2 * (12 * N + 8 * E) + 2 * (4 * N + 4 * E),
              nl + 2 * (12 * N + 8 * E) + 16 * E + 64 * N + 16 * N + traffic(Route::OperatorSpMV, N, E).total};
    case Route::OperatorSpMV:
      // per axis: CSR indices + values (4N + 12E), 7 columns in and out (2 x 56N); y read twice, dydt written.
      return {2 * (4 * N + 4 * E), 2 * (4 * N + 12 * E + 112 * N) + 3 * 64 * N};
    case Route::Rebuild:
      return {nl, nl};  // the list written (cell-list work not modelled)
    case Route::LibraryBefore:
    case Route::Gms:
    case Route::GmsBefore:
      return {};  // not modelled (timed against each other)
  }
  return {};
}

/// Minor page faults and system CPU seconds of this process so far (the cost of fresh allocations).
std::pair<double, double> faults_and_system_time() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return {static_cast<double>(u.ru_minflt), u.ru_stime.tv_sec + 1e-6 * u.ru_stime.tv_usec};
}

template <class F>
void time_rate(benchmark::State& state, F&& rate, Eigen::VectorXd& dydt) {
  rate();  // first touch of any buffers outside the timing
  const auto before = faults_and_system_time();
  for (auto _ : state) {
    rate();
    benchmark::DoNotOptimize(dydt.data());
    benchmark::ClobberMemory();
  }
  const auto after = faults_and_system_time();
  state.counters["page_faults"] = benchmark::Counter(after.first - before.first, benchmark::Counter::kAvgIterations);
  state.counters["system_s"] = benchmark::Counter(after.second - before.second, benchmark::Counter::kAvgIterations);
}

void bm_route(benchmark::State& state, int side, double h_over_dx, Route r) {
  Problem& P = problem(side, h_over_dx);
  const Scheme& s = *P.scheme;
  const Checks& c = P.checks;
  double check = 0;
  switch (r) {
    case Route::FusedPrealloc:
      check = c.prealloc;
      break;
    case Route::FusedOnePass:
      check = c.one_pass;
      break;
    case Route::FusedOnePassCubic:
      check = c.cubic;
      break;
    case Route::FusedHalfPairs:
      check = c.half;
      break;
    case Route::Operator:
    case Route::OperatorSpMV:
      check = c.op;
      break;
    case Route::LibraryBefore:
      check = static_cast<double>(c.before_plain);  // values that differ bitwise
      break;
    case Route::Gms:
    case Route::GmsBefore:
      check = static_cast<double>(c.before_gms);
      break;
    default:
      break;
  }
  if (r == Route::LibraryBefore || gms_route(r) ? check != 0 : !(check <= kTol)) {
    const std::string msg =
        std::string(route_name(r)) +
        (r == Route::LibraryBefore || gms_route(r)
             ? ": LibraryBefore differs bitwise from RateFormScheme::rate in " +
                   std::to_string(static_cast<long>(check)) + " values"
             : " differs from RateFormScheme::rate by " + std::to_string(check) + " (relative) > 1e-12");
    state.SkipWithError(msg.c_str());
    return;
  }
  if (gms_route(r) && !P.gms) {
    P.gms = std::make_unique<Scheme>(P.disc, gms_material(), gms_options(), gms_material().density() / kXi);
    P.y_gms = perturbed_state(*P.gms, 7);
  }
  Eigen::VectorXd dydt = Eigen::VectorXd::Zero(s.size());
  const Eigen::VectorXd& y = P.y;
  // The route object f is built before the timed loop, which calls f.rate(at, dydt).
  const auto time_route = [&](auto&& f, const Eigen::VectorXd& at) {
    time_rate(
        state, [&] { f.rate(at, dydt); }, dydt);
  };
  switch (r) {
    case Route::Fused:
      time_route(s, y);
      break;
    case Route::FusedPrealloc:
      time_route(FusedPrealloc(s), y);
      break;
    case Route::FusedOnePass:
      time_route(FusedOnePass<false, false>(s), y);
      break;
    case Route::FusedOnePassCubic:
      time_route(FusedOnePass<true, false>(s), y);
      break;
    case Route::FusedHalfPairs:
      time_route(FusedOnePass<true, true>(s), y);
      break;
    case Route::Operator:
      time_route(OperatorRoute(s), y);
      break;
    case Route::OperatorSpMV: {
      OperatorRoute op(s);
      op.assemble(y);
      time_rate(
          state, [&] { op.products(y, dydt); }, dydt);
      break;
    }
    case Route::Rebuild: {
      const Discretisation<2>& d = *P.disc;
      for (auto _ : state) benchmark::DoNotOptimize(find_neighbours(d.particles, d.kernel.support_radius(d.h)));
      break;
    }
    case Route::LibraryBefore:
      time_route(LibraryBefore(s), y);
      break;
    case Route::Gms:
      time_route(*P.gms, P.y_gms);
      break;
    case Route::GmsBefore:
      time_route(LibraryBefore(*P.gms), P.y_gms);
      break;
  }
  const double N = s.discretisation().size(), E = static_cast<double>(s.discretisation().neighbours.nonzeros());
  const Traffic t = traffic(r, N, E);
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(N));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * t.total));
  state.counters["particles"] = N;
  state.counters["h_over_dx"] = h_over_dx;
  state.counters["pairs"] = E - N;
  state.counters["nl_bytes"] = t.index;
  state.counters["model_bytes"] = t.total;
  state.counters["check"] = check;
  if (r == Route::LibraryBefore || gms_route(r)) state.counters["values_compared"] = static_cast<double>(c.compared);
}

/// STREAM triad a = b + s c on 3 x 256 MiB: about the data one 1e6-particle step touches, far beyond cache.

int self_check() {
  int failures = 0;
  for (int side : {12, 20, 33})
    for (double hdx : {1.3, 1.5}) {
      const Checks c = check_routes(lattice(side, hdx), 100 + side);
      const bool ok = c.all_within(kTol);
      failures += !ok;
      std::printf(
          "%s n=%d h/dx=%.1f: relative difference to RateFormScheme::rate: prealloc %.1e, one-pass %.1e, "
          "cubic %.1e, half-pairs %.1e, operator %.1e; LibraryBefore bitwise: %ld (plain) + %ld (GMS) of %ld values "
          "differ\n",
          ok ? "ok  " : "FAIL", side, hdx, c.prealloc, c.one_pass, c.cubic, c.half, c.op, c.before_plain, c.before_gms,
          c.compared);
    }
  {  // the measure must see a real difference: the two continuity forms on one state
    const auto disc = lattice(12, 1.3);
    const Scheme a(disc, steel(), {.continuity = ContinuityForm::Summation}, steel().density() / kXi);
    const Scheme b(disc, steel(), {.continuity = ContinuityForm::Divergence}, steel().density() / kXi);
    const Eigen::VectorXd y = perturbed_state(a, 5);
    Eigen::VectorXd fa, fb;
    a.rate(y, fa);
    b.rate(y, fb);
    const double d = relative_difference(a, fb, fa);
    const bool ok = d > 1e-6;
    failures += !ok;
    std::printf("%s summation vs divergence differ by %.1e (the check discriminates)\n", ok ? "ok  " : "FAIL", d);
  }
  std::printf("%s\n", failures ? "self-check FAILED" : "self-check passed");
  return failures ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  int max_side = 1000;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--self-check") return self_check();
    if (a == "--max-side" && i + 1 < argc)
      max_side = std::stoi(argv[++i]);
    else
      args.push_back(argv[i]);
  }
  int bargc = static_cast<int>(args.size());
  benchmark::Initialize(&bargc, args.data());

  // CPU time (user + system, so page faults count): the 2 cores are shared, and wall time then includes waiting.
  benchmark::RegisterBenchmark("Triad", bench::stream_triad)->Unit(benchmark::kMillisecond)->MinTime(1.0);
  for (int side : {100, 316, 1000}) {
    if (side > max_side) continue;
    for (double hdx : {1.3, 1.5})
      for (Route r : kRoutes) {
        if (gms_route(r) && hdx != 1.5) continue;
        char name[96];
        std::snprintf(name, sizeof(name), "%s/N:%d/h:%.1f", route_name(r), side * side, hdx);
        auto* b = benchmark::RegisterBenchmark(name, [side, hdx, r](benchmark::State& st) {
                    bm_route(st, side, hdx, r);
                  })->Unit(benchmark::kMillisecond);
        // Best of the repetitions is reported (the machine is shared); 1e6 takes up to ~2 s per step.
        if (side >= 1000)
          b->Iterations(2)->Repetitions(3);
        else
          b->MinTime(0.3)->Repetitions(3);
      }
  }
  benchmark::RegisterBenchmark("TriadAgain", bench::stream_triad)->Unit(benchmark::kMillisecond)->MinTime(1.0);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
