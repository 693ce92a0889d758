// Golden (double-precision) per-carrier amplitude estimators: a bank of K
// sliding-window DFTs evaluated exactly AT each carrier frequency (not at the
// nearest bin), updated on every sample. Independent of hls/: this is the
// reference the fixed-point kernels are compared against.
//
// Number format: IEEE double throughout. Input samples are in any unit (ADC
// LSB after subtracting the mid code); amplitudes come out in the same unit.
//
// Definitions (n = index of the newest sample, s = n - N + 1 the oldest,
// w_k = 2*pi*f_k/fs, h(i) the window, i = 0 .. N-1 from oldest to newest):
//
//   amplitude(k) = (2 / sum_i h(i)) * sum_i h(i) * x[s+i] * exp(-j*w_k*i)
//
// Phase convention: the phase is that of the carrier at the OLDEST sample of
// the window. A tone x[m] = A*cos(w_k*m + phi) gives amplitude(k) =
// A*exp(j*(w_k*s + phi)) plus leakage (none for a bin-centred carrier,
// f_k = b*fs/N with 0 < b < N/2, under the rectangular window). The same
// convention is used by every variant and by carrier_demix.h.
//
// Windows: rectangular h = 1 (scale 2/N) or periodic Hann
// h(i) = 0.5 - 0.5*cos(2*pi*i/N) (sum N/2, scale 4/N). The sliding variants
// realise Hann as 0.5*R(w) - 0.25*R(w - 2*pi/N) - 0.25*R(w + 2*pi/N), where
// R(.) are rectangular sums with the same phase reference.
//
// Before N samples have been pushed the window holds zeros for the samples not
// yet seen (full() tells when it is filled).
//
// Variants (DftVariant in common/eskin/skin_config.h):
//   Direct    the windowed sum above recomputed from the stored window on
//             every amplitude() call (O(N) per carrier): the reference.
//   Recursive naive sliding DFT y <- z*y + x_new - c*x_old with z = e^{jw}
//             and c = e^{jwN} rounded to double. The pole sits on the unit
//             circle, so rounding errors are never forgotten: it drifts
//             (linearly in time for tones at the carrier frequency).
//   Damped    the same with z -> r*z, c -> r^N*c (r = cfg.damping < 1): the
//             errors decay, but the result is the DFT under the exponential
//             window r^(N-1-i) and is scaled like the rectangular one, so a
//             steady tone reads low by 1 - (1 - r^N)/(N*(1 - r)) ~ (N-1)(1-r)/2.
//   Exact     modulated form: a 64-bit integer phase accumulator per carrier,
//             theta(m) = m*inc mod 2^64, inc = round(f/fs*2^64). The term
//             x[m]*exp(-j*theta(m)) is added when sample m enters and the
//             identical term (same stored x[m], same integer phase, same
//             cos/sin call) is subtracted when it leaves, so no error is fed
//             back: the running sum differs from the true window sum only by
//             the rounding of its own additions (a random walk of ~eps*|sum|
//             steps, about eps*sqrt(n)*N*max|x| after n samples). The output
//             is rotated by exp(+j*theta(s)) to the oldest-sample reference.
//             64 rather than 32 phase bits: with 2^32 the frequency would be
//             off by up to fs/2^33 and the phase across one window by up to
//             N*2*pi/2^33 (~2e-8 rad at N = 32), too coarse for a reference
//             that must agree with Direct to ~1e-12; 2^64 makes it ~1e-17.
//   LsDemix   joint least squares of all carriers + DC over the window
//             (CarrierDemix in carrier_demix.h, fed by Exact sums): removes
//             the cross-talk of off-bin carriers. Requires 2K+1 <= N.
#pragma once

#include <complex>
#include <cstdint>
#include <memory>
#include <vector>

#include "eskin/skin_config.h"

namespace eskin::golden {

class SdftBank {
 public:
  virtual ~SdftBank() = default;
  virtual void push(double x) = 0;  // one sample (already mid-code subtracted)
  virtual std::complex<double> amplitude(int k) const = 0;
  double magnitude(int k) const { return std::abs(amplitude(k)); }
  virtual int carriers() const = 0;
  virtual bool full() const = 0;  // N samples seen
  // DC level (mean) over the window; LsDemix: the jointly fitted offset.
  virtual double dc() const = 0;
};

// The variant Auto stands for, for these carriers and this window: Exact
// when every carrier sits on a bin centre k fs/N under a rectangular window
// (no leakage: LS would give the same amplitudes at more cost), LsDemix when
// the joint fit is well posed (2K+1 <= N, condition within the default
// limit), else Exact. Any other variant is returned unchanged.
DftVariant resolve_variant(DftVariant variant, const std::vector<double>& freqs_hz, double fs_hz,
                           const DecoderConfig& cfg);

// Throws ConfigError naming the field: "decoder.window" (N < 2, or LsDemix
// with 2K+1 > N or carriers too close), "decoder.damping" (Damped needs
// 0 < r < 1; Recursive ignores it), "carriers[k]" (expected 0 < f < fs/2),
// "adc.rate_hz" (expected > 0).
std::unique_ptr<SdftBank> make_sdft_bank(DftVariant variant, const std::vector<double>& freqs_hz,
                                         double fs_hz, const DecoderConfig& cfg);

// Window h(i), i = 0..N-1 (oldest first): ones, or periodic Hann.
std::vector<double> window_weights(int n, bool hann);

// Phase increment per sample of a 64-bit accumulator (2^64 = one cycle) for
// frequency f: round(f/fs * 2^64) mod 2^64; negative f wraps.
uint64_t phase_increment(double f_hz, double fs_hz);
// Angle in [-pi, pi) of a 64-bit phase.
double phase_angle(uint64_t phase);

}  // namespace eskin::golden
