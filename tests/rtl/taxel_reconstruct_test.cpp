// rtl/taxel_reconstruct.v against hls/taxel_reconstruct.h, token by token.
//
// Bound: bit-exact (row, col, value, last equal for every token), because the
// HLS kernel is the executable spec of the module; checked in all three modes
// with random input gaps and random back-pressure, and the stream rules (the
// output holds while stalled; nothing lost, duplicated or reordered).
// Timing (header of hls/taxel_reconstruct.h): with in_valid and out_ready
// always high the K inputs of a frame are accepted on K consecutive cycles;
// taxel n of the frame leaves at t_last_in + 1 + (n+1)*c, where c = 1
// (Product), MAG_W+2 (Conductance), MAG_W+7 (Pressure) -- 1 START cycle, then
// c cycles per taxel (SQRT MAG_W, GSCALE 1, SEARCH 4, INTERP 1, OUT 1) -- and
// the next frame's first input is accepted right after the last output, so the
// frame period is K + 1 + T*c with T = active rows * active cols (K + 1 when
// no line is active). Asserted exactly, also with inactive lines skipped.
// Two parameter sets: 16x16 (MAG_W 16, TAX_W 16) and 3x3 (MAG_W 10, TAX_W 32,
// from taxel_reconstruct_test.cmake).
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "Vtaxel_reconstruct.h"
#include "Vtaxel_reconstruct_small.h"
#include "hls/taxel_reconstruct.h"
#include "hls/taxel_reconstruct_config.h"

using namespace eskin::hls;

namespace {

struct Out { TaxelToken tok; uint64_t cycle; };
struct Frame { std::vector<uint16_t> mag; };  // rows then cols

template <class Model, class Kernel, int MAG_W>
struct Bench {
  std::unique_ptr<Model> m = std::make_unique<Model>();
  Kernel k;
  uint64_t cycle = 0;
  std::vector<uint64_t> in_cycles;
  std::vector<Out> outs;

