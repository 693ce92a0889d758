// izhikevich_layer: a layer of Izhikevich neurons in fixed point, one neuron
// update per input token, neurons time-multiplexed in address order.
// Bit-exact executable spec of the `izhikevich_layer` routine of the frame
// engine (rtl/ucode/dtmf_chain.fe, below). Used for the receptor
// layer (input = taxel value) and for the second layer (input = the weighted
// spike sum from synapse_weights): "spiking layers" are instances of this.
//
// Model (project-wide scheme, forward Euler, step dt ms, k = tau * dt):
//   dv = k (0.04 v^2 + 5 v + 140 - u + I),  du = k a (b v - u)
//   v += dv; u += du; if v >= 30: spike, v = c, u += d.
// Rewritten with dt*tau folded into the state and the constants:
//   w = v + 62.5 (so 0.04 v^2 + 5 v + 140 = 0.04 w^2 - 16.25),
//   U = k u (stored instead of u), J = k I (the input, gain folded in):
//   dv = c2 w^2 + C - U + J        c2 = 0.04 k, C = -16.25 k
//   dU = c3 v - c4 U               c3 = k^2 a b, c4 = k a
//   spike: v = c, U += kd          kd = k d
//
// Number formats (all two's complement; "Q.22" = integer / 2^22 in mV, or
// mV per step for J and dv):
//   v      stored Q9.22 int32, always in [V_MIN, V_PEAK) = [-128, 30) mV:
//          saturated below at V_MIN = -128 mV (-2^29); values >= 30 are never
//          stored (they are the spike and reset to c).
//   U      stored int32 = k u in Q.FU (FU = cfg.u_frac in 22..30, chosen by
//          the builder from k: the largest FU with 256 k <= 2^(30-FU), so u
//          keeps ~30 - log2(k) - 8 fraction bits: slow u needs them),
//          saturated to [-2^30, 2^30 - 1], i.e. |U| < 2^(30-FU) <= 256 mV
//          per step (|u| < 256 mV at least). U22 = rnd(U >> (FU - 22)) is U
//          in Q.22 for the v equation.
//   x      input token, signed int32 (receptor: unsigned TAX_W taxel value);
//          xs = sat16(rnd(x >> x_shift)) is the multiplier operand.
//   J      = sat32(rnd(xs * gain >> gain_shift)) (left shift for a negative
//          gain_shift), Q9.22: |J| < 512 mV per step.
//   c2, c3, c4: mantissa m (int16, |m| < 2^15) and right shift s:
//          c2 w^2 = rnd(m2 * sq >> s2) with sq = w^2 in Q.14 (below),
//          c3 v   = rnd(m3 * vh >> s3) in Q.FU, vh = rnd(v >> 14) (units
//                   2^-8 mV; v in [-128, 30) gives vh in [-2^15, 7680]),
//          c4 U   = rnd((m4 * Uh * 2^15 + m4 * Ul) >> s4) in Q.FU, with
//                   U = Uh 2^15 + Ul, Ul in [0, 2^15) (exact split: Uh =
//                   U >> 15, Ul = U & 0x7fff; |Uh| <= 2^15 as |U| <= 2^30).
//   v_reset (c), C: int32 Q9.22; u_jump (k d), u_init: int32 Q.FU.
// Rounding: rnd(y >> s) = (y + 2^(s-1)) >> s, round half up (s = 0: none).
//
// The square: w = v + 62.5 mV (exact: 62.5 * 2^22 is an integer) lies in
// [-65.5, 92.5) mV, so |w| < 2^29 in Q.22 and wh = w >> 15 fits int16
// (|wh| <= 11840), wl = w & 0x7fff in [0, 2^15). Then
//   w^2 * 2^-30 (Q.22^2 -> Q.14) = wh^2 + wh wl / 2^14 + wl^2 / 2^30,
//   sq = wh^2 + rnd(wh * wl >> 14), dropping wl^2 / 2^30 < 1 LSB, so
//   |sq - w^2 2^-30| <= 1.5 and sq >= -1 (w near 0, wh = -1).
// sq <= 11840^2 + 11840 < 2^28: sqh = sq >> 15 in [-1, 2^13), sql = sq & 0x7fff, and
// c2 w^2 = rnd((m2 sqh 2^15 + m2 sql) >> s2). Every product is one signed
// 16 x 16 -> 32 multiply (SB_MAC16): xs*gain, wh*wh, wh*wl, m2*sqh, m2*sql,
// m3*vh, m4*Uh, m4*Ul: eight multiplies per neuron update.
//
// Why nothing overflows (k <= 1 ms, enforced by the config builder):
//   |products| <= 2^15 * 2^15 = 2^30 (int32);
//   |c2 w^2| <= 0.04 * 92.5^2 = 342.3 mV, |C| <= 16.25, |U22| <= 256, |J| < 512,
//   v in [-128, 30): v_new = v + dv lies in (-1171, 1147) mV, i.e.
//   |v_new| < 2^11 mV = 2^33 in Q.22: 35 bits signed (int64 here, 36 in RTL);
//   (m4 Uh 2^15 + m4 Ul) < 2^46; |dU| <= |c3 v| + |c4 U| < 1 + 256: the
//   sum U + dU (+ kd) is formed in int64 and saturated to [-2^30, 2^30).
// Saturation points: v >= -128 mV (below: clamp), U in [-2^30, 2^30) LSB of
//   Q.FU (|k u| < 2^(30-FU) <= 256), J in [-512, 512), xs in [-32768,
//   32767]. No wrap-around for any input.
// Extreme inputs (proved here, tested in tests/hls/izhikevich_layer_test.cpp):
//   * J = +max: at v = c (>= -128) dv >= -16.25 - 256 + 512 > 239 >= 30 - c:
//     a spike every step, whatever U (U saturates, it cannot wrap).
//   * J = -max: at v = -128, dv <= 0.04*65.5^2 + 0 + 256 - 512 < 0 (C < 0):
//     v is pinned at V_MIN and never spikes.
//   * c4 = k a < 1 means U relaxes towards k b v without overshoot, so after
//     any extreme input U returns to its normal range (no stuck state).
// Difference from the double model: only where a saturation acts (v < -128
// mV needs I < -187 mV/ms; |u| >= 256 mV needs a neuron firing every step
// for hundreds of steps), plus rounding (<= 1.5 LSB of Q.22 per step in v,
// <= 1.5 LSB of Q.FU per step in U) and constant quantisation (mantissas
// normalised to [2^14, 2^15): relative error <= 0.5 / 2^14 = 2^-15).
// Measured against the double model (tests/hls): identical spike counts; spike times within one step for inputs clearly above
// rheobase. Near rheobase (slow firing, onsets after silence) the model is
// ill conditioned (the double model itself moves spikes by tens of steps
// for a 2^-20 relative input change) and times may differ by a few steps;
// there the U LSB matters most (a step dU below half an LSB is rounded away,
// so u lags its nullcline by up to c4^-1 * 2^-(FU+1)): FU = 31 would remove
// the state-rounding part, at the price of a wider U (3 products for c4 U).
//
// Interface: update(n, x) advances neuron n by one step with input x; the
// caller addresses every neuron by its index (the DTMF chain: taxel i's
// receptor is neuron i of layer 1 and the weighted neuron i of layer 2), so
// a missing or extra input can never shift another neuron's state.
// Input modes: level (x drives the neuron) or rectified change
// (cfg.input_change: the neuron sees max(0, x - x_prev), x_prev = this
// neuron's previous input, 0 after reset; the builder folds 1/frame into
// the gain), which responds to onsets and is silent while a press is held.
// Hardware: the `izhikevich_layer` routine of the frame engine
// (rtl/ucode/dtmf_chain.fe), state (v, U, x_prev) in DMEM, constants in
// the engine's configuration words (SET_NEURON changes them at run time).
#pragma once

