// hls/sdft_bank.h: exact identities and error bounds.
//
// 1. QuarterSine: the integer table qsin(i) is within 0.5 + 2^-4 LSB of
//    A sin(pi/2 i/Q) for every CW, TW the kernel allows (exhaustive; the
//    header derives 2^-4 from the Q.30 Taylor series). std::sin is accurate to
//    ~1e-16 relative, far below 2^-4 LSB for A < 2^23.
// 2. ExactIdentity*: the kernel's accumulators equal, bit for bit, the direct
//    windowed sum of the same rounded terms, recomputed here from scratch with
//    int64 (own full-wave table built from qsin by symmetry, own index
//    rounding, phase n * inc from the absolute sample number, own floor
//    division). Exact integer arithmetic => equality must hold for ever; a
//    drifting or mis-cancelling accumulator fails it.
// 3. Golden*: (2/N)|acc| / G vs the golden Direct magnitude
//    (host/golden/sdft_bank.h, double): |diff| <= sdft_amplitude_error_bound,
//    derived per term (see hls/sdft_bank_config.h): phase rounded to TW bits
//    moves e^{-j theta} by <= |x| pi/2^TW; the coefficient rounding adds
//    <= |x| sqrt(2) (0.5 + 2^-4)/A; each of the two term roundings <= 0.5
//    (sqrt(2)/2 complex, /G); the 32-bit increment's frequency error
//    <= 2 pi 2^-33 rotates a term by <= N 2 pi 2^-33 relative to the window
//    start. The magnitude of a sum moves by at most the magnitude of the
//    summed errors: N terms, times 2/N.
// 4. ConfigCheck*: each rejected configuration gives its code and a message
//    naming the field.
#include "hls/sdft_bank.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "hls/sdft_bank_config.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using namespace eskin::hls;

// Independent model of the rounded terms: full-wave tables and floor division.
class DirectTerms {
 public:
  DirectTerms(int cw, int tw, int fb = 0) : cw_(cw), tw_(tw), fb_(fb) {
    const int q = 1 << (tw - 2), a = (1 << (cw - 1)) - 1;
    sin_.resize(size_t(4 * q));
    for (int i = 0; i < 4 * q; ++i) {
      const int r = i % (2 * q);  // sin(pi + u) = -sin(u)
      const int mag = r <= q ? (r == q ? a : sdft_quarter_sine(r, q, cw))
                             : sdft_quarter_sine(2 * q - r, q, cw);
      sin_[size_t(i)] = i < 2 * q ? mag : -mag;
    }
  }
  int index(uint32_t theta) const {  // nearest of 2^TW steps, ties up
    const double steps = std::ldexp(double(theta), tw_ - 32);
    return int(int64_t(std::floor(steps + 0.5)) % (int64_t(1) << tw_));
  }
  int64_t sin_at(int i) const { return sin_[size_t(i % int(sin_.size()))]; }
  int64_t cos_at(int i) const { return sin_at(i + int(sin_.size()) / 4); }
  int64_t round_term(int64_t p) const {  // floor(p / 2^(CW-1-FB) + 1/2)
    const int64_t d = int64_t(1) << (cw_ - 1 - fb_), num = 2 * p + d, den = 2 * d;
    return num >= 0 ? num / den : -((-num + den - 1) / den);
  }
  // Window sum over samples x[n-N+1..n] (hist holds x by absolute index).
  void window(const std::vector<int32_t>& hist, uint64_t n, int nwin, uint32_t inc,
              int64_t& re, int64_t& im) const {
    re = im = 0;
    for (int m = 0; m < nwin; ++m) {
      if (uint64_t(m) > n) break;  // before the first sample: zeros
      const uint64_t idx = n - uint64_t(m);
      const int64_t x = hist[idx % hist.size()];
      const int i = index(uint32_t(idx * inc));
      re += round_term(x * cos_at(i));
      im += round_term(-x * sin_at(i));
    }
  }

 private:
  int cw_, tw_, fb_;
  std::vector<int64_t> sin_;
};

struct Rng {  // splitmix64: fast, deterministic
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
};

