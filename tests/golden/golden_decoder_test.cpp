// The golden chain end to end on world-model scenes: pressures against the
// scene's ground truth, ghosts with and without correction, extremes.
#include "host/golden/golden_decoder.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fmt/format.h>

#include "host/golden/decode_score.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace eskin {
namespace {

// A 3x3 skin; `carriers` is either "auto" (bin centres) or explicit lists.
std::string skin_yaml(const std::string& carriers, double noise = 0.0, double gain = 0.5) {
  return fmt::format(R"(
skin:
  rows: 3
  cols: 3
  carriers: {}
  osc_amplitude_v: 1.0
  amp_gain: {}
  conductance: {{kind: saturating, p_half_kpa: 50}}
  adc: {{rate_hz: 35000, bits: 10, full_scale_v: 3.3, offset_v: 1.65, noise_rms_v: {}}}
)",
                     carriers, gain, noise);
}

const char* kThesisCarriers = "{rows: [1900, 3300, 5000], cols: [7140, 8300, 10000]}";

// Each taxel pressed in turn at 60 kPa, 40 ms apart.
std::string presses_in_turn() {
  std::string s = "stimuli:\n";
  for (int t = 0; t < 9; ++t)
    s += fmt::format(
        "  - press: {{taxel: [{}, {}], pressure_kpa: 60, t_start_s: {}, ramp_s: 0.005, "
        "hold_s: 0.02, release_s: 0.005}}\n",
        t / 3, t % 3, 0.01 + 0.04 * t);
  return s;
}

struct SceneRun {
  golden::DecodeScore score;
  golden::Frame last;
  golden::Frame at;  // the frame whose newest sample is `capture`
  size_t clipped = 0;
  std::vector<std::vector<double>> spikes;
};

SceneRun run(const sim::Scene& scene, golden::GoldenOptions opt = {},
             size_t capture = size_t(-1)) {
  golden::GoldenDecoder dec(scene.skin, scene.decoder, scene.neuron, opt);
  sim::WorldModel world(scene);
  golden::DecodeScorer scorer(scene.skin, scene.decoder,
                              [&](size_t n, std::vector<double>& p) { world.pressure_at(n, p); });
  SceneRun r;
  int code;
  while (world.next(code))
    if (dec.push(code)) {
      scorer.add(dec.frame());
      r.last = dec.frame();
      if (dec.frame().sample == capture) r.at = dec.frame();
    }
  r.score = scorer.score();
  r.clipped = world.clipped();
  r.spikes = dec.spike_times_ms();
  return r;
}

// Largest pressure error that a line-amplitude error of `lsb_err` ADC LSB can
// cause for a single touch at p: the decoded conductance fraction is
// sqrt(r c) / F with r, c each within lsb_err of F g, so g moves by at most
// lsb_err / F, and the pressure by the curve's inverse over that interval.
double pressure_bound(const SkinConfig& skin, double p, double lsb_err) {
  const double g = skin.conductance.g(p), dg = lsb_err / skin.full_carrier_lsb();
  return std::max(std::fabs(skin.conductance.inverse(g + dg) - p),
                  std::fabs(skin.conductance.inverse(std::max(0.0, g - dg)) - p));
}

TEST(GoldenDecoder, SingleTouchesOnBinCentresMatchTruthWithinQuantisation) {
  // Bound: carriers on bin centres do not leak (rectangular window), so the
  // only error is ADC rounding, |e| <= 0.5 LSB per sample; the amplitude
  // estimate (2/N) sum e w is then off by at most 1 LSB. pressure_bound()
  // turns that into kPa at the pressed 60 kPa.
  sim::Scene s = sim::parse_scene(skin_yaml("auto") + "duration_s: 0.4\n" + presses_in_turn(),
                                  "single.yaml");
  s.decoder.variant = DftVariant::Exact;
  SceneRun r = run(s);
  const double bound = pressure_bound(s.skin, 60.0, 1.0);
  EXPECT_GT(r.score.steady_frames, 5000u);
  for (size_t t = 0; t < 9; ++t) {
    EXPECT_GT(r.score.taxel[t].steady_frames, 0u);
    EXPECT_LE(r.score.taxel[t].max_error_kpa, bound) << "taxel " << t;
  }
  EXPECT_EQ(r.score.ghost_taxel_frames, 0u);
  EXPECT_EQ(r.score.missed_taxel_frames, 0u);
  RecordProperty("max_error_kpa", fmt::format("{:.3f}", r.score.worst_max_error_kpa()));
  RecordProperty("bound_kpa", fmt::format("{:.3f}", bound));
}

