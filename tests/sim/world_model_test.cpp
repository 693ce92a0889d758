// DTMF world model: determinism, the carriers a press excites and their
// amplitudes (checked with a DFT written here), ground-truth ramps, clipping,
// the idle code, noise level, and the WAV writer (read back with libsndfile).
#include "sim/world_model.h"

#include <gtest/gtest.h>
#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "sim/scene.h"
#include "sim/wav_io.h"

namespace eskin::sim {
namespace {

// 3x3 skin at 35 kHz, 10-bit, carriers on bin centres of a 32-sample window
// (bins 2, 3, 5 for rows, 7, 8, 9 for columns; one bin = 1093.75 Hz).
Scene planned_scene() {
  Scene s;
  s.file = "test";
  s.duration_s = 0.05;
  s.skin.rows = 3;
  s.skin.cols = 3;
  const double bin = 35000.0 / 32;
  s.skin.row_freq_hz = {2 * bin, 3 * bin, 5 * bin};
  s.skin.col_freq_hz = {7 * bin, 8 * bin, 9 * bin};
  s.skin.osc_amplitude_v = 1.0;
  s.skin.amp_gain = 0.5;
  s.skin.conductance.kind = Conductance::Kind::Saturating;
  s.skin.conductance.p_half_kpa = 50;
  s.skin.adc = AdcConfig{};  // 35 kHz, 10 bits, 3.3 V, offset 1.65 V, no noise
  return s;
}

Press taxel_press(int row, int col, double kpa, double t0, double ramp, double hold,
                  double release) {
  Press p;
  p.row = row, p.col = col, p.pressure_kpa = kpa;
  p.t_start_s = t0, p.ramp_s = ramp, p.hold_s = hold, p.release_s = release;
  return p;
}

// |X_k| * 2 / N: the peak amplitude of bin k over codes[n0 .. n0+N).
double bin_amplitude(const std::vector<int>& codes, size_t n0, int N, int k) {
  std::complex<double> acc = 0;
  for (int n = 0; n < N; ++n)
    acc += double(codes[n0 + size_t(n)]) * std::polar(1.0, -2 * M_PI * k * n / N);
  return 2.0 * std::abs(acc) / N;
}

TEST(WorldModel, SameSeedSameStreamOtherSeedDiffers) {
  Scene s = planned_scene();
  s.skin.adc.noise_rms_v = 0.005;
  s.presses.push_back(taxel_press(1, 2, 40, 0.005, 0.005, 0.02, 0.005));
  WorldModel a(s), b(s);
  std::vector<int> ca = a.all_codes(), cb = b.all_codes();
  EXPECT_EQ(ca, cb);  // exact: std::mt19937_64 and the arithmetic are deterministic
  s.seed = 2;
  std::vector<int> cc = WorldModel(s).all_codes();
  ASSERT_EQ(cc.size(), ca.size());
  // Noise of 0.005 V rms is ~1.6 LSB: independent draws give a different
  // code in most samples; require at least half so the check can fail.
  size_t differ = 0;
  for (size_t n = 0; n < ca.size(); ++n) differ += ca[n] != cc[n];
  EXPECT_GT(differ, ca.size() / 2);
  EXPECT_NE(a.start_phase(2), WorldModel(s).start_phase(2));
}

// A press on (i, j) with g = 0.5 must show carriers i and R+j at
// osc * gain * g / lsb = 0.5 * 0.5 / (3.3/1024) = 77.58 LSB and nothing else.
// Bin-centred carriers and a rectangular 32-sample window: no leakage at all,
// so the only error is rounding, |e(n)| <= 0.5 LSB, whose DFT term is at most
// (2/N) * N * 0.5 = 1 LSB in any bin (worst case, triangle inequality).
TEST(WorldModel, SinglePressExcitesExactlyItsRowAndColumnCarriers) {
  const int N = 32;
  const int bins[6] = {2, 3, 5, 7, 8, 9};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      SCOPED_TRACE("taxel " + std::to_string(i) + "," + std::to_string(j));
      Scene s = planned_scene();
      s.seed = uint64_t(10 + 3 * i + j);
      s.presses.push_back(taxel_press(i, j, 50, 0.005, 0.005, 0.03, 0.005));
      std::vector<int> codes = WorldModel(s).all_codes();
      const double lsb = 3.3 / 1024;
      const double expect = 1.0 * 0.5 * (50.0 / (50.0 + 50.0)) / lsb;
      size_t n0 = size_t(0.02 * 35000);  // inside the hold (0.010 .. 0.040 s)
      for (int k = 1; k < N / 2; ++k) {
        double a = bin_amplitude(codes, n0, N, k);
        bool carrier_row = k == bins[i], carrier_col = k == bins[3 + j];
        if (carrier_row || carrier_col)
          EXPECT_NEAR(a, expect, 1.0) << "bin " << k;
        else
          EXPECT_LE(a, 1.0) << "bin " << k;
      }
      // DC: mean code is the bias (1.65 V = 512 LSB) within the 0.5 LSB rounding.
      double mean = 0;
      for (int n = 0; n < N; ++n) mean += codes[n0 + size_t(n)];
      EXPECT_NEAR(mean / N, 512.0, 0.5);
    }
}

// The physics written out independently: with constant pressure the ADC input
// is offset + sum over the two excited carriers of A sin(2 pi f (1+err) n/fs
// + phi); phases come from the model (they are the seed's only effect here).
// Codes must match exactly except where v/lsb lies within 1e-9 of a rounding
// boundary (different summation order), which we skip.
TEST(WorldModel, CodesFollowThePhysicsWithFrequencyError) {
  Scene s = planned_scene();
  s.skin.row_freq_hz = {1900, 3300, 5000};
  s.skin.col_freq_hz = {7140, 8300, 10000};
  s.skin.freq_error = {0.01, -0.02, 0.0, 0.005, 0.03, -0.01};
  s.presses.push_back(taxel_press(2, 1, 30, 0.0, 0.0, 0.05, 0.0));
  WorldModel wm(s);
  std::vector<int> codes = wm.all_codes();
  const double lsb = 3.3 / 1024, g = 30.0 / 80.0, amp = 0.5 * g;
  const double fr = 5000 * 1.0, fc = 8300 * 1.03;
  size_t checked = 0;
  for (size_t n = 0; n < codes.size(); ++n) {
    double v = 1.65 + amp * std::sin(2 * M_PI * fr * n / 35000 + wm.start_phase(2)) +
               amp * std::sin(2 * M_PI * fc * n / 35000 + wm.start_phase(4));
    double x = v / lsb;
    if (std::fabs(x - std::floor(x) - 0.5) < 1e-9) continue;
    ASSERT_EQ(codes[n], int(std::lround(x))) << "n=" << n;
    ++checked;
  }
  EXPECT_GT(checked, codes.size() - 5);
}

// Ground truth: linear ramp up, hold, linear release, zero elsewhere; two
// stimuli on one taxel add. Expected values come from the scene's definition
// (t = n / fs), to 1e-9 kPa (double rounding of t only).
TEST(WorldModel, GroundTruthRampsHoldsReleasesAndAdds) {
  Scene s = planned_scene();
  s.presses.push_back(taxel_press(0, 1, 40, 0.010, 0.004, 0.010, 0.008));
  s.presses.push_back(taxel_press(0, 1, 10, 0.020, 0.0, 0.002, 0.0));
  WorldModel wm(s);
  auto at = [&](double t) {
    std::vector<double> kpa;
    wm.pressure_at(size_t(std::lround(t * 35000)), kpa);
    EXPECT_EQ(kpa.size(), 9u);
    for (int k = 0; k < 9; ++k) {
      if (k == 1) continue;
      EXPECT_EQ(kpa[size_t(k)], 0.0) << "taxel " << k;
    }
    return kpa[1];
  };
  // Sample times on the 35 kHz grid: n = 35 k is exactly t = k ms.
  EXPECT_NEAR(at(0.009), 0.0, 1e-9);
  EXPECT_NEAR(at(0.011), 40.0 * 1 / 4, 1e-9);   // 1 ms into a 4 ms ramp
  EXPECT_NEAR(at(0.013), 40.0 * 3 / 4, 1e-9);
  EXPECT_NEAR(at(0.016), 40.0, 1e-9);           // hold
  EXPECT_NEAR(at(0.021), 40.0 + 10.0, 1e-9);    // second press adds
  EXPECT_NEAR(at(0.026), 40.0 * 6 / 8, 1e-9);   // 2 ms into an 8 ms release
  EXPECT_NEAR(at(0.032), 0.0, 1e-9);
  EXPECT_EQ(wm.touched_taxels(), std::vector<int>{1});
}

// A slide's disk moves at constant speed: from x = -0.5 to 2.5 along row 1
// over 60 ms, its centre passes x = 0, 1, 2 at 10, 30, 50 ms; the most
// pressed taxel there must be column 0, 1, 2 respectively.
TEST(WorldModel, SlideMovesAcrossColumns) {
  Scene s = planned_scene();
  Slide sl;
  sl.x0 = -0.5, sl.y0 = 1, sl.x1 = 2.5, sl.y1 = 1;
  sl.radius = 0.6, sl.pressure_kpa = 30, sl.t_start_s = 0.0, sl.duration_s = 0.06, sl.ramp_s = 0.002;
  s.slides.push_back(sl);
  s.duration_s = 0.06;
  WorldModel wm(s);
  for (int c = 0; c < 3; ++c) {
    std::vector<double> kpa;
    wm.pressure_at(size_t(35 * (10 + 20 * c)), kpa);
    int best = 0;
    for (int k = 1; k < 9; ++k)
      if (kpa[size_t(k)] > kpa[size_t(best)]) best = k;
    EXPECT_EQ(best, 3 + c);
  }
}

// No stimulus, no noise: every code is round(offset / lsb), here
// round(1.0 / (3.3/1024)) = round(310.30) = 310 and mid-scale 512 for 1.65 V.
TEST(WorldModel, NoStimulusGivesConstantBiasCode) {
  for (double offset : {1.65, 1.0}) {
    Scene s = planned_scene();
    s.skin.adc.offset_v = offset;
    WorldModel wm(s);
    std::vector<int> codes = wm.all_codes();
    ASSERT_EQ(codes.size(), size_t(0.05 * 35000));
    int expect = offset == 1.65 ? 512 : 310;
    for (int c : codes) ASSERT_EQ(c, expect);
    EXPECT_EQ(wm.clipped(), 0u);
  }
}

// Clipping: g = 1 on one taxel puts a 1.5 V row and a 1.5 V column carrier on
// a 1.65 V bias, so the sum reaches 1.65 +- 3 V, far outside 0..3.3 V. The
// clipped count must equal the number of samples whose unclipped code lies
// outside 0..1023, computed here from the physics (as in the test above).
TEST(WorldModel, ClippingIsCounted) {
  Scene s = planned_scene();
  s.skin.amp_gain = 1.5;
  s.skin.conductance.kind = Conductance::Kind::Linear;
  s.skin.conductance.p_max_kpa = 10;
  s.presses.push_back(taxel_press(0, 0, 20, 0.0, 0.0, 0.05, 0.0));
  WorldModel wm(s);
  std::vector<int> codes = wm.all_codes();
  const double lsb = 3.3 / 1024, bin = 35000.0 / 32;
  size_t expect = 0, at_rails = 0;
  for (size_t n = 0; n < codes.size(); ++n) {
    double v = 1.65 + 1.5 * std::sin(2 * M_PI * 2 * bin * n / 35000 + wm.start_phase(0)) +
               1.5 * std::sin(2 * M_PI * 7 * bin * n / 35000 + wm.start_phase(3));
    long c = std::lround(v / lsb);
    expect += c < 0 || c > 1023;
    at_rails += codes[n] == 0 || codes[n] == 1023;
  }
  EXPECT_GT(expect, codes.size() / 10);  // the scene really does clip
  EXPECT_EQ(wm.clipped(), expect);
  EXPECT_GE(at_rails, wm.clipped());  // every clipped sample sits on a rail
}

// Noise: with no stimulus the code's spread is the noise plus rounding,
// sigma^2 = noise^2 + lsb^2/12 (rounding of a continuous-valued input). Over
// 35000 samples the sample variance has relative standard error sqrt(2/N) =
// 0.8%; a 5% bound is > 6 standard errors.
TEST(WorldModel, NoiseHasTheConfiguredRms) {
  Scene s = planned_scene();
  s.duration_s = 1.0;
  s.skin.adc.noise_rms_v = 0.01;
  std::vector<int> codes = WorldModel(s).all_codes();
  const double lsb = 3.3 / 1024;
  double sum = 0, sum2 = 0;
  for (int c : codes) sum += c, sum2 += double(c) * c;
  double mean = sum / codes.size(), var = sum2 / codes.size() - mean * mean;
  double expect = (0.01 * 0.01) / (lsb * lsb) + 1.0 / 12;
  EXPECT_NEAR(var / expect, 1.0, 0.05);
  EXPECT_NEAR(mean, 512.0, 0.05);  // 5 sigma of the mean: 3.1 LSB / sqrt(35000)
}

// The shipped scenes are designed not to clip: the carriers' peak excursion
// is at most osc * gain * (sum of all row and column g-sums) (all sines in
// phase), computed here from the ground truth at every sample; with 6 sigma
// of noise added (per-sample exceedance ~2e-9, < 1e-4 over a whole scene)
// it must stay inside the bias headroom, and then the model must report
// zero clipped samples. Every 7th sample is enough for the worst case: the
// shortest ramp in these scenes (2 ms at 280 kHz, 5 ms elsewhere) spans
// more than 80 steps, so the sampled maximum is within ~1% of the true one,
// far inside the margin (the scenes peak below 80% of the headroom).
TEST(WorldModel, ShippedScenesHaveHeadroomAndDoNotClip) {
  for (const char* f : {"neuroskin2", "planned3x3", "staggered10x10", "skin32x32"}) {
    SCOPED_TRACE(f);
    Scene s = load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/" + f + ".yaml");
    WorldModel wm(s);
    const SkinConfig& k = s.skin;
    double worst = 0;
    std::vector<double> kpa;
    for (size_t n = 0; n < wm.total_samples(); n += 7) {
      wm.pressure_at(n, kpa);
      double sum = 0;
      for (double p : kpa) sum += 2 * k.conductance.g(p);  // once in its row, once in its column
      worst = std::max(worst, sum);
    }
    double peak = k.osc_amplitude_v * k.amp_gain * worst + 6 * k.adc.noise_rms_v;
    double room = std::min(k.adc.offset_v, k.adc.full_scale_v - k.adc.offset_v) - k.adc.lsb_v();
    EXPECT_LT(peak, room);
    EXPECT_GT(worst, 0.5);  // the scene does press something firmly
    std::vector<int> codes = wm.all_codes();
    EXPECT_EQ(codes.size(), size_t(std::llround(s.duration_s * k.adc.rate_hz)));
    EXPECT_EQ(wm.clipped(), 0u);
  }
}

TEST(WorldModel, StreamsOneSampleAtATime) {
  Scene s = planned_scene();
  s.presses.push_back(taxel_press(1, 1, 50, 0.001, 0.001, 0.01, 0.001));
  WorldModel a(s), b(s);
  EXPECT_EQ(a.total_samples(), size_t(0.05 * 35000));
  std::vector<int> all = b.all_codes();
  int c;
  for (size_t n = 0; n < all.size(); ++n) {
    EXPECT_EQ(a.position(), n);
    ASSERT_TRUE(a.next(c));
    ASSERT_EQ(c, all[n]);
  }
  EXPECT_FALSE(a.next(c));
  EXPECT_TRUE(b.all_codes().empty());
}

// WAV round trip through libsndfile: mono, the ADC rate, and each 16-bit
// sample equal to (code - 512) * 64 for 10 bits, so code = s / 64 + 512.
TEST(WavIo, RoundTripThroughLibsndfile) {
  Scene s = planned_scene();
  s.presses.push_back(taxel_press(2, 0, 80, 0.002, 0.002, 0.02, 0.002));
  s.skin.amp_gain = 1.2;  // some clipping: rails must survive too
  std::vector<int> codes = WorldModel(s).all_codes();
  std::string path = ::testing::TempDir() + "world_model_test.wav";
  write_wav(path, codes, s.skin.adc);
  SF_INFO info{};
  SNDFILE* f = sf_open(path.c_str(), SFM_READ, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  EXPECT_EQ(info.samplerate, 35000);
  EXPECT_EQ(info.channels, 1);
  EXPECT_EQ(info.format, SF_FORMAT_WAV | SF_FORMAT_PCM_16);
  ASSERT_EQ(info.frames, sf_count_t(codes.size()));
  std::vector<short> back(codes.size());
  ASSERT_EQ(sf_read_short(f, back.data(), info.frames), info.frames);
  sf_close(f);
  std::remove(path.c_str());
  for (size_t n = 0; n < codes.size(); ++n) ASSERT_EQ(back[n] / 64 + 512, codes[n]) << n;
  EXPECT_EQ(wav_sample_from_code(1023, 10), 32704);
  EXPECT_EQ(wav_sample_from_code(0, 10), -32768);
  AdcConfig wide;
  wide.bits = 18;
  EXPECT_THROW(write_wav(path, codes, wide), std::runtime_error);
}

}  // namespace
}  // namespace eskin::sim