  void tick() {
    m->clk = 1; m->eval();
    m->clk = 0; m->eval();
    ++cycle;
  }
  void reset() {
    m->clk = 0; m->rst = 1; m->in_valid = 0; m->out_ready = 0; m->tab_we = 0;
    m->eval();
    for (int i = 0; i < 3; ++i) tick();
    m->rst = 0;
    m->eval();
  }
  void configure(const TaxelReconstructConfig& c) {
    ASSERT_TRUE(k.configure(c));
    m->cfg_rows = c.rows; m->cfg_cols = c.cols; m->cfg_mode = uint8_t(c.mode);
    m->cfg_shift = c.shift; m->cfg_threshold = c.active_threshold;
    m->cfg_recip = c.recip; m->cfg_recip_shift = c.recip_shift;
    m->cfg_slope_shift = c.slope_shift;
    for (int s = 0; s < kTaxelPwlN; ++s) {
      m->tab_we = 1; m->tab_addr = uint8_t(s);
      m->tab_g = c.g_tab[s]; m->tab_p = c.p_tab[s]; m->tab_slope = c.slope[s];
      m->eval();
      tick();
    }
    m->tab_we = 0;
    m->eval();
  }
  // Streams the frames; returns the expected (HLS) tokens. p_valid/p_ready:
  // per-cycle probability that the source offers / the sink accepts.
  std::vector<TaxelToken> stream(const std::vector<Frame>& frames, double p_valid,
                                 double p_ready, uint64_t seed) {
    std::vector<MagToken> in;
    std::vector<TaxelToken> want;
    for (const auto& f : frames)
      for (size_t i = 0; i < f.mag.size(); ++i) {
        in.push_back({uint8_t(i), f.mag[i]});
        k.push(in.back());
        TaxelToken t;
        while (k.pop(t)) want.push_back(t);
      }
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), accept(p_ready);
    size_t next = 0;
    bool offering = false, was_stalled = false;
    TaxelToken stalled{};
    uint64_t progress = cycle;  // give up after 10000 cycles without a handshake
    while ((next < in.size() || outs.size() < want.size()) && cycle - progress < 10000) {
      if (!offering && next < in.size()) offering = offer(rng);
      m->in_valid = offering;
      if (offering) { m->in_k = in[next].k; m->in_mag = in[next].mag; }
      m->out_ready = accept(rng);
      m->eval();
      if (was_stalled) {  // a stalled token must hold
        EXPECT_TRUE(m->out_valid);
        EXPECT_EQ(m->out_row, stalled.row);
        EXPECT_EQ(m->out_col, stalled.col);
        EXPECT_EQ(uint64_t(m->out_value), stalled.value);
      }
      const TaxelToken now{uint8_t(m->out_row), uint8_t(m->out_col), uint32_t(m->out_value),
                           bool(m->out_last)};
      was_stalled = m->out_valid && !m->out_ready;
      stalled = now;
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
    const auto& g = b.outs[n].tok;
    ASSERT_TRUE(g.row == want[n].row && g.col == want[n].col && g.value == want[n].value &&
                g.last == want[n].last)
        << "token " << n << ": rtl (" << int(g.row) << "," << int(g.col) << ")=" << g.value
        << " last " << g.last << ", hls (" << int(want[n].row) << "," << int(want[n].col)
        << ")=" << want[n].value << " last " << want[n].last;
  }
}

std::vector<Frame> frames(int rows, int cols, int n, int mag_w, uint16_t thr, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const uint32_t max = (1u << mag_w) - 1u;
  std::vector<Frame> f{size_t(n)};
  for (auto& fr : f)
    for (int i = 0; i < rows + cols; ++i) {
      uint32_t v = uint32_t(rng() % (max + 1));
      if (rng() % 3 == 0) v = v % (thr + 1u);  // a third of the lines idle
      if (rng() % 17 == 0) v = rng() & 1 ? max : 0;
      fr.mag.push_back(uint16_t(v));
    }
  return f;
}

TaxelReconstructConfig config(int rows, int cols, TaxelMode mode, uint16_t thr, int tax_w,
                              double full) {
  TaxelReconstructConfig c;
  c.rows = uint8_t(rows); c.cols = uint8_t(cols); c.mode = mode;
  c.active_threshold = thr;
  c.shift = uint8_t(tax_w >= 32 ? 0 : 32 - tax_w - 2);
  set_full_carrier(full, c);
  const double g[] = {0, 0.1, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.5};
  double p[10];
  for (int s = 0; s < 10; ++s) p[s] = 50.0 * g[s] / (1.05 - std::min(g[s], 1.0));
  set_pwl(g, p, 10, 1.0 / 64.0, c, tax_w);
  return c;
}

using Big = Bench<Vtaxel_reconstruct, TaxelReconstruct<16, 16, 16, 16>, 16>;
using Small = Bench<Vtaxel_reconstruct_small, TaxelReconstruct<3, 3, 10, 32>, 10>;

template <class B, int MAG_W, int TAX_W>
void bit_exact(int rows, int cols, TaxelMode mode, double full, uint64_t seed) {
  for (auto [pv, pr] : {std::pair{0.6, 0.4}, std::pair{1.0, 1.0}, std::pair{0.3, 0.9}}) {
    B b;
    b.reset();
    const uint16_t thr = uint16_t(1u << (MAG_W - 3));
    b.configure(config(rows, cols, mode, thr, TAX_W, full));
    auto want = b.stream(frames(rows, cols, 40, MAG_W, thr, seed), pv, pr, seed + 1);
    ASSERT_GT(want.size(), 10u);
    expect_same(want, b);
  }
}

// Exact cycle timing with the source and sink always ready (see top comment).
template <class B, int MAG_W, int TAX_W>
void timing(int rows, int cols, TaxelMode mode, uint16_t thr) {
  B b;
  b.reset();
  b.configure(config(rows, cols, mode, thr, TAX_W, 300.0));
  const int K = rows + cols;
  const int c = mode == TaxelMode::Product ? 1 : mode == TaxelMode::Conductance ? MAG_W + 2
                                                                                : MAG_W + 7;
  auto fr = frames(rows, cols, 12, MAG_W, thr, 77);
  auto want = b.stream(fr, 1.0, 1.0, 5);
  expect_same(want, b);
  ASSERT_EQ(b.in_cycles.size(), fr.size() * size_t(K));
  size_t out_n = 0;
  for (size_t f = 0; f < fr.size(); ++f) {
    int ar = 0, ac = 0;  // active lines, counted from the frame itself
    for (int i = 0; i < rows; ++i) ar += fr[f].mag[size_t(i)] >= thr;
    for (int j = 0; j < cols; ++j) ac += fr[f].mag[size_t(rows + j)] >= thr;
    const size_t T = size_t(ar * ac);
    const uint64_t first = b.in_cycles[f * size_t(K)], last = b.in_cycles[f * size_t(K) + size_t(K - 1)];
    EXPECT_EQ(last - first, uint64_t(K - 1)) << "frame " << f << ": one input per cycle";
    for (size_t n = 0; n < T; ++n) {
      ASSERT_EQ(b.outs[out_n + n].cycle, last + 1 + (n + 1) * uint64_t(c))
          << "frame " << f << " taxel " << n;
    }
    out_n += T;
    if (f + 1 < fr.size())
      EXPECT_EQ(b.in_cycles[(f + 1) * size_t(K)] - first, uint64_t(K + 1) + T * uint64_t(c))
          << "frame period, frame " << f << " T " << T;
  }
  EXPECT_EQ(out_n, b.outs.size());
}

}  // namespace

TEST(TaxelReconstructRtl, ProductBitExact16x16) { bit_exact<Big, 16, 16>(16, 16, TaxelMode::Product, 3000, 1); }
TEST(TaxelReconstructRtl, ConductanceBitExact10x7) { bit_exact<Big, 16, 16>(10, 7, TaxelMode::Conductance, 20000, 2); }
TEST(TaxelReconstructRtl, PressureBitExact3x3) { bit_exact<Big, 16, 16>(3, 3, TaxelMode::Pressure, 30000, 3); }
TEST(TaxelReconstructRtl, PressureBitExact16x16) { bit_exact<Big, 16, 16>(16, 16, TaxelMode::Pressure, 50000, 4); }
TEST(TaxelReconstructRtl, SmallAllModesBitExact) {
  bit_exact<Small, 10, 32>(3, 3, TaxelMode::Product, 300, 5);
  bit_exact<Small, 10, 32>(3, 2, TaxelMode::Conductance, 700, 6);
  bit_exact<Small, 10, 32>(2, 3, TaxelMode::Pressure, 500, 7);
}
TEST(TaxelReconstructRtl, TimingProduct) {
  timing<Big, 16, 16>(16, 16, TaxelMode::Product, 0);
  timing<Big, 16, 16>(16, 16, TaxelMode::Product, 20000);
  timing<Big, 16, 16>(3, 3, TaxelMode::Product, 60000);  // mostly idle frames
}
TEST(TaxelReconstructRtl, TimingConductanceAndPressure) {
  timing<Big, 16, 16>(3, 3, TaxelMode::Conductance, 0);
  timing<Big, 16, 16>(3, 3, TaxelMode::Pressure, 0);
  timing<Big, 16, 16>(8, 5, TaxelMode::Pressure, 16000);
  timing<Small, 10, 32>(3, 3, TaxelMode::Pressure, 100);
}
