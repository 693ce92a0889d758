// rtl/ghost_filter.v against hls/ghost_filter.h, token by token.
//
// Bound: bit-exact (row, col, value, last of every site token), because the
// HLS kernel is the executable spec of the module. Frames: synthetic touches
// (staggered and simultaneous onsets, ramps, releases, +-3 units of noise)
// and the default scene's magnitude frames (golden exact SDFT); thesis and
// improved modes; product and conductance values; random input gaps and
// random back-pressure; the output must hold while stalled.
// Timing (header of rtl/ghost_filter.v): with in_valid and out_ready always
// high, the frame's K inputs are accepted on K consecutive cycles; with
// t_last the last input's cycle, P = max(rows, cols), steps/S_b/S_a the
// frame's pairing steps and sites before/after release, fit = the pairing
// was committed (all from the HLS kernel), commit = fit ? steps : 0, site n
// leaves at t_last + 4 + steps*(P+1) + commit + S_b + (n+1)*c (c = 1
// product, MAG_W+2 conductance) and the next frame starts K + 4 +
// steps*(P+1) + commit + S_b + S_a*c cycles after this one. After reset the
// history is cleared for L_MAX*2^KB cycles (32*32) before the first input.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "Vghost_filter.h"
#include "Vghost_filter_small.h"
#include "hls/ghost_filter.h"
#include "hls/taxel_reconstruct_config.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

using namespace eskin;
using namespace eskin::hls;

namespace {

struct Frame { std::vector<uint16_t> mag; };  // rows then cols
struct FrameStats { int steps, s_before, s_after; bool fit; };

// Model: a Verilated ghost_filter; Kernel: the HLS kernel with the same
// parameters; CLEAR: L_MAX * 2^KB (history clear after reset).
template <class Model, class Kernel, int CLEAR>
struct Bench {
  std::unique_ptr<Model> m = std::make_unique<Model>();
  Kernel k;
  uint64_t cycle = 0, ready_cycle = 0;
  std::vector<uint64_t> in_cycles;
  std::vector<std::pair<TaxelToken, uint64_t>> outs;
  std::vector<FrameStats> stats;

  void tick() {
    m->clk = 1; m->eval();
    m->clk = 0; m->eval();
    ++cycle;
  }
  void start(const GhostFilterConfig& c) {
    ASSERT_TRUE(k.configure(c));
    m->cfg_rows = c.rows; m->cfg_cols = c.cols; m->cfg_lookback = c.lookback;
    m->cfg_improved = c.improved; m->cfg_onset = c.onset; m->cfg_pair_tol = c.pair_tol;
    m->cfg_release2 = c.release2; m->cfg_conductance = c.conductance;
    m->cfg_shift = c.shift; m->cfg_recip = c.recip; m->cfg_recip_shift = c.recip_shift;
    m->clk = 0; m->rst = 1; m->in_valid = 0; m->out_ready = 0;
    m->eval();
    tick();
    m->rst = 0;
    m->eval();
    const uint64_t t0 = cycle;
    while (!m->in_ready && cycle - t0 < 100000) tick();
    ready_cycle = cycle - t0;
  }
  std::vector<TaxelToken> stream(const std::vector<Frame>& frames, double p_valid,
                                 double p_ready, uint64_t seed) {
    std::vector<MagToken> in;
    std::vector<TaxelToken> want;
    for (const auto& f : frames)
      for (size_t i = 0; i < f.mag.size(); ++i) {
        in.push_back({uint8_t(i), f.mag[i]});
        if (!k.push(in.back())) continue;
        stats.push_back({k.pair_steps(), k.sites_before_release(), k.sites_after_release(),
                         k.pairing_fit()});
        TaxelToken t;
        while (k.pop(t)) want.push_back(t);
      }
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), accept(p_ready);
    size_t next = 0;
    bool offering = false, stalled = false;
    TaxelToken held{};
    uint64_t progress = cycle;
    while ((next < in.size() || outs.size() < want.size()) && cycle - progress < 20000) {
      if (!offering && next < in.size()) offering = offer(rng);
      m->in_valid = offering;
      if (offering) { m->in_k = in[next].k; m->in_mag = in[next].mag; }
      m->out_ready = accept(rng);
      m->eval();
      const TaxelToken now{uint8_t(m->out_row), uint8_t(m->out_col), uint32_t(m->out_value),
                           bool(m->out_last)};
      if (stalled) {
        EXPECT_TRUE(m->out_valid);
        EXPECT_TRUE(now.row == held.row && now.col == held.col && now.value == held.value);
      }
      stalled = m->out_valid && !m->out_ready;
      held = now;
      if (m->out_valid && m->out_ready) { outs.push_back({now, cycle}); progress = cycle; }
      if (offering && m->in_ready) {
        in_cycles.push_back(cycle); ++next; offering = false; progress = cycle;
      }
      tick();
    }
    return want;
  }
};

