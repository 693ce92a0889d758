// carrier_demix: joint least-squares cross-talk cancellation between K
// off-bin carriers (+ DC) of an N-sample rectangular window, on the window
// sums of sdft_bank. Bit-exact executable spec of the `carrier_demix`
// routine of the frame engine (rtl/ucode/dtmf_chain.fe).
// Cost study and derivation: docs/carrier_demix.md.
//
// Why a constant matrix: referred to the OLDEST sample s of the window, the
// sums P_k = sum_i x[s+i] e^{-j w_k i} and D = sum_i x[s+i] are the normal
// equations' right-hand side b = (Re P_1, -Im P_1, ..., Re P_K, -Im P_K, D)
// of the least-squares fit x[s+i] ~ d + sum_k a_k cos(w_k i) + b_k sin(w_k i);
// the fit is theta = G^{-1} b with the constant Gram matrix G = B^T B. We
// output y = (N/2) theta, i.e. in window-sum units (a bin-centred tone of
// amplitude A reads |y| = A N/2, exactly as |sum| does without demixing),
// so carrier_magnitude and the rest of the pipeline are unchanged.
// sdft_bank's sums use the absolute phase theta_k(m) = m inc_k, so each is
// first rotated by e^{+j theta_k(s)}, s = n - N + 1; this kernel keeps its
// own per-carrier phase of s: phase0[k] = theta_k(s) of the first frame
// after configure(), + inc[k] (the phase advance per frame: STEP samples x
// the per-sample increment) for every later frame, in step with sdft_bank
// when both are reset together. Frames on every sample from sample 0:
// phase0 = (1 - N) inc_k; frames every STEP samples once the window is
// full (hls/dtmf_chain.h): phase0 = 0, inc = STEP inc_k.
//
// Input per frame (one sample of sdft_bank): K+1 tokens k = 0..K in order,
// `last` on k = K. k < K are the carriers; k = K is the DC channel: an extra
// sdft_bank carrier with inc = 0 (its sum is x summed over the window).
// Output per frame: K tokens {k, re, im}, k = 0..K-1, `last` on k = K-1,
// re = y_{2k}, im = -y_{2k+1}: re + j im is the golden amplitude a_k - j b_k
// times N/2 (oldest-sample phase). The fitted DC, y_{2K}, is kept in dc()
// (not streamed).
//
// Number formats
//   in.re, in.im : signed ACC_W-bit sums (sdft_bank units).
//   sine table   : signed SW-bit, Q1.(SW-1), quarter wave of Q = 2^(TW-2)+1
//                  entries, qsin[i] ~ (2^(SW-1)-1) sin(pi/2 i/Q'), Q' = Q-1;
//                  loaded with the config (host-side builder).
//   rotation     : idx = round(phase / 2^(32-TW)) mod 2^TW (round half up);
//                  Re P = R(re C - im S), Im P = R(re S + im C), R(p) =
//                  (p + 2^(SW-2)) >> (SW-1) (round half up, arithmetic).
//                  |P| <= sqrt(2) 2^(ACC_W-1): ACC_W + 1 bits signed.
//   coef         : signed CW-bit, Q(CW-CF).CF, row-major (2K+1)^2 matrix
//                  M = (N/2) G^{-1} / gains (host-side builder).
//   y            : y_i = R_CF(sum_j coef_ij b_j), R_CF(p) = (p + 2^(CF-1))
//                  >> CF, accumulated exactly in 64 bits (products of the
//                  rotated sums, ACC_W + 1 bits, and CW-bit coefficients: <
//                  2^(ACC_W + CW); 2K+1 <= 257 of them: < 2^(ACC_W + CW + 9)
//                  <= 2^59; a carrier's two sums share 2^ACC_W, so at most
//                  2^(CW-1) (K+1) (2^ACC_W + 1), 2^56.01 at the widest, is
//                  reached, as tests/hls/carrier_demix_test.cpp checks),
//                  then saturated to signed OUT_W bits.
//
// Hardware (the frame engine's `carrier_demix` routine): per frame 4
// products per input token (the rotation to the oldest sample) + 2K (2K+1)
// for the matrix rows (the DC row is not computed) = 184 multiplies for
// K = 6 on the engine's SB_MAC16, the matrix in its KROM (DMEM after a
// SET_DEMIX_COEF).
#pragma once

#include <cstdint>

namespace eskin::hls {

struct CarrierDemixToken {
  uint8_t k = 0;
  int32_t re = 0;
  int32_t im = 0;
  bool last = false;
};

template <int K_MAX, int TW = 10, int SW = 16, int CW = 16>
struct CarrierDemixConfig {
  static constexpr int DIM_MAX = 2 * K_MAX + 1;
  static constexpr int QN = (1 << (TW - 2)) + 1;
  int carriers = 0;                      // K (without the DC channel)
  uint32_t inc[K_MAX] = {};              // phase advance per frame, 2^32 = 1 cycle
  uint32_t phase0[K_MAX] = {};           // theta_k(s) of the first frame's oldest sample
  int32_t qsin[QN] = {};                 // quarter-wave sine, SW-bit signed
  int32_t coef[DIM_MAX * DIM_MAX] = {};  // CW-bit signed, Q(CW-CF).CF, row-major
};

template <int K_MAX, int N, int ACC_W = 24, int OUT_W = 24, int TW = 10, int SW = 16,
          int CW = 16, int CF = 14>
class CarrierDemix {
  // 128: a 64x64 skin's carriers (hls/dtmf_chain.h instantiates the demix
  // type for every chain, demixing or not).
  static_assert(K_MAX >= 1 && K_MAX <= 128,
                "K_MAX must be 1..128 (2K+1 <= 257 terms: sums < 2^(ACC_W + CW + 9) <= 2^59)");
  static_assert(N >= 3, "window N must be >= 3 (2 K + 1 <= N is checked by the builder)");
  static_assert(ACC_W >= 2 && ACC_W <= 32, "ACC_W must be 2..32");
  static_assert(OUT_W >= 2 && OUT_W <= 32, "OUT_W must be 2..32");
  static_assert(TW >= 3 && TW <= 14, "TW must be 3..14");
  static_assert(SW >= 3 && SW <= 18, "SW must be 3..18");
  static_assert(CW >= 2 && CW <= 18 && CF >= 1 && CF < CW + 8, "coefficient format");