// Worst-case amplitude error (LSB) of the joint LS fit for +-0.5 LSB rounding:
// each fitted cos/sin coefficient is a fixed linear combination (a row of the
// pseudo-inverse P) of the window, so it moves by at most 0.5 * ||P_row||_1;
// the magnitude moves by at most the sum of its two coefficients' moves.
// Computed here independently of the decoder's own LS machinery.
double ls_amplitude_error_bound(const std::vector<double>& f, double fs, int n) {
  const int k = int(f.size());
  Eigen::MatrixXd a(n, 2 * k + 1);
  for (int m = 0; m < n; ++m) {
    for (int c = 0; c < k; ++c) {
      a(m, 2 * c) = std::cos(2 * M_PI * f[size_t(c)] * m / fs);
      a(m, 2 * c + 1) = std::sin(2 * M_PI * f[size_t(c)] * m / fs);
    }
    a(m, 2 * k) = 1.0;
  }
  const Eigen::MatrixXd p = (a.transpose() * a).inverse() * a.transpose();
  double worst = 0;
  for (int c = 0; c < k; ++c)
    worst = std::max(worst, 0.5 * (p.row(2 * c).lpNorm<1>() + p.row(2 * c + 1).lpNorm<1>()));
  return worst;
}

TEST(GoldenDecoder, ThesisCarriersNeedDemixing) {
  // Off-bin thesis carriers: the plain DFT leaks up to ~20% between
  // neighbours, so a single touch lights the neighbouring line too; joint LS
  // demixing brings the error back to the quantisation bound (computed above).
  sim::Scene s = sim::parse_scene(
      skin_yaml(kThesisCarriers) + "duration_s: 0.4\n" + presses_in_turn(), "thesis.yaml");
  s.decoder.variant = DftVariant::Exact;
  const SceneRun plain = run(s);
  s.decoder.variant = DftVariant::LsDemix;
  const SceneRun ls = run(s);
  const double lsb = ls_amplitude_error_bound(s.skin.carrier_freqs_hz(), 35000, 32);
  const double bound = pressure_bound(s.skin, 60.0, lsb);
  EXPECT_LE(ls.score.worst_max_error_kpa(), bound);
  EXPECT_GT(plain.score.worst_max_error_kpa(), 3 * bound);  // cross-talk dominates
  RecordProperty("plain_max_error_kpa", fmt::format("{:.2f}", plain.score.worst_max_error_kpa()));
  RecordProperty("ls_max_error_kpa", fmt::format("{:.3f}", ls.score.worst_max_error_kpa()));
  RecordProperty("ls_bound_kpa", fmt::format("{:.3f}", bound));
}

// Taxels lit (conductance fraction above the threshold) in a pressure matrix.
int lit(const Eigen::MatrixXd& p, const SkinConfig& skin, double thr) {
  int n = 0;
  for (int i = 0; i < p.rows(); ++i)
    for (int j = 0; j < p.cols(); ++j) n += skin.conductance.g(p(i, j)) > thr;
  return n;
}

TEST(GoldenDecoder, ThreeStaggeredTouchesOn10x10LightNineWithoutCorrectionThreeWith) {
  // Thesis Fig. 5.4/5.5: three touches on distinct rows and columns, 10 ms
  // apart, all held at the end. Row/column products light the 3x3 = 9
  // intersections; the active-site filter keeps exactly the 3 true ones.
  sim::Scene s = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/staggered10x10.yaml");
  const size_t at = size_t(0.2 * s.skin.adc.rate_hz);  // all three touches held
  const SceneRun r = run(s, {}, at);
  ASSERT_EQ(r.at.sample, at);
  std::vector<double> truth;
  sim::WorldModel(s).pressure_at(at, truth);
  int true_lit = 0;
  for (double p : truth) true_lit += s.skin.conductance.g(p) > s.decoder.ghost_threshold;
  ASSERT_EQ(true_lit, 3) << "scene must end with three held touches";
  EXPECT_EQ(lit(r.at.pressure_raw, s.skin, s.decoder.ghost_threshold), 9);
  EXPECT_EQ(lit(r.at.pressure, s.skin, s.decoder.ghost_threshold), 3);
  for (int i = 0; i < s.skin.rows; ++i)
    for (int j = 0; j < s.skin.cols; ++j)
      EXPECT_EQ(s.skin.conductance.g(r.at.pressure(i, j)) > s.decoder.ghost_threshold,
                s.skin.conductance.g(truth[size_t(i * s.skin.cols + j)]) > s.decoder.ghost_threshold)
          << i << "," << j;
}

