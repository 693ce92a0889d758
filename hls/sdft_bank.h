// sdft_bank: exact sliding DFT of K carriers over an N-sample rectangular
// window. Bit-exact executable spec of rtl/sdft_bank.v.
//
// Method (modulated sliding DFT): carrier k has a 32-bit phase accumulator,
// theta_k(n) = n * inc_k mod 2^32 (inc_k = round(f_k / fs * 2^32), built by
// hls/sdft_bank_config.h). The sample x[n] adds the term
//   T(x[n], theta_k(n))  = { R(x * C(theta)), R(x * -S(theta)) }
// to the carrier's accumulator, and the identical term is recomputed N
// samples later from the stored x[n-N] and its re-derived phase
// theta_k(n) - N * inc_k (mod 2^32) and subtracted. Integer arithmetic is
// exact, so after every sample
//   acc_k(n) = sum_{m=n-N+1}^{n} T(x[m], theta_k(m))       (bit for bit)
// forever (samples before the first are 0). |acc_k| approximates
// |sum_m x[m] e^{-j 2 pi f_k m / fs}|, the window sum, times G below.
//
// Number formats
//   x      : signed XW-bit sample (ADC code minus mid code). push() keeps the
//            low XW bits, sign-extended (what the RTL port of width XW does).
//   C, S   : signed CW-bit coefficients, Q1.(CW-1): C(theta) = cos, S = sin of
//            the phase rounded to TW bits, idx = round(theta / 2^(32-TW))
//            mod 2^TW (round half up), from a quarter-wave table of
//            Q = 2^(TW-2) entries, table[i] = qsin(i) ~ A sin(pi/2 * i/Q),
//            A = 2^(CW-1) - 1, qsin(Q) = A. qsin is computed by integer
//            arithmetic (sdft_quarter_sine below; the RTL evaluates the same
//            function at elaboration) and is within 0.5 + 2^-4 LSB of
//            A sin (checked exhaustively by tests/hls/sdft_bank_test.cpp).
//   R(p)   : p / 2^(CW-1-FB) rounded half up: (p + 2^(CW-2-FB)) >>
//            (CW-1-FB), arithmetic shift; FB (default 0) fraction bits are
//            kept below the sample LSB. |R| <= 2^(XW-1+FB): XW+1+FB bits.
//   re, im : signed ACC_W-bit window sums in units of 2^-FB sample LSB
//            (FB = 0: sample LSB, the data path contract's units), gain
//            G = A / 2^(CW-1) = 1 - 2^-(CW-1). Never saturate: |sum| <=
//            N * 2^(XW-1+FB) < 2^(ACC_W-1), enforced by the static_assert
//            ACC_W >= XW + 1 + FB + ceil(log2 N). Arithmetic is modulo 2^ACC_W
//            (as in the RTL); since the exact window sum always fits, the
//            wrap never changes a result.
//
// Output per sample: `carriers` tokens {k, re, im, last}, k = 0..K-1,
// last on k = K-1. Phase convention: absolute (theta(m) = m * inc), not
// referred to the oldest sample: only the magnitude is comparable with
// the golden model directly.
//
// Accuracy (bound derived in sdft_bank_config.h, measured by
// bench/hls_tradeoff): the phase rounding to TW bits dominates; defaults
// (CW 16, TW 10, FB 0) give <= 0.03% of full scale amplitude error against
// the double-precision DFT, TW 12 + FB 4 about 0.006%.
//
// RTL schedule (rtl/sdft_bank.v): one multiplier used 4x per carrier, one
// quarter-sine ROM read per cycle. Initiation interval II = 6 K + 2 cycles
// per sample (K active carriers, output never stalled): 38 for K = 6,
// 194 for K = 32. Latency: sample handshake at cycle t -> first token valid
// at cycle t + 8; token k valid at t + 8 + 6 k.
#pragma once

#include <cstdint>