const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};
constexpr double kFs = 35000;

TEST(SdftBank, QuarterSine) {
  for (int cw = 3; cw <= 24; ++cw) {
    for (int tw = 3; tw <= 14; ++tw) {
      const int q = 1 << (tw - 2);
      const double a = std::ldexp(1.0, cw - 1) - 1;
      for (int i = 0; i <= q; ++i) {
        const double ideal = a * std::sin(M_PI / 2 * i / q);
        ASSERT_LE(std::fabs(sdft_quarter_sine(i, q, cw) - ideal), 0.5 + 0.0625)
            << "cw=" << cw << " tw=" << tw << " i=" << i;
      }
    }
  }
}

// Runs `samples` inputs from gen(n) through Bank and compares with the
// direct sum every `every` samples and at the end.
template <class Bank, class Gen>
void check_identity(const std::vector<double>& freqs, uint64_t samples, uint64_t every, Gen gen,
                    int cw, int tw, int n_win, int fb = 0) {
  typename Bank::Config cfg;
  ASSERT_TRUE(make_sdft_bank_config<Bank>(freqs, kFs, cfg).ok());
  Bank bank;
  ASSERT_TRUE(bank.configure(cfg));
  DirectTerms direct(cw, tw, fb);
  std::vector<int32_t> hist(size_t(n_win), 0);
  typename Bank::Token out[sizeof(cfg.inc) / sizeof(cfg.inc[0])];
  int compared = 0;
  for (uint64_t n = 0; n < samples; ++n) {
    const int32_t x = gen(n);
    hist[n % hist.size()] = x;
    ASSERT_EQ(bank.push(x, out), cfg.carriers);
    if ((n + 1) % every != 0 && n + 1 != samples) continue;
    for (int k = 0; k < cfg.carriers; ++k) {
      int64_t re, im;
      direct.window(hist, n, n_win, cfg.inc[k], re, im);
      ASSERT_EQ(out[k].re, re) << "sample " << n << " carrier " << k;
      ASSERT_EQ(out[k].im, im) << "sample " << n << " carrier " << k;
      ASSERT_EQ(out[k].k, k);
      ASSERT_EQ(out[k].last, k == cfg.carriers - 1);
    }
    ++compared;
  }
  EXPECT_GE(compared, int(samples / every));
}

// 10^8 random full-scale samples, compared every 2^20 samples and at the end.
TEST(SdftBank, ExactIdentity100MSamples) {
  using Bank = SdftBank<6, 32>;  // XW 13, CW 16, TW 10, ACC_W 24
  Rng rng{12345};
  check_identity<Bank>(kThesis, 100'000'000, 1u << 20,
                       [&](uint64_t) { return int32_t(rng.next() >> 51) - 4096; }, 16, 10, 32);
}

// Extremes with the narrowest legal accumulator (19 = 13 + 1 + 5 bits): every
// sample compared. Pinned +FS/-FS give the largest sums a DC input can;
// alternating +-FS is a Nyquist tone; zero must stay exactly zero.
TEST(SdftBank, ExactIdentityExtremes) {
  using Bank = SdftBank<6, 32, 13, 16, 10, 19>;
  static_assert(sdft_min_acc_width(32, 13) == 19, "narrowest legal width");
  const uint64_t len = 20000;
  check_identity<Bank>(kThesis, len, 1, [](uint64_t) { return 4095; }, 16, 10, 32);
  check_identity<Bank>(kThesis, len, 1, [](uint64_t) { return -4096; }, 16, 10, 32);
  check_identity<Bank>(kThesis, len, 1,
                       [](uint64_t n) { return n % 2 ? -4096 : 4095; }, 16, 10, 32);
  check_identity<Bank>(kThesis, len, 1, [](uint64_t) { return 0; }, 16, 10, 32);
  // Carriers near the edges of the legal band, full-scale random, N = 64,
  // coarse table and coefficients, 3 term fraction bits, narrowest
  // accumulator (13 + 1 + 3 + 6 = 23).
  using Coarse = SdftBank<4, 64, 13, 10, 6, 23, 3>;
  Rng rng{7};
  check_identity<Coarse>({kFs / 64, 5000, 9000, kFs / 2 - kFs / 64}, 200000, 1,
                         [&](uint64_t) { return int32_t(rng.next() >> 51) - 4096; }, 10, 6, 64,
                         3);
  check_identity<Coarse>({kFs / 64, 5000, 9000, kFs / 2 - kFs / 64}, 5000, 1,
                         [](uint64_t n) { return n % 2 ? -4096 : 4095; }, 10, 6, 64, 3);
}