TEST(GoldenDecoder, DefaultSceneGhostRateAndSpikes) {
  // The default scene ends with two simultaneous touches, the case the thesis
  // algorithm cannot resolve; the improved filter must not do worse. Every
  // taxel is pressed in turn, so every receptor neuron fires.
  sim::Scene s = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  golden::GoldenOptions opt;
  opt.spikes = true;
  const SceneRun r = run(s, opt);
  EXPECT_EQ(r.clipped, 0u);
  EXPECT_LE(r.score.ghost_taxel_frames, r.score.ghost_taxel_frames_raw);
  for (size_t t = 0; t < r.spikes.size(); ++t) EXPECT_GT(r.spikes[t].size(), 0u) << "taxel " << t;
  RecordProperty("ghost_frames_raw", std::to_string(r.score.ghost_frames_raw));
  RecordProperty("ghost_frames_corrected", std::to_string(r.score.ghost_frames));
  RecordProperty("steady_frames", std::to_string(r.score.steady_frames));
}

TEST(GoldenDecoder, ZeroInputLightsNothingAndFiresNothing) {
  // No stimulus: every code is the bias code, every amplitude exactly 0.
  sim::Scene s = sim::parse_scene(skin_yaml(kThesisCarriers) + "duration_s: 0.05\nstimuli: []\n",
                                  "zero.yaml");
  golden::GoldenOptions opt;
  opt.spikes = true;
  const SceneRun r = run(s, opt);
  EXPECT_EQ(r.last.amp_lsb.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(lit(r.last.pressure, s.skin, s.decoder.ghost_threshold), 0);
  for (const auto& t : r.spikes) EXPECT_TRUE(t.empty());
}

TEST(GoldenDecoder, ClippingIsCountedAndDecodingStaysFinite) {
  // Gain 2: one fully pressed line alone swings +-2 V around 1.65 V, beyond
  // the 0..3.3 V input, so the ADC clips; the decoder must stay finite.
  sim::Scene s = sim::parse_scene(
      skin_yaml("auto", 0.0, 2.0) + "duration_s: 0.4\n" + presses_in_turn(), "clip.yaml");
  const SceneRun r = run(s);
  EXPECT_GT(r.clipped, 0u);
  EXPECT_TRUE(r.last.pressure.allFinite());
  EXPECT_TRUE(r.last.amp_lsb.allFinite());
}

TEST(GoldenDecoder, AllTaxelsPressedIsUniformAndShowsTheProductBias) {
  // All nine taxels pressed equally together: every line carries 3 g, so the
  // thesis product reads g' = sqrt(3g * 3g) = 3g on every taxel, i.e. the
  // pressure inverse(3 g(10 kPa)) = inverse(0.5) = 50 kPa: uniform but biased
  // (the row/column sum model cannot tell one full row from one taxel).
  // Bound: bin-centred carriers, so each line amplitude is within 1 LSB.
  std::string st = "stimuli:\n";
  for (int t = 0; t < 9; ++t)
    st += fmt::format("  - press: {{taxel: [{}, {}], pressure_kpa: 10, t_start_s: 0.01, "
                      "ramp_s: 0.005, hold_s: 0.05, release_s: 0.005}}\n",
                      t / 3, t % 3);
  sim::Scene s = sim::parse_scene(skin_yaml("auto") + "duration_s: 0.07\n" + st, "all.yaml");
  const size_t at = size_t(0.05 * s.skin.adc.rate_hz);  // inside the hold
  const SceneRun r = run(s, {}, at);
  ASSERT_EQ(r.at.sample, at);
  const double expect = s.skin.conductance.inverse(3 * s.skin.conductance.g(10.0));
  ASSERT_NEAR(expect, 50.0, 1e-9);
  const double bound = pressure_bound(s.skin, expect, 1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(r.at.pressure_raw(i, j), expect, bound);
  EXPECT_TRUE(r.at.pressure.allFinite());
}

TEST(GoldenDecoder, CarrierNearNyquistIsRejectedBeforeRunning) {
  // 17 kHz at 35 kHz is within one bin (1094 Hz) of Nyquist (17.5 kHz).
  const std::string y = skin_yaml("{rows: [1900, 3300, 5000], cols: [7140, 8300, 17000]}") +
                        "duration_s: 0.01\nstimuli: []\n";
  try {
    sim::parse_scene(y, "nyquist.yaml");
    FAIL() << "scene with a carrier near Nyquist was accepted";
  } catch (const sim::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("nyquist.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Nyquist"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace eskin
