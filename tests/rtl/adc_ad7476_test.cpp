// rtl/adc_ad7476.v against the AD7476A pin model sim/ad7476_model.h.
//
// Bounds and why:
//  * Exact sample sequence: every token equals the code the model served for
//    that conversion (m_t = conversion index), for the scene's codes at
//    35 kSPS (12 MHz clock, 6 MHz SCLK) and for random full-range 12-bit
//    codes at 1 MSPS on two channels (40 MHz clock, 20 MHz SCLK). The model
//    returns random levels wherever the datasheet leaves SDATA undefined, so
//    a wrong sampling instant shows up as wrong codes.
//  * Zero timing violations in both legal configurations (the model checks
//    every datasheet limit it knows, listed in its header).
//  * The pads and the board: the model delays SCLK out and SDATA back by
//    its Ad7476Board (default: the middle of the range the module is built
//    for); at 1 MSPS the codes are exact at both ends of that range, and
//    wrong beyond it (the module samples half a clock late there: its
//    header's LAG).
//  * Exact cycles: CS falls every round(CLK_HZ/SAMPLE_HZ) clocks (343 at
//    12 MHz/35 kSPS, 40 at 40 MHz/1 MSPS); m_valid rises 31*H clocks after
//    CS falls: the 16th SCLK falling edge is driven 31 H clocks after CS
//    (t2 = H, then 15 periods of 2 H) and the code is registered on that
//    same clock edge, H = SCLK_DIV; at 40 MHz a clock later (the bit is
//    taken on the falling edge after).
//  * Back-pressure: a stalled consumer loses whole samples, never corrupts
//    one: delivered tokens match codes[m_t], data stable while valid &&
//    !ready, and every completed conversion is accounted for exactly:
//    completed = delivered + overruns + (1 if a token is still pending).
//  * Negative controls: 24 MHz SCLK is reported as a tSCLK violation; a
//    1.2 MSPS rate at 20 MHz SCLK as tQUIET and tACQ violations. And the
//    model alone: a reader sampling at the SCLK rising edge at 20 MHz (25 ns
//    after the falling edge, before the 40 ns access time) reads wrong
//    codes; one sampling just before each falling edge reads them all.
//  * Every limit the model checks, broken alone in a hand-driven waveform,
//    is reported under its own name (t1, t2, t5, t6, tSCLK, tQUIET, tACQ,
//    fewer or more than 16 clocks, samples exhausted).
//  * The cycle level's C++ model (sim/cycle/adc_ad7476.h) gives the same
//    pins and output port as the RTL at every clock, with SDATA random at
//    every half clock, en, m_ready and clear at random, at the rising-edge
//    sample point (12 MHz) and the falling-edge one (40 MHz, two
//    channels) (bound: exact).
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vadc_ad7476.h"
#include "Vadc_ad7476_badrate.h"
#include "Vadc_ad7476_badsclk.h"
#include "Vadc_ad7476_fast.h"
#include "sim/ad7476_model.h"
#include "sim/cycle/adc_ad7476.h"
#include "sim/scene.h"
#include "sim/world_model.h"

using eskin::sim::Ad7476Board;
using eskin::sim::Ad7476Model;

