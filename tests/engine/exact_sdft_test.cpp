// host/engine/exact_sdft against the kernels it must equal bit for bit:
// hls/sdft_bank.h (window sums) and hls/carrier_magnitude.h (magnitudes).
// Bound everywhere: exact equality. Both sides are integer arithmetic
// defined to the bit; any difference is a bug.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "hls/carrier_magnitude.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/engine/exact_sdft.h"

namespace {

using eskin::engine::ExactSdft;
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
  ExactSdft fast(SdftWidthsRt{N, XW, CW, TW, ACC_W, FB}, inc);
  const auto x = stimulus(XW, samples, 7 + N + CW);
  eskin::hls::SdftBankToken tok[K];
  // Frames (sums out of push_block) at samples N-1 + 7 m, fed in blocks.
  const eskin::engine::FrameClock clock{N - 1, 7};
  std::vector<int32_t> want_frames;
  for (size_t i = 0; i < x.size(); ++i) {
    hls->push(x[i], tok);
    fast.push_block(&x[i], 1);
    for (int k = 0; k < cfg.carriers; ++k) {
      ASSERT_EQ(fast.re(k), tok[k].re) << "sample " << i << " carrier " << k;
      ASSERT_EQ(fast.im(k), tok[k].im) << "sample " << i << " carrier " << k;
    }
    if (i + 1 >= size_t(N) && (i + 1 - N) % 7 == 0) {
      for (int k = 0; k < cfg.carriers; ++k) want_frames.push_back(tok[k].re);
      for (int k = 0; k < cfg.carriers; ++k) want_frames.push_back(tok[k].im);
    }
  }
  ExactSdft framed(SdftWidthsRt{N, XW, CW, TW, ACC_W, FB}, inc);
  std::vector<int32_t> got(want_frames.size() + 2 * size_t(cfg.carriers) * 200);
  size_t frames = 0;
  for (size_t a = 0; a < x.size(); a += 999)
    frames += framed.push_block(&x[a], std::min<size_t>(999, x.size() - a), clock,
                                got.data() + frames * 2 * size_t(cfg.carriers));
  got.resize(frames * 2 * size_t(cfg.carriers));
  ASSERT_EQ(got, want_frames) << "frame sums";
  // The fused path: each frame's magnitudes straight out of the sample
  // loop equal carrier_magnitude's of its sums (magnitude_exact, checked
  // against the kernel below).
  const int kc = cfg.carriers;
  const MagnitudeWidths mw{ACC_W, 16, ACC_W > 16 ? ACC_W - 16 : 0};
  ExactSdft fused(SdftWidthsRt{N, XW, CW, TW, ACC_W, FB}, inc);
  std::vector<uint16_t> mags(frames * size_t(kc) + size_t(kc) * 200);
  size_t mframes = 0;
  for (size_t a = 0; a < x.size(); a += 999)
    mframes += fused.push_block(&x[a], std::min<size_t>(999, x.size() - a), clock, mw,
                                mags.data() + mframes * size_t(kc));
  ASSERT_EQ(mframes, frames);
  for (size_t f = 0; f < frames; ++f)
    for (int k = 0; k < kc; ++k)
      ASSERT_EQ(mags[f * size_t(kc) + size_t(k)],
                eskin::engine::magnitude_exact(want_frames[2 * size_t(kc) * f + size_t(k)],
                                               want_frames[2 * size_t(kc) * f + size_t(kc + k)], mw))
          << "frame " << f << " carrier " << k;
  // Warm-up: a bank started N samples before sample s equals the kernel
  // from s on (zero samples add zero terms).
  ExactSdft late(SdftWidthsRt{N, XW, CW, TW, ACC_W, FB}, inc);
  const size_t s = x.size() / 2;
  late.start_at(s - N);
  late.push_block(&x[s - N], N);
  auto hls2 = std::make_unique<Bank>();
  hls2->configure(cfg);
  for (size_t i = 0; i < s; ++i) hls2->push(x[i], tok);
  for (int k = 0; k < cfg.carriers; ++k) {
    ASSERT_EQ(late.re(k), tok[k].re) << "warm-up, carrier " << k;
    ASSERT_EQ(late.im(k), tok[k].im) << "warm-up, carrier " << k;
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
