// No include guard: included by pair_lanes.hpp once per instruction set, inside a namespace that defines V (the
// vector of doubles), Mask (its comparison result) and vsqrt. Lanes are independent: lane q of every operation
// below is the scalar operation of the functions pair_lanes.hpp names, in their order.

constexpr std::size_t kLanes = sizeof(V) / sizeof(double);
static_assert(kMaxPairLanes % kLanes == 0, "pair_lanes: a row's arrays reach to a whole number of vectors");

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

/// The row's scalars (pair_lanes.hpp) by whole vectors: the last one reaches past len (PairLaneRow).
template <ViscositySwitch kViscosity, bool kStress, bool kXsph>
void row(const PairLaneConstants& k, const PairLaneRow& p) {
  for (std::size_t q = 0; q < p.len; q += kLanes)
    block<kViscosity, kStress, kXsph>(k, p.rho_i, p.r2 + q, p.vr + q, p.rhoj + q, p.w + q, p.gf + q, p.f + q, p.ib + q,
                                      p.c + q);
}
