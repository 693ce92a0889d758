// host/engine/exact_sdft against the kernels it must equal bit for bit:
// hls/sdft_bank.h (window sums) and hls/carrier_magnitude.h (magnitudes).
// Bound everywhere: exact equality. Both sides are integer arithmetic
// defined to the bit; any difference is a bug.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hls/carrier_magnitude.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/engine/exact_sdft.h"

namespace {

using eskin::engine::ExactSdft;
using eskin::engine::FrameMode;
using eskin::engine::MagnitudeWidths;
using eskin::engine::SdftWidthsRt;

// Samples that exercise everything: full-scale extremes (the worst case for
// the sums), alternating signs, random values, runs of zeros.
std::vector<int32_t> stimulus(int xw, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const int32_t hi = (int32_t(1) << (xw - 1)) - 1, lo = -(int32_t(1) << (xw - 1));
  std::uniform_int_distribution<int32_t> any(lo, hi);
  std::vector<int32_t> x(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t seg = (i / 1000) % 4;
    x[i] = seg == 0 ? any(rng) : seg == 1 ? ((i & 1) ? hi : lo) : seg == 2 ? (i % 7 ? 0 : hi)
                                                                           : any(rng) / 16;
  }
  return x;
}

template <int K, int N, int XW, int CW, int TW, int ACC_W, int FB>
void expect_bank_equal(const std::vector<double>& freqs, double fs, size_t samples) {
  using Bank = eskin::hls::SdftBank<K, N, XW, CW, TW, ACC_W, FB>;
  typename Bank::Config cfg;
  ASSERT_TRUE(eskin::hls::make_sdft_bank_config<Bank>(freqs, fs, cfg).ok());
  auto hls = std::make_unique<Bank>();
  hls->configure(cfg);
  std::vector<uint32_t> inc(cfg.inc, cfg.inc + cfg.carriers);
  const SdftWidthsRt w{N, XW, CW, TW, ACC_W, FB};
  const int kc = cfg.carriers;
  ExactSdft fast(w, inc), portable(w, inc, false);
  const auto x = stimulus(XW, samples, 7 + N + CW);
  eskin::hls::SdftBankToken tok[K];
  // The kernel's sums after every sample; the engine fed one sample at a
  // time (sliding) equals them throughout.
  std::vector<int32_t> want_re, want_im;
  for (size_t i = 0; i < x.size(); ++i) {
    hls->push(x[i], tok);
    fast.push_block(&x[i], 1);
    portable.push_block(&x[i], 1);
    for (int k = 0; k < kc; ++k) {
      ASSERT_EQ(fast.re(k), tok[k].re) << "sample " << i << " carrier " << k;
      ASSERT_EQ(fast.im(k), tok[k].im) << "sample " << i << " carrier " << k;
      ASSERT_EQ(portable.re(k), tok[k].re) << "portable, sample " << i << " carrier " << k;
      ASSERT_EQ(portable.im(k), tok[k].im) << "portable, sample " << i << " carrier " << k;
      want_re.push_back(tok[k].re), want_im.push_back(tok[k].im);
    }
  }
  // Frames out of push_block, sums and magnitudes (the kernel's
  // carrier_magnitude of the kernel's sums), fed in blocks of 999 samples:
  // sliding, direct and the automatic choice; steps below, near and above
  // N (the choice goes both ways); a first frame before the window is full
  // (zero samples before the start), at it and later.
  constexpr int kShift = ACC_W > 16 ? ACC_W - 16 : 0;
  using Mag = eskin::hls::CarrierMagnitude<ACC_W, 16, kShift>;
  const MagnitudeWidths mw{ACC_W, 16, kShift};
  for (const bool pairs : {true, false})
    for (const FrameMode mode : {FrameMode::Sliding, FrameMode::Direct, FrameMode::Auto})
      for (const int step : {1, 7, N - 1, N + 3, 3 * N})
        for (const uint64_t first : {uint64_t(N - 1), uint64_t(N / 2), uint64_t(2 * N + 5)}) {
          const std::string what = std::string(pairs ? "pair kernels" : "portable kernels") +
                                   ", mode " + std::to_string(int(mode)) + " step " +
                                   std::to_string(step) + " first " + std::to_string(first);
          const eskin::engine::FrameClock clock{first, step};
          ExactSdft framed(w, inc, pairs), fused(w, inc, pairs);
          framed.set_frame_mode(mode), fused.set_frame_mode(mode);
          const size_t cap = x.size() / size_t(step) + 2;
          std::vector<int32_t> sums(cap * 2 * size_t(kc));
          std::vector<uint16_t> mags(cap * size_t(kc));
          size_t frames = 0, mframes = 0;
          for (size_t a = 0; a < x.size(); a += 999) {
            const size_t len = std::min<size_t>(999, x.size() - a);
            frames += framed.push_block(&x[a], len, clock, sums.data() + frames * 2 * size_t(kc));
            mframes += fused.push_block(&x[a], len, clock, mw, mags.data() + mframes * size_t(kc));
          }
          ASSERT_EQ(frames, (x.size() - 1 - first) / size_t(step) + 1) << what;
          ASSERT_EQ(mframes, frames) << what;
          for (size_t f = 0; f < frames; ++f) {
            const size_t s = first + f * size_t(step);
            for (int k = 0; k < kc; ++k) {
              const int32_t re = want_re[s * size_t(kc) + size_t(k)];
              const int32_t im = want_im[s * size_t(kc) + size_t(k)];
              const int32_t* got = sums.data() + f * 2 * size_t(kc);
              ASSERT_EQ(got[k], re) << what << " frame " << f << " carrier " << k;
              ASSERT_EQ(got[kc + k], im) << what << " frame " << f << " carrier " << k;
              ASSERT_EQ(mags[f * size_t(kc) + size_t(k)], Mag::magnitude(re, im))
                  << what << " frame " << f << " carrier " << k;
            }
          }
        }
  // Direct frames, then the sums read between frames (recomputed from the
  // last N samples), then sliding again (the ring rebuilt from them), with
  // either kernels (their rings differ).
  for (const bool pairs : {true, false}) {
    ExactSdft mixed(w, inc, pairs);
    mixed.set_frame_mode(FrameMode::Direct);
    const size_t half = x.size() / 2;
    std::vector<int32_t> scratch((half / size_t(N) + 2) * 2 * size_t(kc));
    mixed.push_block(x.data(), half, {uint64_t(N - 1), N}, scratch.data());
    for (int k = 0; k < kc; ++k) {
      const size_t at = (half - 1) * size_t(kc) + size_t(k);
      ASSERT_EQ(mixed.re(k), want_re[at]) << "after direct, carrier " << k;
      ASSERT_EQ(mixed.im(k), want_im[at]) << "after direct, carrier " << k;
    }
    mixed.set_frame_mode(FrameMode::Sliding);
    for (size_t i = half; i < std::min(x.size(), half + 3 * size_t(N)); ++i) {
      mixed.push_block(&x[i], 1);
      for (int k = 0; k < kc; ++k) {
        const size_t at = i * size_t(kc) + size_t(k);
        ASSERT_EQ(mixed.re(k), want_re[at]) << "sliding again, sample " << i;
        ASSERT_EQ(mixed.im(k), want_im[at]) << "sliding again, sample " << i;
      }
    }
  }
  // Warm-up: a bank started N samples before sample s equals the kernel
  // from s on (zero samples add zero terms), sliding or keeping only the
  // samples (direct, no frames: the sums computed when read).
  const size_t s = x.size() / 2;
  for (const FrameMode mode : {FrameMode::Sliding, FrameMode::Direct}) {
    ExactSdft late(w, inc);
    late.set_frame_mode(mode);
    late.start_at(s - N);
    late.push_block(&x[s - N], N);
    for (int k = 0; k < kc; ++k) {
      ASSERT_EQ(late.re(k), want_re[(s - 1) * size_t(kc) + size_t(k)]) << "warm-up, carrier " << k;
      ASSERT_EQ(late.im(k), want_im[(s - 1) * size_t(kc) + size_t(k)]) << "warm-up, carrier " << k;
    }
  }
}

const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};