namespace {

struct Token { uint32_t t; std::vector<uint16_t> codes; };

struct Result {
  std::vector<Token> tokens;
  std::vector<uint64_t> cs_fall_edges, valid_rise_edges;
  std::vector<std::string> violations;
  size_t violation_count = 0;
  uint32_t overruns = 0;
  size_t completed = 0;  // conversions with all 16 clocks (the model's count)
  bool pending = false;  // m_valid still high at the end
  bool stable_ok = true;
};

template <class M>
Result run(double clk_hz, int nch, const std::vector<std::vector<uint16_t>>& codes,
           size_t n_tokens, double p_ready, uint64_t seed, uint64_t max_edges,
           const Ad7476Board& board = {}) {
  auto m = std::make_unique<M>();
  std::vector<Ad7476Model> adc;
  for (int c = 0; c < nch; ++c)
    adc.emplace_back(codes[size_t(c)], eskin::sim::Ad7476Timing{}, seed + c, board);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution ready(p_ready);
  const double tc = 1e9 / clk_hz;
  Result r;
  m->clk = 0; m->rst = 1; m->en = 0; m->m_ready = 0; m->sdata = 0;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0; m->en = 1;
  bool prev_cs = true, prev_valid = false, stalled = false;
  uint64_t held_data = 0; uint32_t held_t = 0;
  for (uint64_t edge = 1; edge <= max_edges && r.tokens.size() < n_tokens; ++edge) {
    const double t = double(edge) * tc;
    const bool rdy = ready(rng);
    m->m_ready = rdy;
    uint32_t sd = 0;
    for (int c = 0; c < nch; ++c) sd |= uint32_t(adc[size_t(c)].sdata(t)) << c;
    m->sdata = sd;
    m->eval();
    if (m->m_valid) {
      if (stalled && (uint64_t(m->m_data) != held_data || m->m_t != held_t)) r.stable_ok = false;
      if (rdy) {
        Token k{m->m_t, {}};
        for (int c = 0; c < nch; ++c) k.codes.push_back(uint16_t((uint64_t(m->m_data) >> (12 * c)) & 0xFFF));
        r.tokens.push_back(k);
        stalled = false;
      } else {
        stalled = true; held_data = uint64_t(m->m_data); held_t = m->m_t;
      }
    }
    m->clk = 1; m->eval();
    for (int c = 0; c < nch; ++c) adc[size_t(c)].drive(t, m->cs_n, m->sclk);
    // SDATA half a period on, at the falling edge (a build that samples there).
    sd = 0;
    for (int c = 0; c < nch; ++c) sd |= uint32_t(adc[size_t(c)].sdata(t + tc / 2)) << c;
    m->sdata = sd;
    m->clk = 0; m->eval();
    if (prev_cs && !m->cs_n) r.cs_fall_edges.push_back(edge);
    if (!prev_valid && m->m_valid) r.valid_rise_edges.push_back(edge);
    prev_cs = m->cs_n; prev_valid = m->m_valid;
  }
  for (auto& a : adc) {
    r.violations.insert(r.violations.end(), a.violations().begin(), a.violations().end());
    r.violation_count += a.violation_count();
  }
  r.completed = adc[0].conversions();
  r.pending = m->m_valid;
  r.overruns = m->overruns;
  return r;
}

std::vector<uint16_t> random_codes(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<uint16_t> v{0, 4095, 0xAAA, 0x555, 0x800, 0x7FF};
  while (v.size() < n) v.push_back(uint16_t(rng() & 0xFFF));
  return v;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

void expect_exact(const Result& r, const std::vector<std::vector<uint16_t>>& codes, size_t n) {
  ASSERT_EQ(r.tokens.size(), n);
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(r.tokens[i].t, i);
    for (size_t c = 0; c < codes.size(); ++c)
      ASSERT_EQ(r.tokens[i].codes[c], codes[c][i]) << "sample " << i << " channel " << c;
  }
}

// valid_after: clocks from CS falling to m_valid (31 H; a clock more where
// the module samples late, LAG > 0 in its header: the 40 MHz builds).
void expect_cycles(const Result& r, uint64_t period, uint64_t valid_after) {
  ASSERT_GE(r.cs_fall_edges.size(), 3u);
  for (size_t i = 1; i < r.cs_fall_edges.size(); ++i)
    ASSERT_EQ(r.cs_fall_edges[i] - r.cs_fall_edges[i - 1], period);
  for (size_t i = 0; i < r.valid_rise_edges.size() && i < r.cs_fall_edges.size(); ++i)
    ASSERT_EQ(r.valid_rise_edges[i] - r.cs_fall_edges[i], valid_after);
}

}  // namespace