namespace eskin::hls {

// rtl/sdft_lanes.v's initiation interval: clocks from one sample's
// handshake to the next one's, input always valid, K channels over `lanes`
// sdft_bank lanes, the consumer taking a token whenever one is valid and
// then needing `take_clocks` clocks before the next (1: out_ready always
// high, as rtl/frame_capture.v keeps it; 2 or more: a slower consumer).
// One lane is sdft_bank: 6 K + 2 (it offers a token every 6 clocks, so any
// consumer up to 6 clocks per token keeps up). The derivation is in the
// RTL's header; tests/rtl/sdft_lanes_test.cpp checks it clock for clock.
constexpr int64_t sdft_lanes_interval(int64_t k, int64_t lanes, int64_t take_clocks = 1) {
  if (lanes <= 1) return 6 * k + 2;
  const int64_t wait = 6 - take_clocks * lanes;  // idle clocks per row boundary
  return 9 + take_clocks * (k - 1) + (wait > 0 ? wait : 0) * ((k + lanes - 1) / lanes - 1);
}

// rtl/sdft_lanes.v's interval after a skipped sample (in_skip: computed,
// no tokens): the fullest lane's 6 ceil(K / lanes) + 2 clocks, whatever the
// consumer (one lane: sdft_bank's 6 K + 2, as with tokens).
constexpr int64_t sdft_skip_interval(int64_t k, int64_t lanes) {
  const int64_t l = lanes > 1 ? lanes : 1;
  return 6 * ((k + l - 1) / l) + 2;
}

// rtl/sdft_front.v (a FIFO of `depth` samples in front of the lanes) fed
// by an ADC that converts every `period` clocks and holds one sample: the
// most samples the FIFO holds at once after a frame's sample that takes
// `frame_clocks` (F, sdft_lanes_interval with a consumer taking a token a
// clock) entered on arrival, floor((F - 1) / P), should it have room. The
// derivation is in the RTL's header; tests/rtl/sdft_front_test.cpp
// measures it.
constexpr int64_t sdft_front_backlog(int64_t frame_clocks, int64_t period) {
  return period > 0 && frame_clocks > 0 ? (frame_clocks - 1) / period : 0;
}

// The shortest ADC period (clocks) at which rtl/sdft_front.v loses no
// sample, every sample but one in `step` skipped (skip_clocks each, S):
// the least P with S <= P, F < (depth + 2) P and F - P <= (step - 1)(P -
// S); step 1 (every sample a frame's): F. depth 0 is the lanes behind the
// ADC's register alone (F < 2 P: the sample after a frame's must be taken
// before the next conversion lands, which rtl/adc_ad7476.v would drop).
constexpr int64_t sdft_front_min_period(int64_t frame_clocks, int64_t skip_clocks, int64_t step,
                                        int64_t depth) {
  const int64_t f = frame_clocks, s = skip_clocks;
  if (step <= 1) return f;
  const int64_t by_fifo = f / (depth + 2) + 1;                  // F < (depth + 2) P
  const int64_t by_catch_up = (f + (step - 1) * s + step - 1) / step;  // step P >= F + (step-1) S
  int64_t p = s > by_fifo ? s : by_fifo;
  return p > by_catch_up ? p : by_catch_up;
}

constexpr int sdft_ceil_log2(int64_t v) {
  int b = 0;
  while ((int64_t(1) << b) < v) ++b;
  return b;
}

// Smallest accumulator that holds any window sum: term XW+1 bits, N terms.
constexpr int sdft_min_acc_width(int n, int xw, int fb = 0) {
  return xw + 1 + fb + sdft_ceil_log2(n);
}

// The width rules the static_asserts enforce, as one predicate the host-side
// config checker (sdft_bank_config.h) reuses.
constexpr bool sdft_widths_ok(int n, int xw, int cw, int tw, int acc_w, int fb = 0) {
  return n >= 2 && n <= 65536 && xw >= 2 && xw <= 24 && cw >= 3 && cw <= 24 &&
         tw >= 3 && tw <= 14 && fb >= 0 && fb <= cw - 2 && acc_w <= 32 &&
         acc_w >= sdft_min_acc_width(n, xw, fb);
}

// qsin(i) ~ round((2^(cw-1) - 1) * sin(pi/2 * i/q)), i in 0..q, q a power of
// two <= 2^12. Integer Taylor series in Q.30: x <= 1.571 * 2^30, x2 <= 2^31.3,
// every product < 2^63; eight terms leave a truncation error < 2^-40 and each
// step rounds by < 2^-30, so |qsin - A sin| < 0.5 + 2^-4 for A < 2^23.
constexpr int32_t sdft_quarter_sine(int i, int q, int cw) {
  const int64_t half_pi_q30 = 1686629713;  // round(pi/2 * 2^30)
  const int64_t x = (half_pi_q30 * i + q / 2) / q;
  const int64_t x2 = (x * x) >> 30;
  int64_t t = x, s = x;
  for (int n = 1; n <= 8; ++n) {
    t = -(((t * x2) >> 30) / ((2 * n) * (2 * n + 1)));
    s += t;
  }
  const int64_t a = (int64_t(1) << (cw - 1)) - 1;
  return int32_t((s * a + (int64_t(1) << 29)) >> 30);
}

struct SdftBankToken {
  uint8_t k = 0;      // carrier index (rows first, then columns)
  int32_t re = 0;     // signed ACC_W-bit window sum, real part
  int32_t im = 0;     // signed ACC_W-bit window sum, imaginary part
  bool last = false;  // k == carriers - 1
};

// Runtime carrier table (what the RTL config port writes).
template <int K_MAX>
struct SdftBankConfig {
  int carriers = 0;           // K, 1..K_MAX
  uint32_t inc[K_MAX] = {};   // phase increment per sample, 2^32 = one cycle
};

template <int K_MAX, int N, int XW = 13, int CW = 16, int TW = 10, int ACC_W = 24, int FB = 0>
class SdftBank {
  static_assert(K_MAX >= 1 && K_MAX <= 256, "K_MAX must be 1..256 (k is 8 bits)");
  static_assert(N >= 2 && N <= 65536, "window N must be 2..65536");
  static_assert(XW >= 2 && XW <= 24, "sample width XW must be 2..24");
  static_assert(CW >= 3 && CW <= 24, "coefficient width CW must be 3..24");
  static_assert(TW >= 3 && TW <= 14, "table index width TW must be 3..14");
  static_assert(ACC_W <= 32, "ACC_W must be <= 32 (tokens carry int32)");
  static_assert(FB >= 0 && FB <= CW - 2, "term fraction bits FB must be 0..CW-2");
  static_assert(ACC_W >= sdft_min_acc_width(N, XW, FB),
                "ACC_W too small: a window sum needs XW + 1 + FB + ceil(log2 N) bits");

