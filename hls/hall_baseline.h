// Hall baseline (geomagnetic / rest field) subtraction. Bit-exact spec of
// rtl/hall_baseline.v.
//
// Input: HallSampleToken (hls/hall_token.h) of sensors ID_BASE ..
// ID_BASE + NS - 1 (other ids are dropped and counted). Codes become signed
// values v = code - offset[axis] (offset 0: the code is two's complement).
// Tokens without data (flags & 0x78) are dropped and counted.
// Capture: each sensor sums its first 2^CAPTURE_LOG2 data tokens per axis
// (sum: 16 + CAPTURE_LOG2 <= 31 bits, exact) and keeps
// base = floor((sum + 2^(n-1)) / 2^n) (round half up; arithmetic shift),
// emitting nothing meanwhile. After: out d = sat16(v - base) (the 17-bit
// difference saturated to int16), id, t and flags passed on.
// Commands: set(sensor, axis, value) loads a baseline (and ends that
// sensor's capture: it is "captured" once all three axes were set or
// captured); recapture() restarts every sensor's capture.
// RTL timing: one token per cycle in and out (II = 1), latency 1 cycle.
#pragma once

#include <cstdint>

#include "hls/hall_token.h"

namespace eskin::hls {

struct HallBaselineConfig {
  uint16_t offset[3] = {0, 0, 0};  // per axis: 0 (two's complement), 0x8000 or 0x4000
};

template <int NS, int CAPTURE_LOG2 = 4, int ID_BASE = 0>
class HallBaseline {
  static_assert(NS >= 1 && NS <= 64, "NS: 1..64 sensors");
  static_assert(CAPTURE_LOG2 >= 0 && CAPTURE_LOG2 <= 15, "capture sum must fit 31 bits");
  static_assert(ID_BASE >= 0 && ID_BASE + NS <= 256, "ids are 8 bits");

 public:
  explicit HallBaseline(const HallBaselineConfig& c = {}) : cfg_(c) { recapture(); }

  void recapture() {
    for (int s = 0; s < NS; ++s) {
      count_[s] = 0;
      set_mask_[s] = 0;
      for (int a = 0; a < 3; ++a) sum_[s][a] = 0, base_[s][a] = 0;
    }
  }

  void set(int sensor, int axis, int16_t value) {
    base_[sensor][axis] = value;
    set_mask_[sensor] = uint8_t(set_mask_[sensor] | (1u << axis));
  }

  int16_t baseline(int sensor, int axis) const { return base_[sensor][axis]; }
  bool captured(int sensor) const {
    return count_[sensor] == (1u << CAPTURE_LOG2) || set_mask_[sensor] == 7u;
  }
  uint16_t dropped() const { return dropped_; }

  // Returns true when `out` holds an output token.
  bool push(const HallSampleToken& in, HallDeltaToken& out) {
    const int s = int(in.id) - ID_BASE;
    if (s < 0 || s >= NS || (in.flags & kHallFlagNoData)) {
      if (dropped_ != 0xFFFF) ++dropped_;
      return false;
    }
    const uint16_t code[3] = {in.x, in.y, in.z};
    int32_t v[3];
    for (int a = 0; a < 3; ++a)
      v[a] = cfg_.offset[a] ? int32_t(code[a]) - int32_t(cfg_.offset[a]) : int32_t(int16_t(code[a]));
    if (!captured(s)) {
      for (int a = 0; a < 3; ++a) sum_[s][a] += v[a];
      if (++count_[s] == (1u << CAPTURE_LOG2))
        for (int a = 0; a < 3; ++a)
          if (!(set_mask_[s] & (1u << a)))
            base_[s][a] = int16_t(CAPTURE_LOG2 ? (sum_[s][a] + (int32_t(1) << (CAPTURE_LOG2 - 1))) >> CAPTURE_LOG2
                                               : sum_[s][a]);
      return false;
    }
    out.id = in.id;
    out.t = in.t;
    out.flags = in.flags;
    for (int a = 0; a < 3; ++a) out.d[a] = sat16(v[a] - base_[s][a]);
    return true;
  }

 private:
  HallBaselineConfig cfg_;
  int32_t sum_[NS][3];
  int16_t base_[NS][3];
  uint32_t count_[NS];
  uint8_t set_mask_[NS];
  uint16_t dropped_ = 0;
};

}  // namespace eskin::hls