 public:
  static constexpr int DIM_MAX = 2 * K_MAX + 1;
  static constexpr int kN = N, kTW = TW, kSW = SW, kCW = CW, kCF = CF, kKMax = K_MAX;
  using Config = CarrierDemixConfig<K_MAX, TW, SW, CW>;
  using Token = CarrierDemixToken;

  CarrierDemix() { clear(); }

  // Loads the tables and restarts the phases (frame 0 = sample 0). False
  // (state unchanged) unless 1 <= carriers <= K_MAX.
  bool configure(const Config& cfg) {
    if (cfg.carriers < 1 || cfg.carriers > K_MAX) return false;
    cfg_ = cfg;
    clear();
    for (int k = 0; k < cfg_.carriers; ++k) phase_[k] = cfg_.phase0[k];
    return true;
  }

  int carriers() const { return cfg_.carriers; }
  const Config& config() const { return cfg_; }
  // One matrix entry (row-major, 0 .. (2K+1)^2 - 1) from the next frame on;
  // phases and the rest unchanged (SET_DEMIX_COEF). False if out of range.
  bool set_coef(int index, int32_t value) {
    const int dim = 2 * cfg_.carriers + 1;
    if (index < 0 || index >= dim * dim) return false;
    cfg_.coef[index] = value;
    return true;
  }
  int32_t dc() const { return dc_; }

  // sin(2 pi idx / 2^TW) from the quarter table, idx mod 2^TW.
  int32_t sine(uint32_t idx) const {
    const uint32_t q = uint32_t(1) << (TW - 2);
    const uint32_t quad = (idx >> (TW - 2)) & 3u, o = idx & (q - 1u);
    const int32_t v = (quad & 1u) ? cfg_.qsin[q - o] : cfg_.qsin[o];
    return (quad & 2u) ? -v : v;
  }
  int32_t cosine(uint32_t idx) const { return sine(idx + (uint32_t(1) << (TW - 2))); }
  static uint32_t index(uint32_t theta) { return ((theta >> (31 - TW)) + 1u) >> 1; }

  // One input token; returns the number of output tokens written (K at the
  // end of a frame, else 0).
  int push(const Token& in, Token (&out)[K_MAX]) {
    const int kk = cfg_.carriers;
    if (kk < 1 || in.k > kk) return 0;
    // Rotate to the oldest-sample reference (DC: phase 0 -> C = A, S = 0).
    const uint32_t idx = in.k < kk ? index(phase_[in.k]) : 0u;
    const int64_t c = cosine(idx), s = sine(idx);
    const int64_t half = int64_t(1) << (SW - 2);
    const int64_t pr = (int64_t(in.re) * c - int64_t(in.im) * s + half) >> (SW - 1);
    const int64_t pi = (int64_t(in.re) * s + int64_t(in.im) * c + half) >> (SW - 1);
    if (in.k < kk) {
      b_[2 * in.k] = pr;       // sum x cos(w i)
      b_[2 * in.k + 1] = -pi;  // sum x sin(w i)
    } else {
      b_[2 * kk] = pr;         // sum x
    }
    if (!in.last) return 0;
    const int dim = 2 * kk + 1;
    int32_t y[DIM_MAX];
    for (int i = 0; i < dim; ++i) {
      int64_t acc = 0;
      for (int j = 0; j < dim; ++j) acc += int64_t(cfg_.coef[i * dim + j]) * b_[j];
      y[i] = sat((acc + (int64_t(1) << (CF - 1))) >> CF);
    }
    for (int k = 0; k < kk; ++k) {
      out[k].k = uint8_t(k);
      out[k].re = y[2 * k];
      out[k].im = sat(-int64_t(y[2 * k + 1]));
      out[k].last = k == kk - 1;
      phase_[k] += cfg_.inc[k];
    }
    dc_ = y[2 * kk];
    return kk;
  }

 private:
  static int32_t sat(int64_t v) {
    const int64_t hi = (int64_t(1) << (OUT_W - 1)) - 1, lo = -hi - 1;
    return int32_t(v > hi ? hi : (v < lo ? lo : v));
  }
  void clear() {
    for (int i = 0; i < DIM_MAX; ++i) b_[i] = 0;
    for (int k = 0; k < K_MAX; ++k) phase_[k] = 0;
    dc_ = 0;
  }

  Config cfg_{};
  int64_t b_[DIM_MAX] = {};     // rotated sums of the current frame
  uint32_t phase_[K_MAX] = {};  // theta_k(s) of the current frame
  int32_t dc_ = 0;
};

}  // namespace eskin::hls