TEST(ExactSdft, EqualsKernelAtTheTopDefaults) {
  expect_bank_equal<6, 32, 12, 16, 10, 18, 0>(kThesis, 35000, 20000);
}
TEST(ExactSdft, EqualsKernelWithFractionBitsAndWideTable) {
  expect_bank_equal<6, 64, 13, 16, 12, 24, 4>(kThesis, 35000, 12000);
}
TEST(ExactSdft, EqualsKernelWithWideCoefficients) {  // CW > 16: two tables
  expect_bank_equal<6, 32, 12, 18, 12, 22, 4>(kThesis, 35000, 12000);
}
TEST(ExactSdft, EqualsKernelWith64BitProducts) {     // XW + CW > 32
  expect_bank_equal<6, 16, 12, 24, 14, 25, 8>({2500, 4800, 7100, 9400, 11700, 14000}, 35000,
                                              8000);
}
// One block of 8 lanes with 1, 3 and 8 carriers (the table reads skip the
// padding lanes: 2, 4 and 8 live ones).
TEST(ExactSdft, EqualsKernelOneThreeAndEightCarriers) {
  expect_bank_equal<1, 32, 12, 16, 10, 18, 0>({5000}, 35000, 6000);
  expect_bank_equal<3, 64, 12, 16, 10, 19, 0>({2000, 6100, 9900}, 35000, 6000);
  expect_bank_equal<8, 32, 12, 16, 10, 18, 0>(
      {1900, 3300, 5000, 7140, 8300, 10000, 11500, 13000}, 35000, 6000);
}
TEST(ExactSdft, EqualsKernelManyCarriers) {  // 40 carriers: more than two vector blocks
  std::vector<double> f;
  for (int b = 0; b < 40; ++b) f.push_back((3 + 3 * b) * 35000.0 / 256 + 17.0);
  expect_bank_equal<40, 256, 12, 16, 10, 21, 0>(f, 35000, 6000);
}

