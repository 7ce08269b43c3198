// No include guard: included by lanes.hpp once per instruction set, inside a namespace that defines V (the
// vector of doubles), Mask (its comparison result) and vsqrt. Lanes are independent: lane q of every operation
// below is the scalar operation of the functions lanes.hpp names, in their order.

constexpr std::size_t kLanes = sizeof(V) / sizeof(double);
static_assert(kMaxPairLanes % kLanes == 0, "lanes: a row's arrays reach to a whole number of vectors");

SPHSTAB_ALWAYS_INLINE inline V splat(double x) {
  V v;
  for (std::size_t l = 0; l < kLanes; ++l) v[l] = x;
  return v;
}
SPHSTAB_ALWAYS_INLINE inline V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
SPHSTAB_ALWAYS_INLINE inline void store(double* p, V v) { std::memcpy(p, &v, sizeof v); }
/// m ? a : b per lane (m all ones or all zeros).
SPHSTAB_ALWAYS_INLINE inline V select(Mask m, V a, V b) {
  return reinterpret_cast<V>((reinterpret_cast<Mask>(a) & m) | (reinterpret_cast<Mask>(b) & ~m));
}

/// kLanes pairs from q: the arrays of `row` offset by q.
template <ViscositySwitch kViscosity, bool kStress, bool kXsph>
SPHSTAB_ALWAYS_INLINE inline void block(const PairLaneConstants& k, double rho_i, const double* r2, const double* vr,
                                        const double* rhoj, double* w, double* gf, double* f, double* ib, double* c) {
  constexpr bool kViscous = kViscosity != ViscositySwitch::Off;
  const V zero = splat(0.0), one = splat(1.0), two = splat(2.0);
  // CubicFunctions::row_pairs: s = r (1/h); W = c_w ((1 - 1.5 s^2) + (0.75 s^2) s) inside s < 1, c_w 0.25 (a (a a))
  // with a = 2 - s up to s < 2; dW/dr / r = (c_d / h)(-3 + 2.25 s), (-0.75 c_d)(a a) / r; 0 from s >= 2.
  const V r2q = load(r2), r = vsqrt(r2q);
  const V s = r * splat(k.inv_h), a = two - s;
  const Mask outside = s >= two, near = s < one;
  const V aa = a * a, ss = s * s;
  const V w_in = (one - splat(1.5) * ss) + (splat(0.75) * ss) * s;
  const V w_out = splat(0.25) * (a * aa);
  const V wq = splat(k.cw) * select(outside, zero, select(near, w_in, w_out));
  store(w, wq);
  const V g_in = splat(k.cd_h) * (splat(-3.0) + splat(2.25) * s);
  const V g_out = (splat(k.cd_out) * aa) / r;
  store(gf, select(outside, zero, select(near, g_in, g_out)));
  if constexpr (kStress) {  // PairFactor::row_by_reciprocal, n = 4
    const V x = wq * splat(k.inv_w_dp);
    store(f, (x * x) * (x * x));
  }
  if constexpr (kViscous || kXsph) {
    const V ibq = two / (splat(rho_i) + load(rhoj));
    store(ib, ibq);
    if constexpr (kViscous) {  // viscosity_mu, viscosity_pi; the switch on v_ij . r_ij < 0
      const V vrq = load(vr);
      const V mu = (splat(k.h) * vrq) / (r2q + splat(k.eta2));
      V pi = splat(k.alpha_c0) * mu;
      if constexpr (kViscosity == ViscositySwitch::Compression) pi = pi + (splat(k.beta) * mu) * mu;
      const V cq = pi * ibq;
      if constexpr (kViscosity == ViscositySwitch::Compression)
        store(c, select(vrq < zero, cq, zero));
      else
        store(c, cq);
    }
  }
}

/// The row's scalars (lanes.hpp) by whole vectors: the last one reaches past len (PairLaneRow).
template <ViscositySwitch kViscosity, bool kStress, bool kXsph>
void row(const PairLaneConstants& k, const PairLaneRow& p) {
  for (std::size_t q = 0; q < p.len; q += kLanes)
    block<kViscosity, kStress, kXsph>(k, p.rho_i, p.r2 + q, p.vr + q, p.rhoj + q, p.w + q, p.gf + q, p.f + q, p.ib + q,
                                      p.c + q);
}