template <class B>
void expect_same(const std::vector<TaxelToken>& want, const B& b) {
  ASSERT_EQ(b.outs.size(), want.size());
  for (size_t n = 0; n < want.size(); ++n) {
    const TaxelToken& g = b.outs[n].first;
    ASSERT_TRUE(g.row == want[n].row && g.col == want[n].col && g.value == want[n].value &&
                g.last == want[n].last)
        << "token " << n << ": rtl (" << int(g.row) << "," << int(g.col) << ")=" << g.value
        << " last " << g.last << "; hls (" << int(want[n].row) << "," << int(want[n].col)
        << ")=" << want[n].value << " last " << want[n].last;
  }
}

// Touches on a rows x cols skin: groups of 1-3 onsets in the same frame or a
// few frames apart, ramps of 0-6 frames, held 20-60 frames; F = 2000 units.
std::vector<Frame> touch_frames(int rows, int cols, int n, uint64_t seed, double F = 2000.0) {
  struct T { int r, c, on, ramp, off; double g; };
  std::mt19937_64 rng(seed);
  auto uni = [&](int a, int b) { return a + int(rng() % uint64_t(b - a + 1)); };
  std::vector<T> ts;
  for (int t = 5; t < n; t += uni(10, 40)) {
    const int k = uni(1, 3);
    for (int q = 0; q < k; ++q) {
      const int on = t + (rng() % 2 ? 0 : uni(0, 6));
      ts.push_back({uni(0, rows - 1), uni(0, cols - 1), on, uni(0, 6), on + uni(20, 60),
                    0.1 + 0.8 * double(rng() % 1000) / 1000.0});
    }
  }
  std::vector<Frame> out;
  for (int f = 0; f < n; ++f) {
    std::vector<double> line(size_t(rows + cols), 0.0);
    for (const T& t : ts) {
      if (f < t.on || f >= t.off) continue;
      const double g = t.g * (t.ramp ? std::min(1.0, double(f - t.on + 1) / t.ramp) : 1.0);
      line[size_t(t.r)] += g;
      line[size_t(rows + t.c)] += g;
    }
    Frame fr;
    for (double v : line)
      fr.mag.push_back(uint16_t(std::max(0.0, std::round(v * F) + uni(-3, 3))));
    out.push_back(fr);
  }
  return out;
}

GhostFilterConfig config(int rows, int cols, bool improved, bool conductance, int lookback,
                         double F) {
  GhostFilterConfig c;
  c.rows = uint8_t(rows); c.cols = uint8_t(cols); c.lookback = uint16_t(lookback);
  c.improved = improved; c.conductance = conductance;
  c.onset = uint16_t(0.05 * F); c.pair_tol = uint16_t(0.02 * F);
  c.release2 = uint32_t(std::ceil(0.05 * F * 0.05 * F));
  c.shift = 8;
  TaxelReconstructConfig t;
  set_full_carrier(F, t);
  c.recip = t.recip; c.recip_shift = t.recip_shift;
  return c;
}

using Big = Bench<Vghost_filter, GhostFilter<16, 16, 32, 16, 16>, 32 * 32>;
// tests/rtl/ghost_filter_test.cmake: R_MAX 3, C_MAX 3, L_MAX 5, MAG_W 12,
// TAX_W 24 (KB = 3: CLEAR = 5 * 8 cycles).
using Small = Bench<Vghost_filter_small, GhostFilter<3, 3, 5, 12, 24>, 5 * 8>;

}  // namespace

TEST(GhostFilterRtl, BitExactSyntheticTouchesAllModes) {
  int variant = 0;
  for (bool improved : {false, true})
    for (bool cond : {false, true})
      for (auto [rows, cols] : {std::pair{10, 10}, std::pair{3, 3}, std::pair{16, 5}}) {
        SCOPED_TRACE("improved " + std::to_string(improved) + " conductance " +
                     std::to_string(cond) + " size " + std::to_string(rows) + "x" + std::to_string(cols));
        Big b;
        b.start(config(rows, cols, improved, cond, 1 + variant % 8, 2000.0));
        auto want = b.stream(touch_frames(rows, cols, 300, uint64_t(variant)), 0.7, 0.5,
                             uint64_t(100 + variant));
        ASSERT_GT(want.size(), 100u);
        expect_same(want, b);
        ++variant;
      }
}