#include <cstdint>

namespace eskin::hls {

// Fixed-point parameters of one layer (all neurons share them). Built by
// make_izhikevich_config() in hls/izhikevich_layer_config.h (host side).
struct IzhikevichConfig {
  int32_t v_init = 0;    // v0, Q9.22
  int32_t u_init = 0;    // U0 = k b v0, Q.FU
  int32_t v_reset = 0;   // c, Q9.22
  int32_t u_jump = 0;    // k d, Q.FU
  uint8_t u_frac = 22;   // FU, fraction bits of U (22..30)
  int32_t c_const = 0;   // C = -16.25 k, Q9.22
  int16_t m2 = 0;        // c2 = 0.04 k = m2 2^-(s2+8)
  uint8_t s2 = 0;
  int16_t m3 = 0;        // c3 = k^2 a b = m3 2^-(s3+FU-8)
  uint8_t s3 = 0;
  int16_t m4 = 0;        // c4 = k a = m4 2^-s4 (U and c4 U both Q.FU)
  uint8_t s4 = 0;
  int16_t gain = 0;      // J = rnd(xs * gain >> gain_shift) (<< -gain_shift if < 0)
  int8_t gain_shift = 0;
  uint8_t x_shift = 0;   // xs = sat16(rnd(x >> x_shift))
  bool input_change = false;  // x -> max(0, x - x_prev) (rectified change)
};

struct IzhikevichOut {
  bool spike = false;
  int32_t v = 0;   // the neuron's state after the update (Q9.22), for
  int32_t U = 0;   // verification and monitoring (Q.FU)
};

namespace izh {

constexpr int kFrac = 22;                                   // Q.22
constexpr int32_t kVMin = -(int32_t(1) << 29);              // -128 mV
constexpr int32_t kVPeak = int32_t(30) << kFrac;            // 30 mV
constexpr int32_t kWOffset = int32_t(125) << (kFrac - 1);   // 62.5 mV
constexpr int32_t kUMax = (int32_t(1) << 30) - 1;           // < 2^(30-FU)
constexpr int32_t kUMin = -(int32_t(1) << 30);              // -2^(30-FU)

// Round half up: (y + 2^(s-1)) >> s; arithmetic shift (floor) for y < 0.
inline int64_t rshift_round(int64_t y, int s) {
  return s <= 0 ? y : (y + (int64_t(1) << (s - 1))) >> s;
}
inline int64_t sat(int64_t y, int64_t lo, int64_t hi) { return y < lo ? lo : (y > hi ? hi : y); }

// Input operand and J (one multiply).
inline int16_t input_operand(const IzhikevichConfig& c, int32_t x) {
  return int16_t(sat(rshift_round(x, c.x_shift), -32768, 32767));
}
inline int32_t input_current(const IzhikevichConfig& c, int32_t x) {
  const int32_t p = int32_t(input_operand(c, x)) * int32_t(c.gain);  // |p| <= 2^30
  const int64_t j = c.gain_shift >= 0 ? rshift_round(p, c.gain_shift)
                                      : int64_t(p) * (int64_t(1) << -c.gain_shift);
  return int32_t(sat(j, INT32_MIN, INT32_MAX));
}

// The square term c2 w^2 in Q.22 (four multiplies).
inline int32_t square_term(const IzhikevichConfig& c, int32_t v) {
  const int32_t w = v + kWOffset;                  // [-65.5, 92.5) mV
  const int32_t wh = w >> 15, wl = w & 0x7fff;
  const int32_t sq = wh * wh + int32_t(rshift_round(int64_t(wh) * wl, 14));
  const int32_t sqh = sq >> 15, sql = sq & 0x7fff;
  const int64_t acc = int64_t(int32_t(c.m2) * sqh) * 32768 + int32_t(c.m2) * sql;
  return int32_t(rshift_round(acc, c.s2));
}

// dU = c3 v - c4 U in Q.22 (three multiplies).
inline int64_t u_change(const IzhikevichConfig& c, int32_t v, int32_t U) {
  const int32_t vh = int32_t(rshift_round(v, 14));
  const int32_t Uh = U >> 15, Ul = U & 0x7fff;
  const int64_t c3v = rshift_round(int32_t(c.m3) * vh, c.s3);
  const int64_t c4u = rshift_round(int64_t(int32_t(c.m4) * Uh) * 32768 + int32_t(c.m4) * Ul, c.s4);
  return c3v - c4u;
}

}  // namespace izh

// One neuron, one step: updates v and U in place, returns true on a spike.
inline bool izhikevich_update(const IzhikevichConfig& c, int32_t& v, int32_t& U, int32_t x) {
  using namespace izh;
  const int64_t J = input_current(c, x);
  const int64_t U22 = rshift_round(U, c.u_frac - kFrac);
  const int64_t v_new = int64_t(v) + square_term(c, v) + c.c_const - U22 + J;
  int64_t U_new = sat(int64_t(U) + u_change(c, v, U), kUMin, kUMax);
  const bool spike = v_new >= kVPeak;
  if (spike) {
    v = c.v_reset;
    U_new = sat(U_new + c.u_jump, kUMin, kUMax);
  } else {
    v = int32_t(v_new < kVMin ? kVMin : v_new);
  }
  U = int32_t(U_new);
  return spike;
}

// N neurons, state in arrays (DMEM in the frame engine), addressed by index.
template <int N>
class IzhikevichLayer {
  static_assert(N >= 1 && N <= 65536, "N must be 1..65536");

