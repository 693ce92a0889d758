// Seed-001 3D force decoupling parameters Rx, Ry, Sz on the FPGA. Bit-exact
// spec of rtl/hall_decouple.v. The golden model (host/golden/hall_decouple.h)
// states the formulas; here they are evaluated without division:
//   Rx = atan2(2 Bx z1, z1^2 + By^2 - Bx^2),  Ry = atan2(2 By z1, z1^2 + Bx^2 - By^2)
//   Sz = ln sqrt(N^2 + (2 By z2)^2) - ln(2 z2),  N = z2^2 - By^2 + Bx^2
// with z1 = k1 Bz + c1, z2 = k2 Bz + c2 (the seed's Bz', Bz'').
//
// Input: HallDeltaToken of sensor ID (the film field, geomagnetic baseline
// removed by hall_baseline). Fixed point, all arithmetic shifts round half up
// (+2^(s-1) then >>, on two's complement):
//   B_a  = (d_a * g_a + 2^9) >> 10      g_a: uT/LSB in UQ16.16, g_a < 2^20
//                                        (<= 16 uT/LSB); B_a in 1/64 uT, |B_a| < 2^25
//   z    = ((Bz * k) + 2^13 >> 14) + c  k: Q2.14 (int16), c: 1/64 uT, |c| < 2^26,
//                                        so |z| < 2^27 and every square or product
//                                        below fits 56 bits
//   guard: z1 > 0, z2 > 0, both atan2 denominators > 0, else valid = 0 and
//          Rx = Ry = Sz = 0 (no division happens anywhere: nothing to trap)
//   squares and products: 50 bits signed (int64 here)
//   atan2(y, x), x > 0: both shifted right by the same s >= 0 so that
//          max(|x|, |y|) < 2^30, then 24 CORDIC vectoring steps with angles
//          round(atan(2^-i) 2^24); result in Q8.24 rad (error <= 2^-22 rad plus
//          the input rounding)
//   ln r, r > 0 (62-bit): e = index of r's top bit, m = r normalised to Q1.30,
//          log2(m) by 24 squarings (one fraction bit each, the square truncated
//          to Q1.30), ln r = round((e << 24 | frac) * ln2_q30 >> 30) in Q8.24
//   |v| of (x, y) for Sz: the CORDIC magnitude x_n ~ K |v| (K = 1.64676...),
//          so ln |v| = ln x_n - ln K (ln K as a Q8.24 constant); Sz is
//          returned for B in uT (minus ln 64, a constant) like the golden
// Output DecoupleToken {t, rx, ry, sz (Q8.24), valid, flags}.
// RTL timing: a fixed schedule per token (asserted in tests/rtl).
#pragma once

#include <cstdint>

#include "hls/hall_token.h"

