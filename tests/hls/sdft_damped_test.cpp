// hls/sdft_damped.h (block Goertzel bank, the cheaper variant) against the
// golden Direct sliding DFT (host/golden/sdft_bank.h), at the block ends,
// where the golden window is exactly the kernel's block.
//
// Bound (goertzel_error_bound in hls/sdft_bank_config.h), per carrier, on
// (2/N)|y| vs (2/N)|X(w)|, X the exact block DFT at the nominal w:
//  * frequency: the resonator runs at w' with cos w' = a / 2^(CW-1) exactly
//    (a rounded); y is then the exact DFT at w' apart from the terms below,
//    and |X(w') - X(w)| <= sum_m |x| |e^{-j w' m} - e^{-j w m}|
//    <= xmax |w' - w| sum_m m = xmax |w' - w| N (N-1)/2.
//  * state rounding: each step adds one rounding error |d| <= 1/2 (in 2^-F
//    sample units) which the resonator carries forward with its impulse
//    response h(m) = sin((m+1) w')/sin w'; s(N-1) and s(N-2) are each off by
//    <= 1/2 sum_{m<N} |h(m)| = G/2, and y = s1 - e^{-j w'} s2 by <= G 2^-F.
//  * b = sin w' rounded to 2^-CW: <= 2^-CW |s2|, |s2| <= (xmax + 2^-F/2) G.
//  * output rounding of re and im: <= 1/2 each, sqrt(2)/2 together.
// Then the magnitude moves by at most the error of the complex value; times
// 2/N. The test also documents (prints) the measured max and RMS errors, and
// checks that tokens come only at block ends with the right k/last.
#include "hls/sdft_damped.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "hls/sdft_bank_config.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using namespace eskin::hls;

constexpr double kFs = 35000;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};

template <class Bank>
void compare_golden(const std::vector<double>& freqs, const std::vector<int32_t>& xs, int n,
                    int cw, int f, double* max_out = nullptr) {
  typename Bank::Config cfg;
  const auto st = make_goertzel_config<Bank>(freqs, kFs, cfg);
  ASSERT_TRUE(st.ok()) << st.message;
  Bank bank;
  ASSERT_TRUE(bank.configure(cfg));
  eskin::DecoderConfig dec;
  dec.window = n;
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::Direct, freqs, kFs, dec);
  int32_t xmax = 0;
  for (int32_t x : xs) xmax = std::max(xmax, std::abs(x));
  std::vector<double> bound(freqs.size());
  for (size_t k = 0; k < freqs.size(); ++k)
    bound[k] = goertzel_error_bound(n, cw, f, cfg.a[k], 2 * M_PI * freqs[k] / kFs, xmax);
  typename Bank::Token out[sizeof(cfg.a) / sizeof(cfg.a[0])];
  double max_err = 0, sum2 = 0;
  size_t count = 0, blocks = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    golden->push(double(xs[i]));
    const int got = bank.push(xs[i], out);
    const bool block_end = (i + 1) % size_t(n) == 0;
    ASSERT_EQ(got, block_end ? int(freqs.size()) : 0) << "sample " << i;
    if (!block_end) continue;
    ++blocks;
    for (int k = 0; k < got; ++k) {
      ASSERT_EQ(out[k].k, k);
      ASSERT_EQ(out[k].last, k == got - 1);
      const double mag = 2.0 / n * std::hypot(double(out[k].re), double(out[k].im));
      const double err = std::fabs(mag - golden->magnitude(k));
      ASSERT_LE(err, bound[size_t(k)]) << "sample " << i << " carrier " << k;
      max_err = std::max(max_err, err);
      sum2 += err * err;
      ++count;
    }
  }
  ASSERT_EQ(blocks, xs.size() / size_t(n));
  const double worst_bound = *std::max_element(bound.begin(), bound.end());
  // Non-vacuous: the bound is a small fraction of the largest amplitude.
  EXPECT_LT(worst_bound, 0.02 * xmax + 1.0);
  std::printf("N=%d CW=%d F=%d xmax=%d: max |error| %.3f LSB, RMS %.3f LSB, bound %.3f LSB\n",
              n, cw, f, xmax, max_err, std::sqrt(sum2 / double(count)), worst_bound);
  if (max_out) *max_out = max_err;
}