TEST(AdcAd7476, SceneCodesAt35kSps) {
  eskin::sim::WorldModel world(eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml"));
  std::vector<uint16_t> codes;
  int code;
  while (codes.size() < 1500 && world.next(code)) codes.push_back(uint16_t(code));
  ASSERT_EQ(codes.size(), 1500u);
  const size_t n = codes.size() - 1;
  const auto r = run<Vadc_ad7476>(12e6, 1, {codes}, n, 1.0, 1, 400 * 1500);
  EXPECT_EQ(r.violation_count, 0u) << joined(r.violations);
  expect_exact(r, {codes}, n);
  expect_cycles(r, (12000000 + 17500) / 35000, 31);
  EXPECT_EQ(r.overruns, 0u);
}

TEST(AdcAd7476, RandomCodesAt1MspsTwoChannels) {
  const size_t n = 4000;
  const std::vector<std::vector<uint16_t>> codes{random_codes(n + 1, 2), random_codes(n + 1, 3)};
  const auto r = run<Vadc_ad7476_fast>(40e6, 2, codes, n, 1.0, 2, 41 * (n + 2));
  EXPECT_EQ(r.violation_count, 0u) << joined(r.violations);
  expect_exact(r, codes, n);
  expect_cycles(r, 40, 32);  // the falling clock edge after the SCLK fall's takes each bit
}

// The pads and the board (sim/ad7476_model.h's Ad7476Board): at 1 MS/s
// (20 MHz SCLK: tSCLK - t4 = 10 ns) the round trip of SCLK out and SDATA
// back takes the setup budget of a capture at the edge that drives the
// next SCLK fall. The module samples on the falling clock edge after it
// at 40 MHz (LAG 1, its header), so the codes are exact at both ends of
// the round trip it is built for: the slowest board (15 ns: the edge
// itself would see each bit 5 ns before it is valid, and read the
// model's random levels) and the fastest (5 ns: the half clock, 12.5 ns,
// still inside t7 + 5 ns of hold). A board beyond the range (25 ns) reads
// wrong codes: the check that the delays reach the sample point.
TEST(AdcAd7476, RandomCodesAt1MspsAtBothEndsOfTheBoardsRoundTrip) {
  EXPECT_EQ(Ad7476Board::slowest().round_trip(), eskin::sim::kRoundTripMaxNs);
  EXPECT_EQ(Ad7476Board::fastest().round_trip(), eskin::sim::kRoundTripMinNs);
  const size_t n = 2000;
  const std::vector<std::vector<uint16_t>> codes{random_codes(n + 1, 12), random_codes(n + 1, 13)};
  for (const Ad7476Board& board : {Ad7476Board::slowest(), Ad7476Board::fastest()}) {
    SCOPED_TRACE("round trip " + std::to_string(board.round_trip()) + " ns");
    const auto r = run<Vadc_ad7476_fast>(40e6, 2, codes, n, 1.0, 12, 41 * (n + 2), board);
    EXPECT_EQ(r.violation_count, 0u) << joined(r.violations);
    expect_exact(r, codes, n);
  }
  const Ad7476Board beyond{15.0, 2.0, 6.0};
  ASSERT_EQ(beyond.round_trip(), 25.0);
  const auto r = run<Vadc_ad7476_fast>(40e6, 2, codes, n, 1.0, 12, 41 * (n + 2), beyond);
  ASSERT_EQ(r.tokens.size(), n);
  size_t wrong = 0;
  for (size_t i = 0; i < n; ++i) wrong += r.tokens[i].codes[0] != codes[0][r.tokens[i].t];
  EXPECT_GT(wrong, n / 2);
}

TEST(AdcAd7476, BackPressureDropsWholeSamplesAndCountsThem) {
  const size_t n = 600;
  const auto codes = random_codes(4 * n, 4);
  // Ready only 0.2% of cycles: a token waits ~500 cycles, beyond the 343-cycle period.
  const auto r = run<Vadc_ad7476>(12e6, 1, {codes}, n, 0.002, 5, 343 * 3 * n);
  ASSERT_EQ(r.tokens.size(), n);
  EXPECT_TRUE(r.stable_ok);
  uint32_t skipped = 0;
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(r.tokens[i].codes[0], codes[r.tokens[i].t]);
    if (i) {
      ASSERT_GT(r.tokens[i].t, r.tokens[i - 1].t);
      skipped += r.tokens[i].t - r.tokens[i - 1].t - 1;
    }
  }
  EXPECT_GT(skipped, 0u);
  EXPECT_GE(r.overruns, skipped);
  EXPECT_EQ(r.completed, r.tokens.size() + r.overruns + (r.pending ? 1 : 0));
  EXPECT_EQ(r.violation_count, 0u);
}

TEST(AdcAd7476, NegativeControlSclkTooFast) {
  const auto codes = random_codes(100, 6);
  const auto r = run<Vadc_ad7476_badsclk>(48e6, 1, {codes}, 50, 1.0, 6, 48 * 60);
  EXPECT_GT(r.violation_count, 0u);
  ASSERT_FALSE(r.violations.empty());
  EXPECT_NE(r.violations[0].find("tSCLK (fSCLK max 20 MHz)"), std::string::npos) << r.violations[0];
}