TEST(GhostFilterRtl, BitExactDefaultScene) {
  const auto sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  sim::WorldModel world(sc);
  auto codes = world.all_codes();
  auto bank = golden::make_sdft_bank(DftVariant::Exact, sc.skin.carrier_freqs_hz(),
                                     sc.skin.adc.rate_hz, sc.decoder);
  const double half_n = sc.decoder.window / 2.0, F = sc.skin.full_carrier_lsb() * half_n;
  std::vector<Frame> frames;
  for (int code : codes) {
    bank->push(code - sc.skin.adc.mid_code());
    Frame f;
    for (int k = 0; k < bank->carriers(); ++k)
      f.mag.push_back(uint16_t(std::lround(bank->magnitude(k) * half_n)));
    frames.push_back(f);
  }
  for (bool improved : {false, true}) {
    Big b;
    b.start(config(3, 3, improved, true, sc.decoder.window, F));
    auto want = b.stream(frames, 0.8, 0.7, 9);
    ASSERT_GT(want.size(), 1000u);
    expect_same(want, b);
  }
}

// Exact cycles with the source and sink always ready (see top comment).
template <class B, int MAG_W>
void timing(int rows, int cols, bool improved, bool cond, int lookback, double F, int clear) {
  B b;
  b.start(config(rows, cols, improved, cond, lookback, F));
  EXPECT_EQ(b.ready_cycle, uint64_t(clear));
  const auto fr = touch_frames(rows, cols, 200, 7, F);
  auto want = b.stream(fr, 1.0, 1.0, 1);
  expect_same(want, b);
  const uint64_t K = uint64_t(rows + cols), P = uint64_t(std::max(rows, cols));
  const uint64_t c = cond ? MAG_W + 2 : 1;
  size_t out_n = 0;
  long pair_steps = 0;
  for (size_t f = 0; f < fr.size(); ++f) {
    const FrameStats& s = b.stats[f];
    pair_steps += s.steps;
    const uint64_t first = b.in_cycles[f * K], last = b.in_cycles[f * K + K - 1];
    ASSERT_EQ(last - first, K - 1) << "frame " << f;
    const uint64_t commit = s.fit ? uint64_t(s.steps) : 0;
    const uint64_t t_emit = last + 4 + uint64_t(s.steps) * (P + 1) + commit + uint64_t(s.s_before);
    for (int n = 0; n < s.s_after; ++n) {
      ASSERT_EQ(b.outs[out_n + size_t(n)].second, t_emit + uint64_t(n + 1) * c)
          << "frame " << f << " site " << n;
    }
    out_n += size_t(s.s_after);
    if (f + 1 < fr.size()) {
      ASSERT_EQ(b.in_cycles[(f + 1) * K] - first,
                K + 4 + uint64_t(s.steps) * (P + 1) + commit + uint64_t(s.s_before) +
                    uint64_t(s.s_after) * c)
          << "frame " << f;
    }
  }
  EXPECT_EQ(out_n, b.outs.size());
  if (improved) { EXPECT_GT(pair_steps, 0); }  // the pairing path was timed
}

TEST(GhostFilterRtl, ExactLatencyAndFramePeriod) {
  for (bool improved : {false, true})
    for (bool cond : {false, true}) {
      for (auto [rows, cols] : {std::pair{10, 10}, std::pair{3, 3}, std::pair{4, 9}})
        timing<Big, 16>(rows, cols, improved, cond, 4, 2000.0, 32 * 32);
      timing<Small, 12>(3, 3, improved, cond, 5, 1000.0, 5 * 8);
      timing<Small, 12>(2, 3, improved, cond, 3, 1000.0, 5 * 8);
    }
}

// Second parameter set: bit-exact with back-pressure in all modes.
TEST(GhostFilterRtl, SmallParametersBitExact) {
  int variant = 0;
  for (bool improved : {false, true})
    for (bool cond : {false, true}) {
      Small b;
      b.start(config(3, 3, improved, cond, 1 + variant % 5, 1000.0));
      auto want = b.stream(touch_frames(3, 3, 400, uint64_t(50 + variant), 1000.0), 0.6, 0.5,
                           uint64_t(7 + variant));
      ASSERT_GT(want.size(), 100u);
      expect_same(want, b);
      ++variant;
    }
}
