// carrier_magnitude: complex window sum {k, re, im} -> magnitude {k, mag}.
// Bit-exact executable spec of the `carrier_magnitude` routine of the frame
// engine (rtl/ucode/dtmf_chain.fe) in rtl/dtmf_top.v, and of the streaming
// block rtl/carrier_magnitude.v (one carrier a clock, push() per token).
//
// Number formats
//   in.re, in.im : signed ACC_W-bit integers (two's complement, ACC_W <= 32),
//                  the sliding-DFT window sums, same units as the sums.
//   out.mag      : unsigned MAG_W-bit integer (MAG_W <= 30), in units of
//                  2^SHIFT sum-LSB:
//                    mag = min(floor(sqrt(re^2 + im^2) / 2^SHIFT + 1/2),
//                              2^MAG_W - 1)
//                  i.e. the exact magnitude, right-shifted by SHIFT, rounded
//                  half up, saturated at full scale.
// Error: |mag - sqrt(re^2+im^2)/2^SHIFT| <= 1/2 LSB whenever not saturated
//   (the result is the correctly rounded value, ties up). Saturation happens
//   iff sqrt(re^2+im^2)/2^SHIFT >= 2^MAG_W - 1/2; with the default
//   SHIFT = ACC_W - MAG_W it never does: |re + j im| <= sqrt(2) 2^(ACC_W-1),
//   so the scaled magnitude is <= 2^MAG_W / sqrt(2) < 2^MAG_W - 1/2.
//
// Method (exact, no approximation): P = re^2 + im^2 (2*ACC_W-1 bits,
//   unsigned), Q = floor(4 P / 4^SHIFT) (= P >> (2 SHIFT - 2), or P << 2
//   when SHIFT = 0), root = floor(sqrt(Q)) by the restoring digit-by-digit
//   square root (one result bit per step), mag = (root + 1) >> 1.
//   Why this rounds correctly: floor(sqrt(floor(y))) = floor(sqrt(y)) for
//   real y >= 0, so root = floor(2 x) with x = sqrt(P)/2^SHIFT, and
//   (floor(2x) + 1) >> 1 = floor(x + 1/2). Only NB = MAG_W + 1 root bits are
//   needed: Q >= 4^NB means root >= 2^NB, i.e. x >= 2^MAG_W: saturate.
//
// Hardware (the frame engine, docs/frame_engine.md): P from 16-bit halves
//   of re and im on the engine's 16x16 multiplier (the SB_MAC16) into its
//   48-bit accumulator, the root by its `sqrt` instruction (the clocks:
//   docs/frame_engine.md). With SHIFT = 0 and demixed inputs (ACC_W = 24:
//   P up to 2^47) 4 P does not fit that accumulator: the routine takes
//   `sqrtr` of P itself, floor(sqrt(P) + 1/2), the same mag. k and last
//   pass through unchanged.
#pragma once

#include <cstdint>

namespace eskin::hls {

struct CarrierMagnitudeIn {
  uint8_t k = 0;      // carrier index (rows first, then columns)
  int32_t re = 0;     // signed ACC_W-bit window sum, real part
  int32_t im = 0;     // signed ACC_W-bit window sum, imaginary part
  bool last = false;  // set on the last carrier of a frame (k = K-1)
};

struct CarrierMagnitudeOut {
  uint8_t k = 0;
  uint32_t mag = 0;   // unsigned MAG_W bits
  bool last = false;
};

// Stateless: no configuration beyond the widths.
struct CarrierMagnitudeConfig {};

template <int ACC_W = 24, int MAG_W = 16, int SHIFT = ACC_W - MAG_W>
struct CarrierMagnitude {
  static_assert(ACC_W >= 2 && ACC_W <= 32, "ACC_W must be 2..32");
  static_assert(MAG_W >= 1 && MAG_W <= 30, "MAG_W must be 1..30");
  static_assert(SHIFT >= 0 && SHIFT <= ACC_W, "SHIFT must be 0..ACC_W");

  static constexpr int NB = MAG_W + 1;  // root bits computed
  static constexpr uint32_t MAG_MAX = (uint32_t(1) << MAG_W) - 1u;

  CarrierMagnitudeConfig cfg;

  // floor(sqrt(q)) for q < 4^NB, restoring method, NB steps (the RTL loop).
  static uint32_t isqrt_steps(uint64_t q) {
    uint64_t rem = 0, root = 0;
    for (int i = NB - 1; i >= 0; --i) {
      rem = (rem << 2) | ((q >> (2 * i)) & 3u);
      const uint64_t trial = (root << 2) | 1u;
      root <<= 1;
      if (rem >= trial) {
        rem -= trial;
        root |= 1u;
      }
    }
    return uint32_t(root);
  }

  static uint32_t magnitude(int32_t re, int32_t im) {
    // |v| <= 2^31 fits uint64; squares <= 2^62, sum <= 2^63: no overflow.
    const uint64_t ar = re < 0 ? uint64_t(0) - uint64_t(int64_t(re)) : uint64_t(re);
    const uint64_t ai = im < 0 ? uint64_t(0) - uint64_t(int64_t(im)) : uint64_t(im);
    const uint64_t p = ar * ar + ai * ai;
    // Q = floor(4 P / 4^SHIFT); P < 2^63, so P << 2 (SHIFT = 0) is checked
    // for overflow of the NB-step range before shifting.
    uint64_t q;
    if (SHIFT == 0) {
      if (p >= (uint64_t(1) << (2 * NB - 2))) return MAG_MAX;
      q = p << 2;
    } else {
      q = p >> (2 * SHIFT - 2);
    }
    if (q >= (uint64_t(1) << (2 * NB))) return MAG_MAX;  // 2 NB <= 62
    const uint32_t mag = (isqrt_steps(q) + 1u) >> 1;
    return mag > MAG_MAX ? MAG_MAX : mag;
  }

  // One output per input; always returns true.
  bool push(const CarrierMagnitudeIn& in, CarrierMagnitudeOut& out) const {
    out.k = in.k;
    out.last = in.last;
    out.mag = magnitude(in.re, in.im);
    return true;
  }
};

}  // namespace eskin::hls
