// hls/carrier_magnitude.h against independent references.
//
// The kernel's contract: mag = min(floor(x + 1/2), 2^MAG_W - 1) with
// x = sqrt(re^2 + im^2) / 2^SHIFT (round half up, saturate). Two independent
// checks of that contract:
//  * exact integer characterisation (no square root at all): for m >= 1,
//    m = floor(x + 1/2)  <=>  (2m-1)^2 4^SHIFT <= 4 P < (2m+1)^2 4^SHIFT,
//    and m = 0 <=> 4 P < 4^SHIFT, with P = re^2 + im^2, all in 128-bit
//    integers. Saturated outputs must have x >= 2^MAG_W - 1/2, i.e.
//    4 P >= (2^(MAG_W+1) - 1)^2 4^SHIFT.
//  * double precision: |mag - x| <= 1/2 (+1e-9 for the double's own
//    rounding: P < 2^63 is exact to 2^-53 relative, sqrt adds half an ulp)
//    whenever not saturated — the worst case stated in the header.
// The golden-model comparison on the default scene (test
// CarrierMagnitudeGolden) is in this file too; its bound is derived there.
#include "hls/carrier_magnitude.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <random>
#include <vector>

#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using u128 = unsigned __int128;

template <int ACC_W, int MAG_W, int SHIFT>
void expect_exact(int32_t re, int32_t im) {
  const uint32_t m = eskin::hls::CarrierMagnitude<ACC_W, MAG_W, SHIFT>::magnitude(re, im);
  const uint32_t mag_max = (uint32_t(1) << MAG_W) - 1;
  const u128 p = u128(int64_t(re) * int64_t(re)) + u128(int64_t(im) * int64_t(im));
  const u128 p4 = p * 4;
  const u128 scale = u128(1) << (2 * SHIFT);
  ASSERT_LE(m, mag_max) << "re=" << re << " im=" << im;
  const u128 lo = (m == 0) ? 0 : u128(2 * uint64_t(m) - 1) * (2 * uint64_t(m) - 1) * scale;
  const u128 hi = u128(2 * uint64_t(m) + 1) * (2 * uint64_t(m) + 1) * scale;
  ASSERT_LE(lo, p4) << "re=" << re << " im=" << im << " mag=" << m;
  if (m == mag_max) {
    // Either exactly rounded to full scale or saturated from above.
    return;
  }
  ASSERT_LT(p4, hi) << "re=" << re << " im=" << im << " mag=" << m;
  const double x = std::sqrt(double(re) * re + double(im) * im) / std::ldexp(1.0, SHIFT);
  ASSERT_LE(std::fabs(double(m) - x), 0.5 + 1e-9) << "re=" << re << " im=" << im;
}

template <int ACC_W, int MAG_W, int SHIFT>
void random_and_extremes(int n_random, uint64_t seed) {
  const int32_t vmax = int32_t((int64_t(1) << (ACC_W - 1)) - 1);
  const int32_t vmin = int32_t(-(int64_t(1) << (ACC_W - 1)));
  // Full-scale corners, zero, axis-aligned, near-zero.
  const int32_t edge[] = {vmin, vmin + 1, -1, 0, 1, vmax - 1, vmax, vmin / 2, vmax / 3};
  for (int32_t re : edge)
    for (int32_t im : edge) expect_exact<ACC_W, MAG_W, SHIFT>(re, im);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int32_t> full(vmin, vmax);
  std::uniform_int_distribution<int> bits(0, ACC_W - 1);
  for (int i = 0; i < n_random; ++i) {
    // Half the draws full range, half at a random magnitude scale (small
    // values are where rounding matters most relative to the value).
    int32_t re = full(rng), im = full(rng);
    if (i & 1) {
      const int b = bits(rng);
      re = int32_t(re >> (ACC_W - 1 - b));
      im = int32_t(im >> (ACC_W - 1 - b));
    }
    expect_exact<ACC_W, MAG_W, SHIFT>(re, im);
  }
}

TEST(CarrierMagnitude, DefaultWidthsRandomAndExtremes) {
  random_and_extremes<24, 16, 8>(200000, 1);
}

TEST(CarrierMagnitude, DefaultShiftNeverSaturates) {
  // SHIFT = ACC_W - MAG_W: the largest magnitude, |(-2^23, -2^23)| / 2^8 =
  // 2^15.5 = 46341.0, is below 2^16 - 1.
  using M = eskin::hls::CarrierMagnitude<24, 16>;
  static_assert(M::NB == 17);
  EXPECT_EQ(M::magnitude(-(1 << 23), -(1 << 23)), 46341u);  // 46340.95 rounded
  EXPECT_EQ(M::magnitude(-(1 << 23), 0), 32768u);
  EXPECT_EQ(M::magnitude(0, 0), 0u);
  EXPECT_EQ(M::magnitude(3 << 8, 4 << 8), 5u);  // 3-4-5 triangle, exact
}

TEST(CarrierMagnitude, SaturatingShiftsRandomAndExtremes) {
  // Small shifts overflow MAG_W for large sums: saturation is checked by
  // expect_exact's lower bound at mag = 2^MAG_W - 1.
  random_and_extremes<24, 16, 0>(50000, 2);
  random_and_extremes<24, 16, 3>(50000, 3);
  random_and_extremes<32, 30, 0>(50000, 4);
  random_and_extremes<32, 16, 16>(50000, 5);
  random_and_extremes<13, 8, 2>(20000, 6);
}

TEST(CarrierMagnitude, ExhaustiveSmallWidths) {
  // Every (re, im) of 8 bits, with and without saturation.
  for (int re = -128; re < 128; ++re)
    for (int im = -128; im < 128; ++im) {
      expect_exact<8, 8, 0>(re, im);
      expect_exact<8, 6, 1>(re, im);
      expect_exact<8, 4, 4>(re, im);
    }
}

