// Seed-003 multi-range force curve of up to NC cells. Bit-exact spec of
// rtl/force_curve.v.
//
// Input: HallDeltaToken (hall_baseline's output) of sensors ID_BASE ..
// ID_BASE + NC - 1, one sensor per cell. Per token:
//   p_a = (d_a * g_a + 32) >> 6          g_a: per-axis uT/LSB in UQ4.12 (16 bits);
//                                        p_a: field change in 1/64 uT (arith. shift,
//                                        round half up); the radicand below needs
//                                        |p_a| < 2^23, i.e. |dB| < 1.3 T per axis
//   m   = isqrt(p_x^2 + p_y^2 + p_z^2)   |dB| in 1/64 uT, floor, 24-bit root of a
//                                        48-bit radicand (one bit per step)
//   k   = the last breakpoint with db[k] <= m (k = 0 when m < db[0]; at most
//         NB - 2, so beyond the last breakpoint the last slope continues)
//   F   = sat32(f[k] + round_half_up((m - db[k]) * slope[k] >> 16))   mN
//   range = the index of the first lock force >= F (0, 1, 2, ...)
// Curve per cell: NB breakpoints db (1/64 uT, ascending), f (mN), slope
// (mN per 1/64 uT in Q15.16, from the builder hls/force_curve_config.h).
// Output ForceToken {cell, t, force_mn, range, flags}.
// RTL timing: out_valid NB + 33 cycles after the input handshake (schedule
// in rtl/force_curve.v).
#pragma once

#include <cstdint>

#include "hls/hall_token.h"

namespace eskin::hls {

struct ForceToken {
  uint8_t cell = 0;
  uint32_t t = 0;
  int32_t force_mn = 0;
  uint8_t range = 0;
  uint8_t flags = 0;
};

template <int NB>
struct ForceCurveTable {
  int32_t db[NB] = {};     // 1/64 uT, ascending
  int32_t f[NB] = {};      // mN
  int32_t slope[NB] = {};  // mN per 1/64 uT, Q15.16 (segment k: db[k]..db[k+1])
};

template <int NB, int NR>
struct ForceCurveConfig {
  uint16_t gain[3] = {0, 0, 0};  // UQ4.12 uT per LSB of each axis
  int32_t lock_mn[NR] = {};      // range ends (mN), ascending
};

// floor(sqrt(x)) for x < 2^48, one result bit per step (restoring).
inline uint32_t isqrt48(uint64_t x) {
  uint64_t rem = 0, root = 0;
  for (int i = 23; i >= 0; --i) {
    rem = (rem << 2) | ((x >> (2 * i)) & 3u);
    const uint64_t trial = (root << 2) | 1u;
    if (rem >= trial) rem -= trial, root = (root << 1) | 1u;
    else root <<= 1;
  }
  return uint32_t(root);
}

template <int NC, int NB = 13, int NR = 3, int ID_BASE = 0>
class ForceCurve {
  static_assert(NC >= 1 && NC <= 64, "NC: 1..64 cells");
  static_assert(NB >= 2 && NB <= 32, "NB: 2..32 breakpoints");
  static_assert(NR >= 1 && NR <= 8, "NR: 1..8 ranges");

 public:
  explicit ForceCurve(const ForceCurveConfig<NB, NR>& c) : cfg_(c) {}
  ForceCurveTable<NB>& table(int cell) { return tab_[cell]; }

  // |dB| in 1/64 uT of a token (the RTL's first stage).
  uint32_t magnitude(const HallDeltaToken& in) const {
    uint64_t s = 0;
    for (int a = 0; a < 3; ++a) {
      const int32_t p = (int32_t(in.d[a]) * int32_t(cfg_.gain[a]) + 32) >> 6;
      s += uint64_t(int64_t(p) * int64_t(p));
    }
    return isqrt48(s);
  }

  bool push(const HallDeltaToken& in, ForceToken& out) {
    const int c = int(in.id) - ID_BASE;
    if (c < 0 || c >= NC) return false;
    const int32_t m = int32_t(magnitude(in));
    const ForceCurveTable<NB>& t = tab_[c];
    int k = 0;
    for (int i = 1; i < NB - 1; ++i)
      if (t.db[i] <= m) k = i;
    const int64_t x = (int64_t(m) - int64_t(t.db[k])) * int64_t(t.slope[k]);
    const int64_t f = int64_t(t.f[k]) + ((x + (int64_t(1) << 15)) >> 16);
    out.cell = uint8_t(c);
    out.t = in.t;
    out.force_mn = int32_t(f > 2147483647LL ? 2147483647LL : f < -2147483648LL ? -2147483648LL : f);
    uint8_t r = 0;
    for (int i = 0; i < NR; ++i)
      if (out.force_mn > cfg_.lock_mn[i]) r = uint8_t(i + 1);
    out.range = uint8_t(r < NR ? r : NR - 1);
    out.flags = in.flags;
    return true;
  }

 private:
  ForceCurveConfig<NB, NR> cfg_;
  ForceCurveTable<NB> tab_[NC];
};

}  // namespace eskin::hls