TEST(SdftBank, ZeroInputGivesZero) {
  SdftBank<6, 32> bank;
  SdftBank<6, 32>::Config cfg;
  ASSERT_TRUE((make_sdft_bank_config<SdftBank<6, 32>>(kThesis, kFs, cfg).ok()));
  ASSERT_TRUE(bank.configure(cfg));
  SdftBankToken out[6];
  for (int n = 0; n < 1000; ++n) {
    ASSERT_EQ(bank.push(0, out), 6);
    for (const auto& t : out) ASSERT_TRUE(t.re == 0 && t.im == 0);
  }
}

// Magnitude vs golden Direct on one sample stream (x already mid-subtracted).
template <class Bank>
void compare_golden(const std::vector<double>& freqs, const std::vector<int32_t>& xs,
                    const SdftWidths& w, double max_rel_bound, double* max_err_out) {
  typename Bank::Config cfg;
  ASSERT_TRUE(make_sdft_bank_config<Bank>(freqs, kFs, cfg).ok());
  Bank bank;
  ASSERT_TRUE(bank.configure(cfg));
  eskin::DecoderConfig dec;
  dec.window = w.n;
  dec.variant = eskin::DftVariant::Direct;
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::Direct, freqs, kFs, dec);
  int32_t xmax = 0;
  for (int32_t x : xs) xmax = std::max(xmax, std::abs(x));
  const double bound = sdft_amplitude_error_bound(w, xmax);
  const double g = (std::ldexp(1.0, w.cw - 1) - 1) / std::ldexp(1.0, w.cw - 1);
  typename Bank::Token out[sizeof(cfg.inc) / sizeof(cfg.inc[0])];
  double max_err = 0;
  for (size_t n = 0; n < xs.size(); ++n) {
    bank.push(xs[n], out);
    golden->push(double(xs[n]));
    for (int k = 0; k < cfg.carriers; ++k) {
      const double mag = 2.0 / w.n * std::hypot(double(out[k].re), double(out[k].im)) / g *
                         std::ldexp(1.0, -w.fb);
      const double err = std::fabs(mag - golden->magnitude(k));
      max_err = std::max(max_err, err);
      ASSERT_LE(err, bound) << "sample " << n << " carrier " << k;
    }
  }
  // The bound must not be vacuous for this signal: it is a small fraction of
  // the largest amplitude a carrier can have: 2 pi/2^TW relative, plus the
  // ~1.41 LSB of term rounding that does not scale with the signal.
  EXPECT_LT(bound, max_rel_bound * xmax + 1.5);
  std::printf("N=%d CW=%d TW=%d xmax=%d: max |error| %.3f LSB, bound %.3f LSB\n", w.n, w.cw,
              w.tw, xmax, max_err, bound);
  *max_err_out = max_err;
}

TEST(SdftBank, GoldenDefaultScene) {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  eskin::sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  const int mid = int(std::lround(scene.skin.adc.mid_code()));
  std::vector<int32_t> xs;
  for (int c : codes) xs.push_back(c - mid);
  ASSERT_GT(xs.size(), 10000u);
  ASSERT_EQ(scene.decoder.window, 32);
  double max_err = 0;
  compare_golden<SdftBank<6, 32>>(scene.skin.carrier_freqs_hz(), xs, SdftWidths{}, 0.01,
                                  &max_err);
  RecordProperty("max_abs_error_lsb", std::to_string(max_err));
}