TEST(AdcAd7476, NegativeControlSampleRateTooHigh) {
  const auto codes = random_codes(100, 7);
  const auto r = run<Vadc_ad7476_badrate>(40e6, 1, {codes}, 50, 1.0, 7, 40 * 60);
  const std::string all = joined(r.violations);
  EXPECT_NE(all.find("tQUIET"), std::string::npos) << all;
  EXPECT_NE(all.find("tACQ"), std::string::npos) << all;
  EXPECT_EQ(all.find("tSCLK"), std::string::npos) << all;  // SCLK itself is legal
}

// The model alone, hand-driven at 20 MHz SCLK (25 ns half periods): reading
// each bit at the rising edge (25 ns after the falling edge, inside the
// t7..t4 = 10..40 ns undefined window) must give wrong codes; reading just
// before each falling edge (t7 hold) gives the right ones.
TEST(Ad7476Model, UndefinedWindowIsNotReadable) {
  const auto codes = random_codes(64, 8);
  for (bool at_rise : {false, true}) {
    Ad7476Model adc(codes, {}, 1, {0, 0, 0});  // at the ADC's pins: no board delays
    double t = 1000;
    size_t wrong = 0;
    for (size_t s = 0; s < codes.size(); ++s) {
      adc.drive(t, false, true);  // CS falls
      uint16_t word = 0;
      uint16_t leading = 0;
      for (int k = 1; k <= 16; ++k) {
        const double fall = t + 25 + 50.0 * (k - 1);
        int bit;
        if (at_rise) {
          adc.drive(fall, false, false);
          bit = adc.sdata(fall + 25);
          adc.drive(fall + 25, false, true);
        } else {
          bit = adc.sdata(fall);  // just before the edge
          adc.drive(fall, false, false);
          adc.drive(fall + 25, false, true);
        }
        if (k <= 4) leading = uint16_t(leading << 1 | bit);
        else word = uint16_t(word << 1 | bit);
      }
      adc.drive(t + 800, true, true);
      t += 1000;
      if (!at_rise) {
        EXPECT_EQ(leading, 0);
      }
      if (word != codes[s]) ++wrong;
    }
    EXPECT_EQ(adc.violation_count(), 0u) << joined(adc.violations());
    if (at_rise) {
      EXPECT_GT(wrong, codes.size() / 2);
    } else {
      EXPECT_EQ(wrong, 0u);
    }
  }
}

// Each datasheet limit the model checks, broken alone in a hand-driven
// conversion that is otherwise legal (20 MHz SCLK, 1 us period): exactly the
// named parameter must be reported. The legal waveform itself reports nothing.
namespace {

struct Wave {
  double t2 = 25, half = 25, low = 25;  // CS->first fall, high and low times
  int clocks = 16;
  double period = 1000;                  // CS falling to CS falling
  double cs_high_at = -1;                // default: with the 16th rise
};

std::vector<std::string> drive_wave(const Wave& w, int conversions = 3) {
  Ad7476Model adc(random_codes(8, 9));
  double t0 = 1000;
  for (int c = 0; c < conversions; ++c) {
    adc.drive(t0, false, true);
    double t = t0 + w.t2;
    for (int k = 0; k < w.clocks; ++k) {
      adc.drive(t, false, false);
      adc.drive(t + w.low, false, true);
      t += w.low + w.half;
    }
    adc.drive(w.cs_high_at >= 0 ? t0 + w.cs_high_at : t - w.half, true, true);
    t0 += w.period;
  }
  return adc.violations();
}

bool only(const std::vector<std::string>& v, const std::string& name) {
  if (v.empty()) return false;
  for (const auto& s : v)
    if (s.find(name) == std::string::npos) return false;
  return true;
}

}  // namespace