 public:
  explicit IzhikevichLayer(const IzhikevichConfig& cfg) : cfg_(cfg) { reset(); }

  void reset() {
    for (int i = 0; i < N; ++i) {
      v_[i] = cfg_.v_init;
      U_[i] = cfg_.u_init;
      x_prev_[i] = 0;
    }
  }
  // New constants (SET_NEURON) take effect from the next update; state kept.
  void set_config(const IzhikevichConfig& cfg) { cfg_ = cfg; }

  // Neuron n (0..N-1), one step with input x; true on a spike.
  bool update(int n, int32_t x, IzhikevichOut* out = nullptr) {
    int32_t drive = x;
    if (cfg_.input_change) {
      const int64_t d = int64_t(x) - x_prev_[n];
      drive = d > 0 ? int32_t(d > INT32_MAX ? INT32_MAX : d) : 0;
      x_prev_[n] = x;
    }
    const bool spike = izhikevich_update(cfg_, v_[n], U_[n], drive);
    if (out) *out = IzhikevichOut{spike, v_[n], U_[n]};
    return spike;
  }

  // Neuron i's state, for a caller that keeps it elsewhere (the neuron
  // unit's port model: the state lives in the engine's DMEM).
  void set_state(int i, int32_t v, int32_t U, int32_t x_prev) {
    v_[i] = v, U_[i] = U, x_prev_[i] = x_prev;
  }

  int32_t v(int i) const { return v_[i]; }   // Q9.22 mV
  int32_t U(int i) const { return U_[i]; }   // Q.FU, k u
  int32_t x_prev(int i) const { return x_prev_[i]; }
  const IzhikevichConfig& config() const { return cfg_; }

 private:
  IzhikevichConfig cfg_;
  int32_t v_[N];
  int32_t U_[N];
  int32_t x_prev_[N];
};

}  // namespace eskin::hls