TEST(SdftBank, GoldenRandomMultiTone) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> amp(6), ph(6);
  for (int k = 0; k < 6; ++k) amp[k] = 600 * u(rng), ph[k] = 2 * M_PI * u(rng);
  std::vector<int32_t> xs;
  for (int n = 0; n < 50000; ++n) {
    double v = 200 * (u(rng) - 0.5);  // wide-band noise on top
    for (int k = 0; k < 6; ++k) v += amp[k] * std::cos(2 * M_PI * kThesis[k] / kFs * n + ph[k]);
    xs.push_back(int32_t(std::lround(std::clamp(v, -4096.0, 4095.0))));
  }
  double e1 = 0, e2 = 0;
  compare_golden<SdftBank<6, 32>>(kThesis, xs, SdftWidths{}, 0.01, &e1);
  // A coarse configuration: the bound scales with it and still holds.
  compare_golden<SdftBank<6, 64, 13, 12, 8, 20>>(kThesis, xs, SdftWidths{64, 13, 12, 8, 20}, 0.03,
                                               &e2);
  EXPECT_GT(e2, e1);  // coarser table and coefficients => larger error
  // A fine one: 24-bit coefficients, 2^14-step phase, 8 term fraction bits.
  double e3 = 0;
  compare_golden<SdftBank<6, 32, 13, 24, 14, 27, 8>>(kThesis, xs, SdftWidths{32, 13, 24, 14, 27, 8},
                                                     0.002, &e3);
  EXPECT_LT(e3, e1);
}

TEST(SdftBank, ConfigCheckAccepts) {
  SdftBankConfig<6> cfg;
  const auto st = make_sdft_bank_config<SdftBank<6, 32>>(kThesis, kFs, cfg);
  ASSERT_TRUE(st.ok()) << st.message;
  EXPECT_EQ(cfg.carriers, 6);
  // round(1900/35000 * 2^32) = round(233155367.497...) (exact rational
  // arithmetic, by hand/Python): 233155367.
  EXPECT_EQ(cfg.inc[0], 233155367u);
}

TEST(SdftBank, ConfigCheckRejects) {
  using E = SdftConfigError;
  const SdftWidths w{};
  const auto expect = [](const SdftConfigStatus& st, E e, const char* field) {
    EXPECT_EQ(st.error, e) << st.message;
    EXPECT_NE(st.message.find(field), std::string::npos) << st.message;
  };
  expect(check_sdft_bank({0, 5000}, kFs, w, 6), E::CarrierTooLow, "carriers[0]");
  expect(check_sdft_bank({1000, 5000}, kFs, w, 6), E::CarrierTooLow, "carriers[0]");
  expect(check_sdft_bank({5000, 17500}, kFs, w, 6), E::CarrierTooHigh, "carriers[1]");
  expect(check_sdft_bank({5000, 17000}, kFs, w, 6), E::CarrierTooHigh, "carriers[1]");
  expect(check_sdft_bank({5000, 5500, 9000}, kFs, w, 6), E::SpacingBelowBin, "carriers[1]");
  expect(check_sdft_bank({}, kFs, w, 6), E::NoCarriers, "carriers");
  expect(check_sdft_bank(kThesis, kFs, w, 4), E::TooManyCarriers, "K_MAX");
  expect(check_sdft_bank(kThesis, 0, w, 6), E::BadRate, "fs_hz");
  expect(check_sdft_bank(kThesis, kFs, SdftWidths{32, 13, 16, 10, 18}, 6),
         E::AccumulatorOverflow, "acc_w");
  expect(check_sdft_bank(kThesis, kFs, SdftWidths{32, 13, 2, 10, 24}, 6), E::BadWidths,
         "widths");
  // The spacing rule follows the window: 500 Hz apart is fine with N = 128.
  EXPECT_TRUE(check_sdft_bank({5000, 5500}, kFs, SdftWidths{128, 13, 16, 10, 24}, 6).ok());
  EXPECT_FALSE(sdft_widths_ok(128, 13, 16, 10, 20));  // needs 21
  EXPECT_TRUE(sdft_widths_ok(128, 13, 16, 10, 21));
}

}  // namespace