template <int ACC_W, int MAG_W, int SHIFT>
void expect_magnitude_equal() {
  const MagnitudeWidths mw{ACC_W, MAG_W, SHIFT};
  std::mt19937_64 rng(ACC_W * 100 + MAG_W + SHIFT);
  const int32_t lim = int32_t((int64_t(1) << (ACC_W - 1)) - 1);
  std::uniform_int_distribution<int32_t> any(-lim - 1, lim);
  std::vector<int32_t> re, im;
  // Random points, the axes and the extremes, and points whose squared
  // radius sits on either side of a perfect square (where a wrong root shows).
  for (int i = 0; i < 200000; ++i) re.push_back(any(rng)), im.push_back(any(rng) >> (i % 20));
  for (int32_t v : {0, 1, -1, lim, -lim - 1}) re.push_back(v), im.push_back(v);
  for (int64_t r = 1; r < lim && re.size() < 260000; r = r * 9 / 8 + 1)
    for (int d = -1; d <= 1; ++d) re.push_back(int32_t(r)), im.push_back(d);
  // Q = floor(P / 4^(SHIFT-1)) exactly an odd square b^2 and just either
  // side (where the rounded magnitude steps), over the whole range.
  const int64_t unit = SHIFT > 1 ? int64_t(1) << (SHIFT - 1) : 1;
  for (int64_t b = 1; b * unit < lim && re.size() < 400000; b = b * 17 / 16 + 2 - (b * 17 / 16) % 2)
    for (int d = -1; d <= 1; ++d) re.push_back(int32_t(b * unit + d)), im.push_back(0);
  std::vector<uint16_t> got(re.size());
  eskin::engine::magnitudes(re.data(), im.data(), int(re.size()), mw, got.data());
  using M = eskin::hls::CarrierMagnitude<ACC_W, MAG_W, SHIFT>;
  for (size_t i = 0; i < re.size(); ++i) {
    const uint32_t want = M::magnitude(re[i], im[i]);
    ASSERT_EQ(got[i], want) << "re " << re[i] << " im " << im[i];
    ASSERT_EQ(eskin::engine::magnitude_exact(re[i], im[i], mw), want);
  }
}

TEST(ExactSdftMagnitude, EqualsKernelFastPath) {
  EXPECT_TRUE(eskin::engine::magnitude_fast_ok({18, 16, 2}));
  expect_magnitude_equal<18, 16, 2>();   // dtmf_top
  expect_magnitude_equal<21, 16, 0>();   // 12-bit skin, N = 256 (saturates)
  expect_magnitude_equal<24, 16, 8>();   // carrier_magnitude's default shift
  expect_magnitude_equal<20, 12, 1>();
}
TEST(ExactSdftMagnitude, EqualsKernelDigitLoopPath) {
  EXPECT_FALSE(eskin::engine::magnitude_fast_ok({30, 16, 14}));
  expect_magnitude_equal<30, 16, 14>();
  expect_magnitude_equal<32, 16, 16>();
}

TEST(ExactSdft, RejectsIllegalWidthsNamingTheField) {
  try {
    ExactSdft bad(SdftWidthsRt{32, 12, 16, 10, 17, 0}, {1});
    FAIL() << "ACC_W 17 < 18 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sdft.acc_w"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ExactSdft(SdftWidthsRt{32, 12, 16, 10, 18, 0}, {}), std::invalid_argument);
  EXPECT_THROW(ExactSdft(SdftWidthsRt{32, 12, 16, 15, 18, 0}, {1}), std::invalid_argument);
}

}  // namespace