TEST(Ad7476Model, EachViolationIsNamed) {
  EXPECT_TRUE(drive_wave(Wave{}).empty()) << joined(drive_wave(Wave{}));
  Wave w;
  w.t2 = 8;
  EXPECT_TRUE(only(drive_wave(w), "t2 (CS to SCLK setup)")) << joined(drive_wave(w));
  w = Wave{}; w.half = 15; w.low = 15; w.period = 1000;  // 33 MHz
  EXPECT_TRUE(only(drive_wave(w), "tSCLK (fSCLK max 20 MHz)")) << joined(drive_wave(w));
  w = Wave{}; w.half = 15; w.low = 45; w.period = 1500;  // 60 ns period, 25 % high
  EXPECT_TRUE(only(drive_wave(w), "t6 (SCLK high pulse width")) << joined(drive_wave(w));
  w = Wave{}; w.half = 45; w.low = 15; w.period = 1500;
  EXPECT_TRUE(only(drive_wave(w), "t5 (SCLK low pulse width")) << joined(drive_wave(w));
  w = Wave{}; w.clocks = 15;
  EXPECT_TRUE(only(drive_wave(w), "CS rose after 15 SCLK falling edges")) << joined(drive_wave(w));
  w = Wave{}; w.clocks = 17; w.cs_high_at = 900;
  EXPECT_TRUE(only(drive_wave(w), "more than 16 SCLK falling edges")) << joined(drive_wave(w));
  w = Wave{}; w.period = 850;  // tACQ = 850 - 650 = 200 ns < 250, tQUIET = 39 ns
  const auto v = drive_wave(w);
  EXPECT_NE(joined(v).find("tACQ"), std::string::npos) << joined(v);
  EXPECT_NE(joined(v).find("tQUIET"), std::string::npos) << joined(v);
  w = Wave{}; w.period = 820; w.cs_high_at = 815;  // CS high only 5 ns
  EXPECT_NE(joined(drive_wave(w)).find("t1 (CS high pulse width)"), std::string::npos)
      << joined(drive_wave(w));
  // Running out of samples is reported, not silently wrapped.
  EXPECT_NE(joined(drive_wave(Wave{}, 9)).find("sample vector exhausted"), std::string::npos);
}

namespace {

template <class M>
void adc_same_as_model(int64_t clk_hz, int64_t sample_hz, int nch, int lag, uint64_t seed) {
  auto m = std::make_unique<M>();
  eskin::cycle::AdcAd7476 model(clk_hz, sample_hz, 1, nch);
  ASSERT_EQ(model.lag(), lag);
  model.reset();
  std::mt19937_64 rng(seed);
  m->clk = 0; m->rst = 1; m->en = 0; m->sdata = 0; m->m_ready = 0; m->clear = 0;
  for (int i = 0; i < 3; ++i) { m->clk = 1; m->eval(); m->clk = 0; m->eval(); }
  m->rst = 0;
  const uint32_t mask = (1u << nch) - 1;
  long delivered = 0, overran = 0;
  bool en = true;
  for (long c = 0; c < 200000; ++c) {
    if (rng() % 20000 == 0) en = !en;
    const uint32_t sd = uint32_t(rng()) & mask;
    // A consumer that stalls for stretches now and then (overruns).
    const bool rdy = (c / 3000) % 4 != 3 && rng() % 3 != 0, clr = rng() % 10000 == 0;
    m->en = en; m->sdata = uint8_t(sd); m->m_ready = rdy; m->clear = clr;
    m->eval();
    ASSERT_EQ(bool(m->cs_n), model.cs_n()) << "clock " << c;
    ASSERT_EQ(bool(m->sclk), model.sclk()) << "clock " << c;
    ASSERT_EQ(bool(m->m_valid), model.m_valid()) << "clock " << c;
    uint32_t data = 0;
    for (int ch = 0; ch < nch; ++ch) data |= uint32_t(model.m_code(ch)) << (12 * ch);
    ASSERT_EQ(uint32_t(m->m_data), data) << "clock " << c;
    ASSERT_EQ(m->m_t, model.m_t()) << "clock " << c;
    ASSERT_EQ(m->overruns, model.overruns()) << "clock " << c;
    delivered += model.m_valid() && rdy;
    model.clock(en, sd, rdy, clr);
    m->clk = 1; m->eval();
    // SDATA changes again before the falling edge (LAG 1 takes it there).
    const uint32_t sd_fall = uint32_t(rng()) & mask;
    m->sdata = uint8_t(sd_fall);
    model.falling_edge(sd_fall);
    m->clk = 0; m->eval();
    overran += model.overruns() > 0;
  }
  EXPECT_GT(delivered, 100);
  EXPECT_GT(overran, 0);
}

}  // namespace

TEST(AdcAd7476, CycleModelEqualsTheRtlEveryClock) {
  adc_same_as_model<Vadc_ad7476>(12000000, 35000, 1, 0, 61);
  adc_same_as_model<Vadc_ad7476_fast>(40000000, 1000000, 2, 1, 62);
}