/// |x| per lane (the sign bit cleared, as std::abs).
SPHSTAB_ALWAYS_INLINE inline V vabs(V x) {
  Mask magnitude;
  for (std::size_t l = 0; l < kLanes; ++l) magnitude[l] = 0x7fffffffffffffffLL;
  return reinterpret_cast<V>(reinterpret_cast<Mask>(x) & magnitude);
}

/// Particles l0 .. l0 + kLanes - 1 of the block (those past count padded with rho = 1, S = 0 and not written).
template <bool kStress>
SPHSTAB_ALWAYS_INLINE inline void stress_vector(const StressLaneConstants& k, const StressLaneBlock& p,
                                                std::size_t l0) {
  V rho, sxx, syy, sxy;
  for (std::size_t l = 0; l < kLanes; ++l) {
    const bool in = l0 + l < p.count;
    rho[l] = in ? p.rho[l0 + l] : 1.0;
    sxx[l] = in ? p.S[3 * (l0 + l)] : 0.0;
    syy[l] = in ? p.S[3 * (l0 + l) + 1] : 0.0;
    sxy[l] = in ? p.S[3 * (l0 + l) + 2] : 0.0;
  }
  const V zero = splat(0.0), one = splat(1.0), two = splat(2.0), half = splat(0.5);
  // eos_pressure() + 0 (no bulk viscosity), then cauchy_stress(): sigma = S - p I entry by entry (p 1 on the
  // diagonal, p 0 off it, as Eigen's expression computes them).
  const V pressure = splat(k.bulk_modulus) * (rho / splat(k.rho0) - one) + zero;
  const V s00 = sxx - pressure * one, s11 = syy - pressure * one, s01 = sxy - pressure * zero;
  const V rho2 = rho * rho;
  const V q00 = s00 / rho2, q11 = s11 / rho2, q01 = s01 / rho2;
  V r00 = zero, r11 = zero, r01 = zero;
  if constexpr (kStress) {
    // particle_artificial_stress<Frame::Read>: the principal frame (principal_frame), then R by its three cases.
    const V mean = half * (s00 + s11), half_diff = half * (s00 - s11);
    const V ad = vabs(half_diff), ax = vabs(s01);
    const V scale = select(ad < ax, ax, ad);  // std::max(|d|, |sxy|)
    const Mask isotropic = ~(scale > zero);
    const V a = half_diff / scale, b = s01 / scale;
    const V root = vsqrt(a * a + b * b);
    const V radius = scale * root;
    const V major = select(isotropic, mean, mean + radius), minor = select(isotropic, mean, mean - radius);
    const V kk = splat(-k.epsilon) / rho2;
    const Mask a_nonneg = a >= zero;
    const V two_root = two * root;
    const V cc = select(a_nonneg, (root + a) / two_root, (b * b) / (two_root * (root - a)));
    const V ss = select(a_nonneg, (b * b) / (two_root * (root + a)), (root - a) / two_root);
    const V sc = b / two_root;
    const V rbar = kk * major;  // back_rotate(f, k major, 0)
    const V rot00 = cc * rbar + ss * zero, rot11 = ss * rbar + cc * zero, rot01 = sc * (rbar - zero);
    const Mask both = minor > zero, tensile = major > zero;
    r00 = select(both, kk * s00, select(tensile, rot00, zero));
    r11 = select(both, kk * s11, select(tensile, rot11, zero));
    r01 = select(both, kk * s01, select(tensile, rot01, zero));
  }
  for (std::size_t l = 0; l < kLanes && l0 + l < p.count; ++l) {
    double* const sigma = p.sigma + 4 * (l0 + l);
    double* const sr = p.sigma_rho2 + 4 * (l0 + l);
    double* const R = p.R + 4 * (l0 + l);
    sigma[0] = s00[l], sigma[1] = s01[l], sigma[2] = s01[l], sigma[3] = s11[l];
    sr[0] = q00[l], sr[1] = q01[l], sr[2] = q01[l], sr[3] = q11[l];
    R[0] = r00[l], R[1] = r01[l], R[2] = r01[l], R[3] = r11[l];
  }
}

/// The block's stresses (lanes.hpp, stress_lanes).
template <bool kStress>
void stresses(const StressLaneConstants& k, const StressLaneBlock& p) {
  for (std::size_t l0 = 0; l0 < p.count; l0 += kLanes) stress_vector<kStress>(k, p, l0);
}