TEST(CarrierMagnitude, PushPassesIndexAndLast) {
  eskin::hls::CarrierMagnitude<> m;
  eskin::hls::CarrierMagnitudeIn in;
  in.k = 5;
  in.re = -(12 << 8);
  in.im = 5 << 8;
  in.last = true;
  eskin::hls::CarrierMagnitudeOut out;
  ASSERT_TRUE(m.push(in, out));
  EXPECT_EQ(out.k, 5);
  EXPECT_TRUE(out.last);
  EXPECT_EQ(out.mag, 13u);
}

// Default scene through hls sdft_bank -> carrier_magnitude, compared with
// the golden magnitude (2/N |window sum|, double) of the same samples.
// Units: the kernel's mag is |acc| / 2^SHIFT, and |acc| approximates G |sum|
// (G = 1 - 2^-(CW-1), sdft_bank's coefficient gain), so the golden-unit
// estimate is M = (2/N) 2^SHIFT mag / G. Bound, by the triangle inequality:
//   |M - golden| <= (2/N) 2^(SHIFT-1) / G             (this kernel: 1/2 LSB)
//                 + sdft_amplitude_error_bound(...)   (sdft_bank's own bound,
//                   derived in tests/hls/sdft_bank_test.cpp)
//                 + 1e-6 (the golden Exact variant's double rounding,
//                   ~1e-16 sqrt(n) N max|x|, far below).
// Both halves are also checked separately: |2^SHIFT mag - |acc|| <= 2^(SHIFT-1)
// on every token of the real stream.
template <int SHIFT>
double golden_scene_max_error(const std::vector<int32_t>& xs, const eskin::sim::Scene& scene,
                              double min_ratio) {
  using Bank = eskin::hls::SdftBank<6, 32>;  // XW 13, CW 16, TW 10, ACC_W 24
  using Mag = eskin::hls::CarrierMagnitude<24, 16, SHIFT>;
  const auto freqs = scene.skin.carrier_freqs_hz();
  const double fs = scene.skin.adc.rate_hz;
  Bank::Config cfg;
  EXPECT_TRUE(eskin::hls::make_sdft_bank_config<Bank>(freqs, fs, cfg).ok());
  Bank bank;
  EXPECT_TRUE(bank.configure(cfg));
  // The HLS bank is the exact sliding DFT, so the golden reference is too.
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::Exact, freqs, fs, scene.decoder);
  const int n_win = 32;
  const double g = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);
  int32_t xmax = 0;
  for (int32_t x : xs) xmax = std::max(xmax, std::abs(x));
  const double sdft_bound = eskin::hls::sdft_amplitude_error_bound(eskin::hls::SdftWidths{}, xmax);
  const double mag_bound = 2.0 / n_win * std::ldexp(1.0, SHIFT - 1) / g;
  const double bound = mag_bound + sdft_bound + 1e-6;
  Bank::Token out[6];
  const Mag mag;
  double max_err = 0, max_amp = 0;
  for (size_t n = 0; n < xs.size(); ++n) {
    EXPECT_EQ(bank.push(xs[n], out), 6);
    golden->push(double(xs[n]));
    for (int k = 0; k < 6; ++k) {
      eskin::hls::CarrierMagnitudeIn in{out[k].k, out[k].re, out[k].im, out[k].last};
      eskin::hls::CarrierMagnitudeOut o;
      mag.push(in, o);
      const double scaled = std::ldexp(double(o.mag), SHIFT);
      const double acc = std::hypot(double(out[k].re), double(out[k].im));
      EXPECT_LE(std::fabs(scaled - acc), std::ldexp(1.0, SHIFT - 1) + 1e-9) << "sample " << n;
      const double m = 2.0 / n_win * scaled / g;
      const double err = std::fabs(m - golden->magnitude(k));
      max_err = std::max(max_err, err);
      max_amp = std::max(max_amp, golden->magnitude(k));
      if (err > bound) {
        ADD_FAILURE() << "sample " << n << " carrier " << k << ": " << m << " vs golden "
                      << golden->magnitude(k) << ", bound " << bound;
        return max_err;
      }
    }
  }
  // Not vacuous: the scene's largest carrier is min_ratio times the bound.
  EXPECT_GT(max_amp, min_ratio * bound);
  std::printf("SHIFT %d: bound %.4f LSB (this kernel %.4f), largest amplitude %.2f\n", SHIFT,
              bound, mag_bound, max_amp);
  return max_err;
}

TEST(CarrierMagnitudeGolden, DefaultScene) {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  ASSERT_EQ(scene.skin.carriers(), 6);
  ASSERT_EQ(scene.decoder.window, 32);
  eskin::sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  ASSERT_GT(codes.size(), 10000u);
  const int mid = int(std::lround(scene.skin.adc.mid_code()));
  std::vector<int32_t> xs;
  for (int c : codes) xs.push_back(c - mid);
  // SHIFT 2: 13-bit samples, N = 32 give |re|, |im| <= 2^17, so the
  // magnitude <= 2^17.5 / 4 < 2^16: no saturation, finest resolution.
  const double e2 = golden_scene_max_error<2>(xs, scene, 20.0);
  // The default SHIFT 8 (for full 24-bit sums): coarser, bound scales.
  const double e8 = golden_scene_max_error<8>(xs, scene, 5.0);
  EXPECT_GT(e8, e2);
  RecordProperty("max_abs_error_lsb_shift2", std::to_string(e2));
  RecordProperty("max_abs_error_lsb_shift8", std::to_string(e8));
  std::printf("max |hls - golden| (ADC LSB): SHIFT 2: %.4f, SHIFT 8: %.4f\n", e2, e8);
}

}  // namespace
