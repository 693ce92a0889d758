// Scene loader: the shipped scenes load and validate; every malformed scene
// is rejected before anything runs, with FILE:LINE:COL, the field path and
// what was expected. Bounds here are exact: a message either names the right
// line and field or it does not.
#include "sim/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace eskin::sim {
namespace {

const std::string kDir = std::string(ESKIN_SOURCE_DIR) + "/scenes/";

// A valid scene, one field per line, so a case can replace line L and expect
// the error on line L.
const std::vector<std::string> kBase = {
    "name: t",                                                                   // 1
    "seed: 1",                                                                   // 2
    "duration_s: 0.1",                                                           // 3
    "skin:",                                                                     // 4
    "  rows: 3",                                                                 // 5
    "  cols: 3",                                                                 // 6
    "  carriers:",                                                               // 7
    "    rows: [1900, 3300, 5000]",                                              // 8
    "    cols: [7140, 8300, 10000]",                                             // 9
    "  conductance: {kind: saturating, p_half_kpa: 50}",                         // 10
    "  adc: {rate_hz: 35000, bits: 10, full_scale_v: 3.3, offset_v: 1.65}",      // 11
    "decoder:",                                                                  // 12
    "  window: 32",                                                              // 13
    "  variant: exact",                                                          // 14
    "neuron: {preset: RA, input: level}",                                        // 15
    "stimuli:",                                                                  // 16
    "  - press: {taxel: [1, 1], pressure_kpa: 50, t_start_s: 0.01}",             // 17
    "  - slide: {from: [0, 0], to: [2, 2], pressure_kpa: 30, t_start_s: 0.05, duration_s: 0.04}",  // 18
    "outputs: [amplitudes, taxels]",                                             // 19
};

std::string with_line(int line, const std::string& text) {
  std::string out;
  for (size_t i = 0; i < kBase.size(); ++i)
    out += (int(i) + 1 == line ? text : kBase[i]) + "\n";
  return out;
}

TEST(Scene, BaseSceneParses) {
  Scene s = parse_scene(with_line(0, ""), "base.yaml");
  EXPECT_EQ(s.skin.rows, 3);
  ASSERT_EQ(s.presses.size(), 1u);
  ASSERT_EQ(s.slides.size(), 1u);
  EXPECT_EQ(s.presses[0].row, 1);
  EXPECT_DOUBLE_EQ(s.slides[0].x1, 2.0);
  EXPECT_FALSE(s.outputs.spikes);
  // offset_v was given; dt_ms defaults to one ADC sample (1000/35000 ms).
  EXPECT_NEAR(s.neuron.dt_ms, 1.0 / 35.0, 1e-15);
}

struct BadCase {
  const char* what;
  int line;                   // line of kBase to replace with `text`
  std::string text;
  int expect_line;            // line the error must name
  std::string field;          // field path the error must name
  std::vector<std::string> says;  // fragments the message must contain
};

class BadScene : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadScene, RejectedWithFileLineAndField) {
  const BadCase& c = GetParam();
  std::string text = with_line(c.line, c.text);
  try {
    parse_scene(text, "bad.yaml");
    FAIL() << c.what << ": accepted";
  } catch (const SceneError& e) {
    std::string msg = e.what();
    std::string head = "bad.yaml:" + std::to_string(c.expect_line) + ":";
    EXPECT_EQ(msg.rfind(head, 0), 0u) << c.what << ": " << msg;
    EXPECT_EQ(e.line(), c.expect_line) << msg;
    EXPECT_EQ(e.field(), c.field) << msg;
    EXPECT_NE(msg.find(": " + c.field + ": "), std::string::npos) << msg;
    // Our own checks say "expected ..., got ..."; eskin::validate's
    // messages (ConfigError, converted) word some errors differently.
    if (std::string(c.what).find("eskin::validate") == std::string::npos) {
      EXPECT_NE(msg.find("expected"), std::string::npos) << msg;
    }
    for (const auto& s : c.says) EXPECT_NE(msg.find(s), std::string::npos) << s << " in " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadScene,
    ::testing::Values(
        BadCase{"top-level typo", 3, "duraton_s: 0.1", 3, "duraton_s",
                {"unknown key 'duraton_s'", "did you mean 'duration_s'"}},
        BadCase{"missing required", 3, "# no duration", 1, "duration_s", {"required"}},
        BadCase{"nested typo", 11, "  adc: {rate_hx: 35000}", 11, "skin.adc.rate_hx",
                {"did you mean 'rate_hz'", "got unknown key"}},
        BadCase{"wrong type", 5, "  rows: three", 5, "skin.rows",
                {"an integer", "got 'three'"}},
        BadCase{"list for a number", 3, "duration_s: [1, 2]", 3, "duration_s",
                {"a number", "got a list"}},
        BadCase{"out of range", 11, "  adc: {rate_hz: 35000, bits: 30}", 11, "skin.adc.bits",
                {"2..24", "got 30"}},
        BadCase{"offset above full scale", 11, "  adc: {full_scale_v: 3.3, offset_v: 4}", 11,
                "skin.adc.offset_v", {"full_scale_v = 3.3", "got 4"}},
        BadCase{"taxel row outside", 17, "  - press: {taxel: [3, 0], pressure_kpa: 50}", 17,
                "stimuli[0].press.taxel[0]", {"0..2", "got 3"}},
        BadCase{"position outside", 17, "  - press: {at: [5, 0], pressure_kpa: 50}", 17,
                "stimuli[0].press.at[0]", {"within the matrix", "got 5"}},
        BadCase{"past duration", 17,
                "  - press: {taxel: [0, 0], pressure_kpa: 50, t_start_s: 0.09, hold_s: 0.02}", 17,
                "stimuli[0].press", {"duration_s = 0.1", "end at 0.12"}},
        BadCase{"slide past duration", 18,
                "  - slide: {from: [0, 0], to: [1, 1], pressure_kpa: 5, t_start_s: 0.08, duration_s: 0.05}",
                18, "stimuli[1].slide", {"end at 0.13"}},
        BadCase{"negative time", 17, "  - press: {taxel: [0, 0], pressure_kpa: 50, t_start_s: -0.01}",
                17, "stimuli[0].press.t_start_s", {">= 0", "got -0.01"}},
        BadCase{"zero pressure", 17, "  - press: {taxel: [0, 0], pressure_kpa: 0}", 17,
                "stimuli[0].press.pressure_kpa", {"got 0"}},
        BadCase{"press without site", 17, "  - press: {pressure_kpa: 50}", 17,
                "stimuli[0].press.taxel", {"taxel: [row, col] or at: [x, y]"}},
        BadCase{"unknown stimulus", 17, "  - poke: {taxel: [0, 0]}", 17, "stimuli[0].poke",
                {"press, slide"}},
        BadCase{"slide ramp too long", 18,
                "  - slide: {from: [0, 0], to: [1, 1], pressure_kpa: 5, duration_s: 0.02, ramp_s: 0.015}",
                18, "stimuli[1].slide.ramp_s", {"duration_s / 2"}},
        BadCase{"carrier above Nyquist (eskin::validate)", 8, "    rows: [1900, 3300, 20000]", 8,
                "skin.carriers.rows[2]", {"Nyquist", "got 20000"}},
        BadCase{"carrier count (eskin::validate)", 8, "    rows: [1900, 3300]", 8,
                "skin.carriers.rows", {"3 frequencies, got 2"}},
        BadCase{"window too short (eskin::validate decoder)", 8, "    rows: [1900, 2000, 5000]", 13,
                "decoder.window", {"closer than fs/N"}},
        BadCase{"bad variant", 14, "  variant: goertzel", 14, "decoder.variant",
                {"direct, recursive, damped, exact, ls", "got 'goertzel'"}},
        BadCase{"kind/parameter mismatch", 10, "  conductance: {kind: linear, p_half_kpa: 50}", 10,
                "skin.conductance.p_half_kpa", {"only p_max_kpa with kind linear"}},
        BadCase{"bad neuron preset", 15, "neuron: {preset: XX}", 15, "neuron.preset",
                {"RS, IB", "got 'XX'"}},
        BadCase{"bad output", 19, "outputs: [amplitudes, spike]", 19, "outputs[1]",
                {"spikes", "got 'spike'"}},
        BadCase{"negative seed", 2, "seed: -1", 2, "seed", {"integer >= 0"}},
        BadCase{"duplicate key", 2, "duration_s: 0.2", 3, "duration_s", {"once"}},
        BadCase{"yaml syntax", 10, "  conductance: {kind: saturating", 11, "(syntax)",
                {"valid YAML"}}));

// Cases that need more than one line changed.
TEST(Scene, FreqErrorCountNamesItsLine) {
  std::string text = with_line(6, "  cols: 3\n  freq_error: [0.01, 0.02]");
  try {
    parse_scene(text, "fe.yaml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 7) << e.what();
    EXPECT_EQ(e.field(), "skin.freq_error") << e.what();
    EXPECT_NE(std::string(e.what()).find("6 values"), std::string::npos) << e.what();
  }
}

// 6 carriers cannot be planned in an 8-sample window (bins 1..3 only): the
// error from eskin::plan_carriers points at the `carriers: auto` line.
TEST(Scene, AutoPlanThatCannotFitNamesCarriersLine) {
  std::string text;
  for (size_t i = 0; i < kBase.size(); ++i) {
    std::string l = kBase[i];
    if (i + 1 == 7) l = "  carriers: auto";
    if (i + 1 == 8 || i + 1 == 9) l = "  # no list";
    if (i + 1 == 13) l = "  window: 8";
    text += l + "\n";
  }
  try {
    parse_scene(text, "auto.yaml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 7) << e.what();
    EXPECT_EQ(e.field(), "skin.carriers") << e.what();
    EXPECT_NE(std::string(e.what()).find("decoder.window"), std::string::npos) << e.what();
  }
}

TEST(Scene, MissingFileNamesThePath) {
  try {
    load_scene("/nonexistent/x.yaml");
    FAIL() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/x.yaml: ", 0), 0u) << e.what();
  }
}

TEST(Scene, ColumnPointsAtTheValue) {
  // "  adc: {rate_hz: 35000, bits: 30}": `30` starts at column 31 (1-based).
  try {
    parse_scene(with_line(11, "  adc: {rate_hz: 35000, bits: 30}"), "c.yaml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.col(), 31) << e.what();
  }
}

// The default scene: thesis hardware, every taxel pressed once, then two
// staggered and two simultaneous touches on different rows and columns.
TEST(Scene, DefaultSceneLoadsAndValidates) {
  Scene s = load_scene(kDir + "neuroskin2.yaml");
  EXPECT_EQ(s.name, "neuroskin2");
  EXPECT_EQ(s.skin.rows, 3);
  EXPECT_EQ(s.skin.cols, 3);
  EXPECT_EQ(s.skin.row_freq_hz, (std::vector<double>{1900, 3300, 5000}));
  EXPECT_EQ(s.skin.col_freq_hz, (std::vector<double>{7140, 8300, 10000}));
  EXPECT_EQ(s.skin.adc.rate_hz, 35000);
  EXPECT_EQ(s.skin.adc.bits, 10);
  EXPECT_EQ(s.decoder.window, 32);
  EXPECT_TRUE(s.outputs.amplitudes && s.outputs.taxels && s.outputs.spikes);
  EXPECT_NO_THROW(validate(s.skin));
  EXPECT_NO_THROW(validate(s.decoder, s.skin));
  // Every one of the 9 taxels is pressed alone at some point.
  std::vector<int> alone(9, 0);
  for (const Press& p : s.presses) {
    bool overlap = false;
    for (const Press& q : s.presses)
      if (&p != &q && q.t_start_s < p.end_s() && p.t_start_s < q.end_s()) overlap = true;
    if (!overlap && !p.at_position) alone[size_t(p.row * 3 + p.col)] = 1;
  }
  for (int k = 0; k < 9; ++k) EXPECT_EQ(alone[size_t(k)], 1) << "taxel " << k;
  EXPECT_LE(s.duration_s, 0.7);
}

TEST(Scene, AllShippedScenesLoad) {
  for (const char* f : {"neuroskin2", "staggered10x10", "skin32x32", "skin64x64", "planned3x3"}) {
    SCOPED_TRACE(f);
    Scene s;
    ASSERT_NO_THROW(s = load_scene(kDir + f + ".yaml"));
    EXPECT_NO_THROW(validate(s.decoder, s.skin));
  }
}

// `carriers: auto` and the planned scene put every carrier on a bin centre
// k * fs / N (integer k, to 1e-9 of a bin: the plan is exact in binary
// fractions here) and all of them on distinct bins.
TEST(Scene, PlannedCarriersSitOnDistinctBinCentres) {
  for (const char* f : {"staggered10x10", "skin32x32", "skin64x64", "planned3x3"}) {
    SCOPED_TRACE(f);
    Scene s = load_scene(kDir + f + ".yaml");
    double bin = s.skin.adc.rate_hz / s.decoder.window;
    std::vector<long> ks;
    for (double hz : s.skin.carrier_freqs_hz()) {
      double k = hz / bin;
      EXPECT_NEAR(k, std::round(k), 1e-9) << hz;
      ks.push_back(std::lround(k));
    }
    EXPECT_EQ(int(ks.size()), s.skin.carriers());
    for (size_t i = 0; i < ks.size(); ++i)
      for (size_t j = 0; j < i; ++j) EXPECT_NE(ks[i], ks[j]);
  }
}

TEST(Scene, LoadSkinReadsSkinOfASceneFile) {
  Scene s = load_scene(kDir + "staggered10x10.yaml");
  SkinConfig k = load_skin(kDir + "staggered10x10.yaml");
  EXPECT_EQ(k.carrier_freqs_hz(), s.skin.carrier_freqs_hz());  // auto plan used the window
  EXPECT_EQ(k.rows, 10);
  EXPECT_EQ(k.adc.rate_hz, 70000);
}

// A skin-only file (no duration, no stimuli) and other top-level keys are fine
// for load_skin; the skin itself is checked as strictly as in a scene.
TEST(Scene, ParseSkinOfASkinOnlyFile) {
  SkinConfig k = parse_skin(
      "skin:\n  rows: 2\n  cols: 4\n  carriers: auto\n  adc: {rate_hz: 70000}\n"
      "decoder: {window: 64}\nnotes: free text\n",
      "skin.yaml");
  EXPECT_EQ(k.rows, 2);
  EXPECT_EQ(k.carriers(), 6);
  const double bin = 70000.0 / 64;
  EXPECT_DOUBLE_EQ(k.row_freq_hz[0], bin);  // plan_carriers starts at bin 1
  EXPECT_DOUBLE_EQ(k.adc.offset_v, 1.65);   // default: half of full scale
  try {
    parse_skin("skin:\n  rows: 2\n  cols: 2\n  carriers: auto\n  amp_gian: 1\n", "skin.yaml");
    FAIL() << "accepted a typo";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 5) << e.what();
    EXPECT_EQ(e.field(), "skin.amp_gian") << e.what();
  }
}

TEST(Scene, EmptyStimuliIsSilence) {
  Scene s = parse_scene("duration_s: 0.01\nskin: {rows: 1, cols: 1, carriers: auto}\nstimuli:\n",
                        "quiet.yaml");
  EXPECT_TRUE(s.presses.empty() && s.slides.empty());
}

TEST(Scene, LoadSkinRejectsFileWithoutSkin) {
  EXPECT_THROW(parse_skin("name: x\n", "noskin.yaml"), SceneError);
}

// Disk footprint: a disk that covers the whole cell gives exactly the full
// pressure (each strip is clipped to the cell); a disk of radius 0.5 centred
// on a taxel lies inside its cell, area pi/4 — the 64-strip midpoint rule is
// within 0.2% of that (chord error O(h^1.5) near the disk's edge); a disk
// centred on the border of two cells splits evenly between them.
TEST(Scene, DiskCoverFraction) {
  EXPECT_DOUBLE_EQ(disk_cover_fraction(1, 1, 1.0, 1, 1), 1.0);
  EXPECT_NEAR(disk_cover_fraction(1, 1, 0.5, 1, 1), M_PI / 4, 0.002 * M_PI / 4);
  EXPECT_EQ(disk_cover_fraction(1, 1, 0.5, 1, 2), 0.0);
  EXPECT_NEAR(disk_cover_fraction(1.5, 1, 0.4, 1, 1), disk_cover_fraction(1.5, 1, 0.4, 1, 2), 1e-12);
}

}  // namespace
}  // namespace eskin::sim