namespace eskin::hls {

struct DecoupleToken {
  uint32_t t = 0;
  int32_t rx = 0, ry = 0, sz = 0;  // Q8.24
  bool valid = false;
  uint8_t flags = 0;
};

struct HallDecoupleConfig {
  uint32_t gain[3] = {0, 0, 0};  // UQ16.16 uT per LSB
  int16_t k1 = 1 << 14, k2 = 1 << 14;  // Q2.14
  int32_t c1 = 0, c2 = 0;        // 1/64 uT
};

constexpr int kCordicSteps = 24;
// round(atan(2^-i) * 2^24), i = 0..23.
constexpr int32_t kCordicAtan[kCordicSteps] = {
    13176795, 7778716, 4110060, 2086331, 1047214, 524117, 262123, 131069,
    65536,    32768,   16384,   8192,    4096,    2048,   1024,   512,
    256,      128,     64,      32,      16,      8,      4,      2};
constexpr int64_t kLn2Q30 = 744261118;        // round(ln 2 * 2^30)
constexpr int32_t kLnCordicGainQ24 = 8368641;  // round(ln(prod sqrt(1 + 2^-2i)) * 2^24), 24 steps
constexpr int32_t kLn64Q24 = 69774480;         // round(ln 64 * 2^24): B in 1/64 uT -> Sz in ln(uT)

inline int64_t shr_round(int64_t v, int s) { return s > 0 ? (v + (int64_t(1) << (s - 1))) >> s : v; }

// Halves x and y (arithmetic shifts) until both are inside (-2^30, 2^30);
// returns the number of halvings (the RTL spends one cycle on each).
inline int cordic_prescale(int64_t& x, int64_t& y) {
  int s = 0;
  while ((x >= (int64_t(1) << 30)) || (y >= (int64_t(1) << 30)) || (y <= -(int64_t(1) << 30))) {
    x >>= 1;
    y >>= 1;
    ++s;
  }
  return s;
}

// CORDIC vectoring of (x, y), x > 0: returns the angle (Q8.24) and leaves
// the scaled magnitude in x.
inline int32_t cordic_vector(int64_t& x, int64_t y, int* halvings = nullptr) {
  const int s = cordic_prescale(x, y);
  if (halvings) *halvings = s;
  int32_t z = 0;
  for (int i = 0; i < kCordicSteps; ++i) {
    const int64_t xs = x >> i, ys = y >> i;
    if (y >= 0) x += ys, y -= xs, z += kCordicAtan[i];
    else x -= ys, y += xs, z -= kCordicAtan[i];
  }
  x <<= s;  // magnitude back on the input scale (low bits lost, state in the header)
  return z;
}

// ln(r) in Q8.24 for r >= 1 (r < 2^62).
inline int32_t ln_q24(uint64_t r) {
  int e = 63;
  while (!((r >> e) & 1u)) --e;
  // Mantissa in Q1.30: r / 2^e in [1, 2).
  uint64_t m = e >= 30 ? (r >> (e - 30)) : (r << (30 - e));
  uint32_t frac = 0;
  for (int i = 0; i < 24; ++i) {
    m = (m * m) >> 30;  // Q2.30 after squaring a Q1.30 value
    frac <<= 1;
    if (m >= (uint64_t(2) << 30)) {
      m >>= 1;
      frac |= 1u;
    }
  }
  const int64_t log2_q24 = (int64_t(e) << 24) | int64_t(frac);
  return int32_t(shr_round(log2_q24 * kLn2Q30, 30));
}

template <int ID = 0>
class HallDecouple {
 public:
  explicit HallDecouple(const HallDecoupleConfig& c) : cfg_(c) {}

  // The prescale halvings of the last token's three vectors (the RTL's
  // variable part of the latency), -1 where no CORDIC ran.
  int halvings(int i) const { return halv_[i]; }

  bool push(const HallDeltaToken& in, DecoupleToken& out) {
    if (in.id != ID) return false;
    halv_[0] = halv_[1] = halv_[2] = -1;
    out = DecoupleToken{};
    out.t = in.t;
    out.flags = in.flags;
    int64_t b[3];
    for (int a = 0; a < 3; ++a) b[a] = shr_round(int64_t(in.d[a]) * int64_t(cfg_.gain[a]), 10);
    const int64_t z1 = shr_round(b[2] * cfg_.k1, 14) + cfg_.c1;
    const int64_t z2 = shr_round(b[2] * cfg_.k2, 14) + cfg_.c2;
    const int64_t bx2 = b[0] * b[0], by2 = b[1] * b[1];
    const int64_t den_x = z1 * z1 + by2 - bx2, den_y = z1 * z1 + bx2 - by2;
    if (z1 <= 0 || z2 <= 0 || den_x <= 0 || den_y <= 0) return true;
    int64_t x = den_x;
    out.rx = cordic_vector(x, 2 * b[0] * z1, &halv_[0]);
    x = den_y;
    out.ry = cordic_vector(x, 2 * b[1] * z1, &halv_[1]);
    const int64_t n = z2 * z2 - by2 + bx2;
    int64_t mag = n < 0 ? -n : n;
    const int64_t y = 2 * b[1] * z2;
    if (mag == 0 && y == 0) return true;  // a zero vector has no logarithm
    if (mag == 0) mag = 1;                // keep x > 0: angle irrelevant, magnitude ~ |y|
    cordic_vector(mag, y, &halv_[2]);
    out.sz = ln_q24(uint64_t(mag)) - kLnCordicGainQ24 - ln_q24(uint64_t(2 * z2)) - kLn64Q24;
    out.valid = true;
    return true;
  }

 private:
  HallDecoupleConfig cfg_;
  int halv_[3] = {-1, -1, -1};
};

}  // namespace eskin::hls
