// Host-side, not synthesised: builds and checks the carrier table of
// hls/sdft_bank.h (and of the RTL config port) and the coefficients of the
// cheaper block Goertzel bank (hls/sdft_damped.h) from frequencies in Hz.
// Uses double and std::string; never throws: every check returns a status
// code and a message naming the field and what was expected.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "hls/sdft_bank.h"
#include "hls/sdft_damped.h"

namespace eskin::hls {

enum class SdftConfigError {
  None = 0,
  NoCarriers,          // empty carrier list
  TooManyCarriers,     // more than K_MAX
  BadRate,             // fs <= 0 or not finite
  BadWidths,           // a width outside its range (see sdft_widths_ok)
  AccumulatorOverflow, // ACC_W < XW + 1 + ceil(log2 N)
  CarrierTooLow,       // f < fs/N: at DC, within one bin of it
  CarrierTooHigh,      // f > fs/2 - fs/N: at/above Nyquist minus one bin
  SpacingBelowBin,     // two carriers closer than fs/N: window too short
};

struct SdftConfigStatus {
  SdftConfigError error = SdftConfigError::None;
  std::string message;  // "" when ok
  bool ok() const { return error == SdftConfigError::None; }
};

struct SdftWidths {
  int n = 32, xw = 13, cw = 16, tw = 10, acc_w = 24, fb = 0;
};

// round(f / fs * 2^32) mod 2^32.
inline uint32_t sdft_phase_increment(double f_hz, double fs_hz) {
  const double cycles = std::ldexp(f_hz / fs_hz, 32);
  return uint32_t(uint64_t(int64_t(std::llround(cycles))) & 0xffffffffu);
}

inline SdftConfigStatus sdft_config_error(SdftConfigError e, const std::string& msg) {
  return SdftConfigStatus{e, msg};
}

// Checks widths, rate and carriers (in that order; the first problem wins).
inline SdftConfigStatus check_sdft_bank(const std::vector<double>& freqs_hz, double fs_hz,
                                        const SdftWidths& w, int k_max) {
  using E = SdftConfigError;
  const auto num = [](double v) {
    std::string s = std::to_string(v);
    while (s.size() > 1 && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  };
  if (!sdft_widths_ok(w.n, w.xw, w.cw, w.tw, 32, 0) || w.fb < 0 || w.fb > w.cw - 2) {
    return sdft_config_error(E::BadWidths,
        "widths: expected 2 <= N <= 65536, 2 <= XW <= 24, 3 <= CW <= 24, 3 <= TW <= 14, "
        "0 <= FB <= CW-2, got N=" + std::to_string(w.n) + " XW=" + std::to_string(w.xw) +
        " CW=" + std::to_string(w.cw) + " TW=" + std::to_string(w.tw) +
        " FB=" + std::to_string(w.fb));
  }
  const int need = sdft_min_acc_width(w.n, w.xw, w.fb);
  if (w.acc_w < need || w.acc_w > 32) {
    return sdft_config_error(E::AccumulatorOverflow,
        "acc_w: " + std::to_string(w.acc_w) + " bits would overflow; expected " +
        std::to_string(need) + " <= ACC_W <= 32 (XW + 1 + FB + ceil(log2 N) for XW=" +
        std::to_string(w.xw) + ", FB=" + std::to_string(w.fb) + ", N=" + std::to_string(w.n) +
        ")");
  }
  if (!(fs_hz > 0) || !std::isfinite(fs_hz)) {
    return sdft_config_error(E::BadRate, "fs_hz: expected a finite rate > 0, got " + num(fs_hz));
  }
  if (freqs_hz.empty()) return sdft_config_error(E::NoCarriers, "carriers: expected 1 or more");
  if (int(freqs_hz.size()) > k_max) {
    return sdft_config_error(E::TooManyCarriers, "carriers: expected at most K_MAX = " +
        std::to_string(k_max) + ", got " + std::to_string(freqs_hz.size()));
  }
  const double bin = fs_hz / w.n, lo = bin, hi = fs_hz / 2 - bin;
  for (size_t k = 0; k < freqs_hz.size(); ++k) {
    const double f = freqs_hz[k];
    const std::string field = "carriers[" + std::to_string(k) + "]";
    if (!(f >= lo)) {
      return sdft_config_error(E::CarrierTooLow, field + ": " + num(f) +
          " Hz is within one bin (fs/N = " + num(bin) + " Hz) of DC; expected >= " + num(lo) +
          " Hz");
    }
    if (!(f <= hi)) {
      return sdft_config_error(E::CarrierTooHigh, field + ": " + num(f) +
          " Hz is at or within one bin of Nyquist; expected <= fs/2 - fs/N = " + num(hi) + " Hz");
    }
  }
  for (size_t a = 0; a < freqs_hz.size(); ++a) {
    for (size_t b = a + 1; b < freqs_hz.size(); ++b) {
      const double d = std::fabs(freqs_hz[a] - freqs_hz[b]);
      if (d < bin) {
        return sdft_config_error(E::SpacingBelowBin, "carriers[" + std::to_string(a) +
            "], carriers[" + std::to_string(b) + "]: spacing " + num(d) +
            " Hz is below one bin fs/N = " + num(bin) + " Hz; the window is too short, expected N >= " +
            std::to_string(int(std::ceil(fs_hz / d))) + " or carriers further apart");
      }
    }
  }
  return {};
}

// Checks, then fills `out` (only when ok) for the kernel type Bank
// (an SdftBank<...> instantiation).
template <int K_MAX, int N, int XW, int CW, int TW, int ACC_W, int FB>
SdftConfigStatus make_sdft_bank_config(const SdftBank<K_MAX, N, XW, CW, TW, ACC_W, FB>*,
                                       const std::vector<double>& freqs_hz, double fs_hz,
                                       SdftBankConfig<K_MAX>& out) {
  SdftConfigStatus st =
      check_sdft_bank(freqs_hz, fs_hz, SdftWidths{N, XW, CW, TW, ACC_W, FB}, K_MAX);
  if (!st.ok()) return st;
  out = SdftBankConfig<K_MAX>{};
  out.carriers = int(freqs_hz.size());
  for (size_t k = 0; k < freqs_hz.size(); ++k) out.inc[k] = sdft_phase_increment(freqs_hz[k], fs_hz);
  return st;
}

// Convenience: make_sdft_bank_config<Bank>(freqs, fs, cfg).
template <class Bank>
SdftConfigStatus make_sdft_bank_config(const std::vector<double>& freqs_hz, double fs_hz,
                                       typename Bank::Config& out) {
  return make_sdft_bank_config(static_cast<const Bank*>(nullptr), freqs_hz, fs_hz, out);
}

// Worst-case error of one carrier's amplitude, (2/N) |acc| 2^-FB / G against the
// exact (2/N) |window sum|, in sample LSB, for samples bounded by |x| <= xmax
// (derivation in tests/hls/sdft_bank_test.cpp): per term
//   phase rounding   |x| * pi / 2^TW        (|theta - idx| <= half a step)
//   coefficient      |x| * sqrt(2) * (0.5 + 2^-4) / A   (cos and sin parts)
//   term rounding    sqrt(2) * 0.5 * 2^-FB / G
//   frequency        |x| * 2 pi * N * 2^-33  (inc rounding, over the window)
// summed over N terms, times 2/N.
inline double sdft_amplitude_error_bound(const SdftWidths& w, double xmax) {
  const double pi = 3.14159265358979323846;
  const double a = std::ldexp(1.0, w.cw - 1) - 1, g = a / std::ldexp(1.0, w.cw - 1);
  const double per_term = xmax * pi / std::ldexp(1.0, w.tw) +
                          xmax * std::sqrt(2.0) * (0.5 + 0.0625) / a +
                          std::sqrt(2.0) * std::ldexp(0.5, -w.fb) / g +
                          xmax * 2 * pi * w.n * std::ldexp(1.0, -33);
  return 2.0 * per_term;
}

// ---- block Goertzel bank (hls/sdft_damped.h) ----

// Same carrier rules as the exact bank (one bin from DC and Nyquist, spacing
// >= fs/N); a = round(2 cos w 2^(CW-2)), b = round(sin w' 2^(CW-1)) with
// cos w' = a / 2^(CW-1), both limited to +-(2^(CW-1) - 1).
template <int K_MAX, int N, int XW, int CW, int F, int SW>
SdftConfigStatus make_goertzel_config(const GoertzelBlockBank<K_MAX, N, XW, CW, F, SW>*,
                                      const std::vector<double>& freqs_hz, double fs_hz,
                                      GoertzelConfig<K_MAX>& out) {
  const SdftWidths w{N, XW, CW, 10, sdft_min_acc_width(N, XW)};
  SdftConfigStatus st = check_sdft_bank(freqs_hz, fs_hz, w, K_MAX);
  if (!st.ok()) return st;
  out = GoertzelConfig<K_MAX>{};
  out.carriers = int(freqs_hz.size());
  const double one = std::ldexp(1.0, CW - 1), lim = one - 1, pi = 3.14159265358979323846;
  for (size_t k = 0; k < freqs_hz.size(); ++k) {
    const double wk = 2 * pi * freqs_hz[k] / fs_hz;
    const double a = std::fmax(-lim, std::fmin(lim, std::nearbyint(std::cos(wk) * one)));
    const double c = a / one;
    out.a[k] = int32_t(a);
    out.b[k] = int32_t(std::fmin(lim, std::nearbyint(std::sqrt(1 - c * c) * one)));
  }
  return st;
}

template <class Bank>
SdftConfigStatus make_goertzel_config(const std::vector<double>& freqs_hz, double fs_hz,
                                      typename Bank::Config& out) {
  return make_goertzel_config(static_cast<const Bank*>(nullptr), freqs_hz, fs_hz, out);
}

// Worst-case error of (2/N)|y| against the exact (2/N)|block DFT at w|, in
// sample LSB, |x| <= xmax, for a carrier with coefficient a (derivation in
// tests/hls/sdft_damped_test.cpp):
//   frequency   xmax |w' - w| N (N-1)/2         (w' = acos(a / 2^(CW-1)))
//   state       G 2^-F, G = sum_{m<N} |sin((m+1) w') / sin w'|
//   b rounding  (xmax + 2^-F/2) G 2^-CW
//   output      sqrt(2)/2
inline double goertzel_error_bound(int n, int cw, int f, int32_t a, double w, double xmax) {
  const double wp = std::acos(a / std::ldexp(1.0, cw - 1));
  double g = 0;
  for (int m = 0; m < n; ++m) g += std::fabs(std::sin((m + 1) * wp) / std::sin(wp));
  const double e = xmax * std::fabs(wp - w) * n * (n - 1) / 2 + g * std::ldexp(1.0, -f) +
                   (xmax + std::ldexp(0.5, -f)) * g * std::ldexp(1.0, -cw) + std::sqrt(0.5);
  return 2.0 / n * e;
}

}  // namespace eskin::hls