 public:
  static constexpr int Q = 1 << (TW - 2);
  static constexpr int32_t A = (int32_t(1) << (CW - 1)) - 1;

  struct Table {
    int32_t v[Q] = {};
  };
  static constexpr Table make_table() {
    Table t{};
    for (int i = 0; i < Q; ++i) t.v[i] = sdft_quarter_sine(i, Q, CW);
    return t;
  }
  static constexpr Table table = make_table();

  using Config = SdftBankConfig<K_MAX>;
  using Token = SdftBankToken;

  SdftBank() { clear(); }

  // Loads the carrier table and clears all state (window, sums, phases),
  // as the RTL does after a config write with `last`. False (state
  // unchanged) unless 1 <= carriers <= K_MAX.
  bool configure(const Config& cfg) {
    if (cfg.carriers < 1 || cfg.carriers > K_MAX) return false;
    cfg_ = cfg;
    clear();
    return true;
  }

  int carriers() const { return cfg_.carriers; }

  // sin(idx * 2 pi / 2^TW) in Q1.(CW-1), idx taken mod 2^TW.
  static int32_t sine(uint32_t idx) {
    const uint32_t quad = (idx >> (TW - 2)) & 3u, o = idx & uint32_t(Q - 1);
    int32_t v;
    if (quad & 1u)  // mirrored quadrant: sin(pi/2 * (Q - o) / Q)
      v = o == 0 ? A : table.v[Q - o];
    else
      v = table.v[o];
    return (quad & 2u) ? -v : v;
  }
  // Table index of a phase: top TW bits, rounded half up.
  static uint32_t index(uint32_t theta) {
    return ((theta >> (31 - TW)) + 1u) >> 1;
  }
  static int32_t cosine(uint32_t idx) { return sine(idx + uint32_t(Q)); }

  // R(x * c): product Q(XW).(CW-1), rounded half up to 2^-FB sample LSB.
  static int64_t term(int32_t x, int32_t c) {
    return (int64_t(x) * c + (int64_t(1) << (CW - 2 - FB))) >> (CW - 1 - FB);
  }
  static int32_t wrap_acc(int64_t v) {  // modulo 2^ACC_W, sign-extended
    const uint64_t m = uint64_t(v) << (64 - ACC_W);
    return int32_t(int64_t(m) >> (64 - ACC_W));
  }
  static int32_t wrap_sample(int32_t x) {
    const uint32_t m = uint32_t(x) << (32 - XW);
    return int32_t(m) >> (32 - XW);
  }

  // One sample in, carriers() tokens out (returned count; 0 if unconfigured).
  int push(int32_t x_in, Token (&out)[K_MAX]) {
    if (cfg_.carriers < 1) return 0;
    const int32_t x = wrap_sample(x_in);
    const int32_t x_old = win_[wp_];
    win_[wp_] = x;
    wp_ = wp_ + 1 == N ? 0 : wp_ + 1;
    for (int k = 0; k < cfg_.carriers; ++k) {
      const uint32_t th = phase_[k];
      const uint32_t th_old = th - cfg_.inc[k] * uint32_t(N);
      const uint32_t in = index(th), io = index(th_old);
      re_[k] = wrap_acc(int64_t(re_[k]) + term(x, cosine(in)) - term(x_old, cosine(io)));
      im_[k] = wrap_acc(int64_t(im_[k]) + term(x, -sine(in)) - term(x_old, -sine(io)));
      phase_[k] = th + cfg_.inc[k];
      out[k].k = uint8_t(k);
      out[k].re = re_[k];
      out[k].im = im_[k];
      out[k].last = k == cfg_.carriers - 1;
    }
    return cfg_.carriers;
  }

 private:
  void clear() {
    for (int i = 0; i < N; ++i) win_[i] = 0;
    for (int k = 0; k < K_MAX; ++k) re_[k] = im_[k] = 0, phase_[k] = 0;
    wp_ = 0;
  }

  Config cfg_{};
  int32_t win_[N] = {};       // last N samples, circular, oldest at wp_
  int wp_ = 0;
  int32_t re_[K_MAX] = {}, im_[K_MAX] = {};
  uint32_t phase_[K_MAX] = {};  // theta_k of the next sample
};

}  // namespace eskin::hls
