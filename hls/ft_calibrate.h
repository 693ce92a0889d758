// Six-axis force/torque of seed 002 (MagTac) as W = C * dB. Bit-exact spec
// of rtl/ft_calibrate.v.
//
// Input: HallDeltaToken (hall_baseline's output) of the three cells'
// sensors ID_BASE, ID_BASE + 1, ID_BASE + 2: dB_j = d[j % 3] of sensor j / 3,
// int16 LSB. The latest token of each sensor is kept; the token of sensor
// ID_BASE + 2 closes a frame, which is computed when all three sensors gave a
// token since the last frame (otherwise the frame is skipped and counted).
// C: 6 x 9 entries, int32 in Q(31-C_FRAC).C_FRAC output units per input LSB,
// loaded at run time (load(i, j, v): the LOAD_C command); output units are
// mN for forces and mN*mm for torques (the builder hls/ft_calibrate_config.h
// scales by the sensors' uT/LSB).
// W_i = sat32( round_half_up( sum_j C_ij * dB_j  >> C_FRAC ) ): products
// 32 x 16 -> 48 bits, sum of 9 in 52 bits (int64 here), one rounding.
// Output WrenchToken {t of the closing token, w[6], flags = OR of the three}.
// RTL timing: 54 multiply-accumulate cycles per frame (one 32x16 product per
// cycle, row-major), then the output; inputs are accepted while idle.
#pragma once

#include <cstdint>

#include "hls/hall_token.h"

namespace eskin::hls {

struct WrenchToken {
  uint32_t t = 0;
  int32_t w[6] = {0, 0, 0, 0, 0, 0};
  uint8_t flags = 0;
};

inline int32_t sat32(int64_t v) {
  return int32_t(v > 2147483647LL ? 2147483647LL : v < -2147483648LL ? -2147483648LL : v);
}

template <int C_FRAC = 16, int ID_BASE = 0>
class FtCalibrate {
  static_assert(C_FRAC >= 1 && C_FRAC <= 30, "C_FRAC 1..30");
  static_assert(ID_BASE >= 0 && ID_BASE + 3 <= 256, "ids are 8 bits");

 public:
  FtCalibrate() {
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 9; ++j) c_[i][j] = 0;
    for (int j = 0; j < 9; ++j) db_[j] = 0;
  }
  void load(int i, int j, int32_t v) { c_[i][j] = v; }
  int32_t entry(int i, int j) const { return c_[i][j]; }
  uint16_t skipped() const { return skipped_; }

  // True when `out` holds a wrench.
  bool push(const HallDeltaToken& in, WrenchToken& out) {
    const int s = int(in.id) - ID_BASE;
    if (s < 0 || s > 2) return false;
    for (int a = 0; a < 3; ++a) db_[3 * s + a] = in.d[a];
    seen_ = uint8_t(seen_ | (1u << s));
    flags_ = uint8_t(flags_ | in.flags);
    if (s != 2) return false;
    const bool complete = seen_ == 7u;
    const uint8_t flags = flags_;
    seen_ = 0;
    flags_ = 0;
    if (!complete) {
      if (skipped_ != 0xFFFF) ++skipped_;
      return false;
    }
    for (int i = 0; i < 6; ++i) {
      int64_t acc = 0;
      for (int j = 0; j < 9; ++j) acc += int64_t(c_[i][j]) * int64_t(db_[j]);
      out.w[i] = sat32((acc + (int64_t(1) << (C_FRAC - 1))) >> C_FRAC);
    }
    out.t = in.t;
    out.flags = flags;
    return true;
  }

 private:
  int32_t c_[6][9];
  int16_t db_[9];
  uint8_t seen_ = 0, flags_ = 0;
  uint16_t skipped_ = 0;
};

}  // namespace eskin::hls