TEST(SdftDamped, GoldenDefaultScene) {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  eskin::sim::WorldModel world(scene);
  const int mid = int(std::lround(scene.skin.adc.mid_code()));
  std::vector<int32_t> xs;
  for (int c : world.all_codes()) xs.push_back(c - mid);
  ASSERT_GT(xs.size(), 10000u);
  compare_golden<GoertzelBlockBank<6, 32>>(scene.skin.carrier_freqs_hz(), xs, 32, 16, 4);
}

std::vector<int32_t> multitone(const std::vector<double>& freqs, double peak, size_t len,
                               uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> amp(freqs.size()), ph(freqs.size());
  for (size_t k = 0; k < freqs.size(); ++k) amp[k] = peak / freqs.size() * u(rng), ph[k] = 6.3 * u(rng);
  std::vector<int32_t> xs;
  for (size_t n = 0; n < len; ++n) {
    double v = 0.05 * peak * (u(rng) - 0.5);
    for (size_t k = 0; k < freqs.size(); ++k)
      v += amp[k] * std::cos(2 * M_PI * freqs[k] / kFs * double(n) + ph[k]);
    xs.push_back(int32_t(std::lround(std::clamp(v, -4096.0, 4095.0))));
  }
  return xs;
}

TEST(SdftDamped, GoldenRandomMultiTone) {
  const auto xs = multitone(kThesis, 4000, 64000, 21);
  double e16 = 0, e12 = 0;
  compare_golden<GoertzelBlockBank<6, 32>>(kThesis, xs, 32, 16, 4, &e16);
  compare_golden<GoertzelBlockBank<6, 32, 13, 12, 0>>(kThesis, xs, 32, 12, 0, &e12);
  compare_golden<GoertzelBlockBank<6, 64, 13, 18, 6>>(kThesis, xs, 64, 18, 6);
  EXPECT_GT(e12, e16);  // fewer coefficient and state bits => larger error
}

// Full-scale extremes: pinned +FS/-FS and the Nyquist square wave drive the
// state hardest; the narrowest legal state width must still hold it (an
// overflow would wrap and break the bound by orders of magnitude).
TEST(SdftDamped, ExtremesAtNarrowestState) {
  using Bank = GoertzelBlockBank<6, 32, 13, 16, 4, goertzel_min_state_width(32, 13, 4)>;
  std::vector<int32_t> pos(3200, 4095), neg(3200, -4096), alt(3200);
  for (size_t i = 0; i < alt.size(); ++i) alt[i] = i % 2 ? -4096 : 4095;
  compare_golden<Bank>(kThesis, pos, 32, 16, 4);
  compare_golden<Bank>(kThesis, neg, 32, 16, 4);
  compare_golden<Bank>(kThesis, alt, 32, 16, 4);
}

TEST(SdftDamped, RejectsBadCarriers) {
  GoertzelBlockBank<6, 32>::Config cfg;
  const auto st = make_goertzel_config<GoertzelBlockBank<6, 32>>({500, 5000}, kFs, cfg);
  EXPECT_EQ(st.error, SdftConfigError::CarrierTooLow) << st.message;
  EXPECT_NE(st.message.find("carriers[0]"), std::string::npos);
  GoertzelBlockBank<6, 32> bank;
  EXPECT_FALSE(bank.configure(cfg));  // carriers = 0: not configured
  static_assert(goertzel_min_state_width(32, 13, 4) == 13 + 4 + 2 + 10, "528 -> 10 bits");
}

}  // namespace
