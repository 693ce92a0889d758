// sdft_damped: the cheaper alternative to hls/sdft_bank.h — a block Goertzel
// bank. (The plan's slot for "the cheaper variant" is named sdft_damped; a
// damped recursive sliding DFT was the other candidate but, for carriers off
// the DFT bin centres, y <- r e^{jw} y + x_new - (r e^{jw})^N x_old costs six
// real multiplies per carrier and sample against four for the exact bank, so
// it is not cheaper; the golden model keeps it as DftVariant::Damped.)
//
// What it computes: the DFT of consecutive, non-overlapping N-sample blocks
// at each carrier, |sum_{m=0}^{N-1} x[m] e^{-j w' m}|, emitted once per block
// (hop N) instead of once per sample. Per sample and carrier ONE multiply:
//   s(n) = x(n) + 2 cos(w') s(n-1) - s(n-2)   (s = 0 at the block start)
// and at the block end two more: y = s(N-1) - e^{-j w'} s(N-2), whose
// magnitude is the block's DFT magnitude. No window buffer, no phase
// accumulator, no sine table: 2 state words and 2 coefficients per carrier.
//
// Number formats
//   x       : signed XW-bit sample; push() keeps the low XW bits, sign-extended.
//   a       : 2 cos(w') as signed CW-bit Q2.(CW-2). w' is the resonator's
//             actual frequency: cos(w') = a / 2^(CW-1) exactly.
//   b       : sin(w') as signed CW-bit Q1.(CW-1), round(sqrt(1 - cos^2) 2^(CW-1))
//             (host-side builder in hls/sdft_bank_config.h).
//   s       : signed state, F fraction bits below the sample LSB, SW bits:
//             s(n) = x 2^F + R2(a s(n-1)) - s(n-2), R2(p) = (p + 2^(CW-3))
//             >> (CW-2) (round half up). |s| <= sum_m |h(m)| |x| 2^F + (rounding)
//             with |h(m)| = |sin((m+1) w') / sin w'| <= m + 1, so
//             SW >= XW + F + 2 + ceil(log2(N (N+1) / 2)) never overflows
//             (static_assert).
//   re, im  : the block sums in sample LSB (int32, same units as sdft_bank's):
//             re = Ro((s1 2^(CW-1) - a s2)), im = Ro(b s2), Ro(p) = (p +
//             2^(CW-2+F)) >> (CW-1+F).
// Error against the exact DFT at the carrier's nominal w (derived in
// tests/hls/sdft_damped_test.cpp, bound in sdft_damped_error_bound()):
// frequency |w' - w| <= 2^-CW / sin w from rounding a; state rounding
// 0.5 per step through the resonator; b's rounding; the output rounding.
//
// Hardware estimate (not in RTL): one multiplier time-shared, K + 2K/N
// multiplies per sample; II ~ K cycles per sample plus 2K per block.
#pragma once

#include <cstdint>

namespace eskin::hls {

constexpr int goertzel_ceil_log2(int64_t v) {
  int b = 0;
  while ((int64_t(1) << b) < v) ++b;
  return b;
}

// Smallest state width that never overflows for any input and frequency.
constexpr int goertzel_min_state_width(int n, int xw, int f) {
  return xw + f + 2 + goertzel_ceil_log2(int64_t(n) * (n + 1) / 2);
}

struct GoertzelToken {
  uint8_t k = 0;
  int32_t re = 0, im = 0;  // block sum, sample LSB
  bool last = false;
};

template <int K_MAX>
struct GoertzelConfig {
  int carriers = 0;
  int32_t a[K_MAX] = {};  // 2 cos w', Q2.(CW-2)
  int32_t b[K_MAX] = {};  // sin w',   Q1.(CW-1)
};

template <int K_MAX, int N, int XW = 13, int CW = 16, int F = 4,
          int SW = goertzel_min_state_width(N, XW, F)>
class GoertzelBlockBank {
  static_assert(K_MAX >= 1 && K_MAX <= 256, "K_MAX must be 1..256");
  static_assert(N >= 2 && N <= 4096, "block N must be 2..4096");
  static_assert(XW >= 2 && XW <= 24 && CW >= 4 && CW <= 24 && F >= 0 && F <= 16,
                "widths: XW 2..24, CW 4..24, F 0..16");
  static_assert(SW >= goertzel_min_state_width(N, XW, F),
                "SW too small: needs XW + F + 2 + ceil(log2(N(N+1)/2)) bits");
  static_assert(SW + CW <= 62, "SW + CW must be <= 62 (products in int64)");

 public:
  using Config = GoertzelConfig<K_MAX>;
  using Token = GoertzelToken;

  // False (state unchanged) unless 1 <= carriers <= K_MAX. Clears the block.
  bool configure(const Config& cfg) {
    if (cfg.carriers < 1 || cfg.carriers > K_MAX) return false;
    cfg_ = cfg;
    clear();
    return true;
  }
  int carriers() const { return cfg_.carriers; }

  static int64_t wrap_state(int64_t v) {  // modulo 2^SW (never taken, see above)
    return int64_t(uint64_t(v) << (64 - SW)) >> (64 - SW);
  }

  // One sample in; at the end of each block carriers() tokens out (returned
  // count), otherwise 0.
  int push(int32_t x_in, Token (&out)[K_MAX]) {
    if (cfg_.carriers < 1) return 0;
    const int32_t x = int32_t(uint32_t(x_in) << (32 - XW)) >> (32 - XW);
    for (int k = 0; k < cfg_.carriers; ++k) {
      const int64_t fb = (int64_t(cfg_.a[k]) * s1_[k] + (int64_t(1) << (CW - 3))) >> (CW - 2);
      const int64_t s0 = wrap_state(int64_t(x) * (int64_t(1) << F) + fb - s2_[k]);
      s2_[k] = s1_[k];
      s1_[k] = s0;
    }
    if (++count_ < N) return 0;
    const int sh = CW - 1 + F;
    const int64_t half = int64_t(1) << (sh - 1);
    for (int k = 0; k < cfg_.carriers; ++k) {
      const int64_t re = s1_[k] * (int64_t(1) << (CW - 1)) - int64_t(cfg_.a[k]) * s2_[k];
      const int64_t im = int64_t(cfg_.b[k]) * s2_[k];
      out[k].k = uint8_t(k);
      out[k].re = int32_t((re + half) >> sh);
      out[k].im = int32_t((im + half) >> sh);
      out[k].last = k == cfg_.carriers - 1;
    }
    clear();
    return cfg_.carriers;
  }

 private:
  void clear() {
    for (int k = 0; k < K_MAX; ++k) s1_[k] = s2_[k] = 0;
    count_ = 0;
  }

  Config cfg_{};
  int64_t s1_[K_MAX] = {}, s2_[K_MAX] = {};  // s(n-1), s(n-2)
  int count_ = 0;                            // samples in the current block
};

}  // namespace eskin::hls
