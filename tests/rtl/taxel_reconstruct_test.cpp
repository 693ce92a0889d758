// rtl/taxel_reconstruct.v against hls/taxel_reconstruct.h, token by token.
//
// Bound: bit-exact (i, j, g, site, last of every taxel) with the kernel's
// streaming form TaxelReconstructStream, whose mask is the hls GhostFilter's
// sites after frame() (the test plays the mask's owner: it writes them
// through mask_we and pulses sites_done, at random clocks, after the
// previous frame's last taxel). Each expected taxel is also checked against
// DtmfChain's own formula ((!ghost || site after release) ? value : 0 from
// TaxelReconstruct::value and GhostFilter::release), so the stream form is
// held to the chain. Random input gaps and output back-pressure (seeded;
// a stalled output must hold its token). Magnitudes: lines that rise and
// fall (touches, so the ghost filter makes and releases sites), zeros and
// full scale (65535); recip / recip_shift from one carrier of 1000, 20000
// and 65535 magnitude units, and the extremes (32767, 0: saturation;
// 1, 31: everything rounds to 0).
// Timing (no gaps, no back-pressure): the K magnitudes on K consecutive
// clocks, the first taxel 25 clocks after the last magnitude, then one
// taxel a clock, and the next frame's first magnitude on the clock after
// the last taxel: a frame every K + rows cols + 24 clocks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vtaxel_reconstruct.h"
#include "Vtaxel_reconstruct_x64.h"
#include "clocked_dut.h"
#include "hls/ghost_filter.h"
#include "hls/taxel_reconstruct.h"

namespace {

using eskin::hls::GhostFilter;
using eskin::hls::GhostFilterConfig;
using eskin::hls::TaxelMagIn;
using eskin::hls::TaxelOut;
using eskin::hls::TaxelReconstruct;
using eskin::hls::TaxelReconstructConfig;
using eskin::hls::TaxelReconstructStream;

struct Frame {
  TaxelReconstructConfig cfg;
  bool ghost = false;
  uint16_t release = 0;
  std::vector<uint16_t> mag;   // rows + cols
  std::vector<uint8_t> mask;   // rows x cols, as written
  std::vector<TaxelOut> want;  // rows x cols, row-major
};

bool same(const TaxelOut& a, const TaxelOut& b) {
  return a.i == b.i && a.j == b.j && a.g == b.g && a.site == b.site && a.last == b.last;
}

std::string show(const TaxelOut& t) {
  return "(" + std::to_string(t.i) + "," + std::to_string(t.j) + ") g " + std::to_string(t.g) + " site " +
         std::to_string(t.site) + " last " + std::to_string(t.last);
}

// recip and recip_shift for one full carrier of F magnitude units, as the
// builder picks them (2^14 <= recip < 2^15, hls/taxel_reconstruct.h).
void full_scale(TaxelReconstructConfig& c, double F) {
  for (int s = 0; s <= 31; ++s) {
    const double r = std::floor(std::ldexp(1.0, 15 + s) / F + 0.5);
    if (r >= 16384 && r < 32768) {
      c.recip = uint16_t(r), c.recip_shift = uint8_t(s);
      return;
    }
  }
  ADD_FAILURE() << "no recip for F " << F;
}

void pick_scale(TaxelReconstructConfig& c, std::mt19937_64& rng) {
  switch (rng() % 6) {
    case 0: full_scale(c, 1000); break;
    case 1: full_scale(c, 20000); break;
    case 2: full_scale(c, 65535); break;
    case 3: c.recip = 32767, c.recip_shift = 0; break;  // saturates
    case 4: c.recip = 1, c.recip_shift = 31; break;     // rounds to 0
    default: c.recip = uint16_t(1 + rng() % 32767), c.recip_shift = uint8_t(rng() % 32); break;
  }
}

// Magnitudes of `frames` frames: each line a level that jumps up (a touch)
// or back down now and then, with noise; some frames all 0 or all 65535.
std::vector<std::vector<uint16_t>> magnitudes(int K, int frames, std::mt19937_64& rng) {
  std::vector<int> level(size_t(K), 2000);
  std::vector<std::vector<uint16_t>> out;
  for (int f = 0; f < frames; ++f) {
    std::vector<uint16_t> m(static_cast<size_t>(K));
    const int kind = int(rng() % 20);
    for (int k = 0; k < K; ++k) {
      int& l = level[size_t(k)];
      const int r = int(rng() % 16);
      if (r == 0) l += 3000 + int(rng() % 30000);
      else if (r == 1) l = 1000 + int(rng() % 3000);
      const int v = l + int(rng() % 200) - 100;
      m[size_t(k)] = uint16_t(kind == 0 ? 0 : kind == 1 ? 65535 : v < 0 ? 0 : v > 65535 ? 65535 : v);
    }
    out.push_back(m);
  }
  return out;
}

// Expected taxels of a sequence of frames with the ghost filter on: the
// mask written for frame f is the filter's sites after frame(mag_f).
template <int R_MAX, int C_MAX>
std::vector<Frame> ghost_frames(int rows, int cols, int frames, uint64_t seed) {
  std::mt19937_64 rng(seed);
  GhostFilterConfig gc;
  gc.rows = uint8_t(rows), gc.cols = uint8_t(cols), gc.lookback = 2;
  gc.onset = 2500, gc.pair_tol = 1500, gc.release = 6000;
  auto gf = std::make_unique<GhostFilter<R_MAX, C_MAX, 4>>();
  EXPECT_TRUE(gf->configure(gc));
  TaxelReconstructStream<R_MAX, C_MAX> ts;
  TaxelReconstruct<R_MAX, C_MAX> tr;
  const auto mags = magnitudes(rows + cols, frames, rng);
  std::vector<Frame> out;
  int sites = 0, released = 0, kept = 0, saturated = 0;
  for (int f = 0; f < frames; ++f) {
    Frame fr;
    fr.cfg.rows = uint8_t(rows), fr.cfg.cols = uint8_t(cols);
    pick_scale(fr.cfg, rng);
    fr.ghost = true;
    fr.release = gc.release;
    fr.mag = mags[size_t(f)];
    EXPECT_TRUE(ts.configure(fr.cfg));
    EXPECT_TRUE(tr.configure(fr.cfg));
    for (int k = 0; k < rows + cols; ++k) {
      TaxelMagIn in;
      in.k = uint8_t(k), in.mag = fr.mag[size_t(k)], in.last = k == rows + cols - 1;
      EXPECT_EQ(ts.push(in), in.last);
    }
    // DtmfChain's order: lines, frame, release, then g at the sites.
    tr.lines(fr.mag.data());
    gf->frame(fr.mag.data());
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < cols; ++j) fr.mask.push_back(gf->site(i, j));
    gf->release([&tr](int i, int j) { return tr.value(i, j); });
    for (int n = 0; n < rows * cols; ++n) {
      const TaxelOut t = ts.taxel(n, fr.mask[size_t(n)], true, fr.release);
      const int i = n / cols, j = n % cols;
      EXPECT_EQ(t.site, gf->site(i, j));
      EXPECT_EQ(t.g, gf->site(i, j) ? tr.value(i, j) : 0);
      sites += fr.mask[size_t(n)];
      released += fr.mask[size_t(n)] && !t.site;
      kept += t.site;
      saturated += t.g == 65535;
      fr.want.push_back(t);
    }
    out.push_back(fr);
  }
  // The inputs reach what they are for.
  EXPECT_GT(kept, 10);
  EXPECT_GT(released, 0);
  EXPECT_GT(saturated, 0);
  EXPECT_GT(sites, kept);
  return out;
}

// Random mask bits (out_site = mask && g >= release; with ghost = false every
// taxel's g comes out); rows and cols from `sizes`, one pair per frame. With
// static_mask every frame has the same mask (one size only).
template <int R_MAX, int C_MAX>
std::vector<Frame> plain_frames(const std::vector<std::pair<int, int>>& sizes, int frames, uint64_t seed,
                                bool ghost = false, bool static_mask = false) {
  std::mt19937_64 rng(seed);
  TaxelReconstructStream<R_MAX, C_MAX> ts;
  std::vector<Frame> out;
  for (int f = 0; f < frames; ++f) {
    Frame fr;
    const auto rc = sizes[size_t(f) % sizes.size()];
    fr.cfg.rows = uint8_t(rc.first), fr.cfg.cols = uint8_t(rc.second);
    pick_scale(fr.cfg, rng);
    fr.release = uint16_t(rng() % 40000);
    fr.mag = magnitudes(rc.first + rc.second, 1, rng)[0];
    if (rng() % 8 == 0)  // the largest root of all lines
      for (auto& m : fr.mag) m = 65535;
    EXPECT_TRUE(ts.configure(fr.cfg));
    for (int k = 0; k < rc.first + rc.second; ++k) {
      TaxelMagIn in;
      in.k = uint8_t(k), in.mag = fr.mag[size_t(k)], in.last = k == rc.first + rc.second - 1;
      ts.push(in);
    }
    TaxelReconstruct<R_MAX, C_MAX> tr;
    EXPECT_TRUE(tr.configure(fr.cfg));
    tr.lines(fr.mag.data());
    fr.ghost = ghost;
    if (static_mask) fr.release = 6000;
    // Every other frame a tie: release equal to one taxel's g, at a site
    // (kept: g >= release).
    const int tie = static_mask || f % 2 ? -1 : int(rng() % uint64_t(rc.first * rc.second));
    if (tie >= 0) fr.release = tr.value(tie / rc.second, tie % rc.second);
    for (int n = 0; n < rc.first * rc.second; ++n) {
      fr.mask.push_back(uint8_t(static_mask ? n % 3 == 0 : n == tie || (rng() & 1)));
      const TaxelOut t = ts.taxel(n, fr.mask.back(), ghost, fr.release);
      const uint16_t g = tr.value(n / rc.second, n % rc.second);
      EXPECT_EQ(t.g, !ghost || (fr.mask.back() && g >= fr.release) ? g : 0);
      fr.want.push_back(t);
    }
    out.push_back(fr);
  }
  return out;
}

template <class V, int R_MAX, int C_MAX>
struct TaxelRun {
  ClockedDut<V> d;
  std::vector<TaxelOut> outs;
  std::vector<uint64_t> in_cycles, out_cycles, sites_cycles;

  // Streams the frames: magnitudes offered with probability p_valid a
  // clock, the mask written (one bit a clock, with probability p_mask) and
  // sites_done pulsed once the previous frame's last taxel is taken,
  // outputs taken with probability p_ready.
  // With static_mask, frame 0's mask is written before the stream and
  // sites_done held high.
  void stream(const std::vector<Frame>& frames, double p_valid, double p_mask, double p_ready, uint64_t seed,
              bool static_mask = false, bool reset = true) {
    auto& m = d.m;
    if (reset) d.reset();
    m.mask_we = 0, m.sites_done = 0;
    if (static_mask) {
      const Frame& f = frames[0];
      for (size_t n = 0; n < f.mask.size(); ++n) {
        m.mask_we = 1;
        m.mask_addr = uint32_t((n / f.cfg.cols) * C_MAX + n % f.cfg.cols);
        m.mask_din = f.mask[n];
        d.tick();
      }
    }
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), write(p_mask), accept(p_ready);
    size_t fin = 0, kin = 0, fmask = 0, nmask = 0, fout = 0, total = 0;
    for (const auto& f : frames) total += f.want.size();
    bool held = false;
    TaxelOut last{};
    const uint64_t limit = d.cycle + 200 * total + 100000;
    while (outs.size() < total && d.cycle < limit) {
      // The configuration of the frame in the block (held to its last taxel).
      const Frame& cur = frames[std::min(fout, frames.size() - 1)];
      m.cfg_rows = cur.cfg.rows, m.cfg_cols = cur.cfg.cols;
      m.cfg_recip = cur.cfg.recip, m.cfg_recip_shift = cur.cfg.recip_shift;
      m.cfg_ghost = cur.ghost, m.cfg_release = cur.release;
      const bool give = fin < frames.size() && offer(rng);
      m.in_valid = give;
      if (give) {
        const Frame& f = frames[fin];
        m.in_k = uint8_t(kin), m.in_mag = f.mag[kin], m.in_last = kin + 1 == f.mag.size();
      }
      m.mask_we = 0, m.sites_done = static_mask;
      if (!static_mask && fmask < frames.size() && fmask == fout && write(rng)) {
        const Frame& f = frames[fmask];
        if (nmask < f.mask.size()) {
          m.mask_we = 1;
          m.mask_addr = uint32_t((nmask / f.cfg.cols) * C_MAX + nmask % f.cfg.cols);
          m.mask_din = f.mask[nmask];
          ++nmask;
        } else {
          m.sites_done = 1;
          sites_cycles.push_back(d.cycle);
          ++fmask, nmask = 0;
        }
      }
      m.out_ready = accept(rng);
      m.eval();
      if (give && m.in_ready) {
        in_cycles.push_back(d.cycle);
        if (++kin == frames[fin].mag.size()) ++fin, kin = 0;
      }
      if (m.out_valid) {
        TaxelOut o;
        o.i = m.out_i, o.j = m.out_j, o.g = m.out_g, o.site = m.out_site, o.last = m.out_last;
        if (held) {
          EXPECT_TRUE(same(o, last)) << "output changed while stalled, cycle " << d.cycle;
        }
        last = o;
        held = !m.out_ready;
        if (m.out_ready) {
          outs.push_back(o), out_cycles.push_back(d.cycle);
          if (o.last) ++fout;
        }
      } else {
        EXPECT_FALSE(held) << "out_valid dropped while stalled, cycle " << d.cycle;
        held = false;
      }
      d.tick();
    }
    ASSERT_EQ(outs.size(), total) << "not all taxels out in " << limit << " clocks";
    ASSERT_EQ(fin, frames.size());
  }

  void expect_bit_exact(const std::vector<Frame>& frames) {
    size_t n = 0;
    for (size_t f = 0; f < frames.size(); ++f)
      for (const auto& w : frames[f].want) {
        ASSERT_LT(n, outs.size());
        ASSERT_TRUE(same(outs[n], w)) << "frame " << f << " taxel " << n << ": rtl " << show(outs[n]) << ", hls "
                                      << show(w);
        ++n;
      }
    EXPECT_EQ(n, outs.size());
  }
};

TEST(TaxelReconstructRtl, BitExact3x3GhostUnderBackPressure) {
  const auto frames = ghost_frames<3, 3>(3, 3, 400, 31);
  auto r = std::make_unique<TaxelRun<Vtaxel_reconstruct, 3, 3>>();
  r->stream(frames, 0.6, 0.15, 0.55, 32);  // the mask often late
  r->expect_bit_exact(frames);
}

TEST(TaxelReconstructRtl, BitExact3x3NoGhostSmallerSkins) {
  const auto frames = plain_frames<3, 3>({{3, 3}, {2, 3}, {1, 1}, {3, 1}, {1, 2}}, 400, 33);
  auto r = std::make_unique<TaxelRun<Vtaxel_reconstruct, 3, 3>>();
  r->stream(frames, 0.7, 0.8, 0.5, 34);
  r->expect_bit_exact(frames);
}

TEST(TaxelReconstructRtl, BitExact64x64GhostUnderBackPressure) {
  const auto frames = ghost_frames<64, 64>(64, 64, 24, 35);
  auto r = std::make_unique<TaxelRun<Vtaxel_reconstruct_x64, 64, 64>>();
  r->stream(frames, 0.5, 0.9, 0.6, 36);
  r->expect_bit_exact(frames);
}

TEST(TaxelReconstructRtl, BitExact64x64NoGhostSmallerSkins) {
  const auto frames = plain_frames<64, 64>({{64, 64}, {17, 40}, {1, 64}, {64, 1}}, 16, 37);
  auto r = std::make_unique<TaxelRun<Vtaxel_reconstruct_x64, 64, 64>>();
  r->stream(frames, 0.9, 1.0, 0.3, 38);
  r->expect_bit_exact(frames);
}

// No gaps, no back-pressure, a static mask (sites_done held high): the
// frame's schedule to the clock.
template <class V, int R_MAX, int C_MAX>
void one_a_clock(int rows, int cols) {
  const auto frames = plain_frames<R_MAX, C_MAX>({{rows, cols}}, 4, 41, true, true);
  auto r = std::make_unique<TaxelRun<V, R_MAX, C_MAX>>();
  r->stream(frames, 1.0, 1.0, 1.0, 42, true);
  r->expect_bit_exact(frames);
  const size_t K = size_t(rows + cols), T = size_t(rows * cols);
  ASSERT_EQ(r->in_cycles.size(), K * frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    const uint64_t first_in = r->in_cycles[f * K], last_in = r->in_cycles[f * K + K - 1];
    EXPECT_EQ(last_in, first_in + K - 1) << "frame " << f << ": magnitudes not one a clock";
    const uint64_t first_out = r->out_cycles[f * T], last_out = r->out_cycles[f * T + T - 1];
    EXPECT_EQ(first_out, last_in + 25) << "frame " << f;
    EXPECT_EQ(last_out, first_out + T - 1) << "frame " << f << ": taxels not one a clock";
    if (f + 1 < frames.size()) {
      EXPECT_EQ(r->in_cycles[(f + 1) * K], last_out + 1) << "frame " << f;
      EXPECT_EQ(r->in_cycles[(f + 1) * K] - first_in, K + T + 24) << "frame period";
    }
  }
}

TEST(TaxelReconstructRtl, OneTaxelAClockLatency25) {
  one_a_clock<Vtaxel_reconstruct, 3, 3>(3, 3);
  one_a_clock<Vtaxel_reconstruct_x64, 64, 64>(64, 64);
}

// The taxel phase waits for sites_done: with the roots stored and the mask
// written, nothing comes out until the pulse; the first taxel 7 clocks
// after it.
TEST(TaxelReconstructRtl, TaxelsWaitForSitesDone) {
  ClockedDut<Vtaxel_reconstruct> d;
  auto& m = d.m;
  d.reset();
  m.mask_we = 0, m.sites_done = 0;
  m.cfg_rows = 3, m.cfg_cols = 3, m.cfg_recip = 26843, m.cfg_recip_shift = 14, m.cfg_ghost = 0, m.cfg_release = 0;
  m.out_ready = 1;
  for (int k = 0; k < 6; ++k) {
    m.in_valid = 1, m.in_k = uint8_t(k), m.in_mag = 20000, m.in_last = k == 5;
    m.eval();
    ASSERT_TRUE(m.in_ready);
    d.tick();
  }
  m.in_valid = 0;
  for (int c = 0; c < 200; ++c) {
    m.eval();
    ASSERT_FALSE(m.out_valid) << c;
    ASSERT_FALSE(m.in_ready) << c;
    d.tick();
  }
  m.sites_done = 1;
  d.tick();
  m.sites_done = 0;
  for (int c = 1; c < 7; ++c) {
    m.eval();
    ASSERT_FALSE(m.out_valid) << c;
    d.tick();
  }
  m.eval();
  ASSERT_TRUE(m.out_valid);
  // One full carrier on both lines: g = 32768 (1.0) up to the roots' floor.
  TaxelReconstruct<3, 3> tr;
  TaxelReconstructConfig c;
  c.recip = 26843, c.recip_shift = 14;
  ASSERT_TRUE(tr.configure(c));
  const uint16_t mag[6] = {20000, 20000, 20000, 20000, 20000, 20000};
  tr.lines(mag);
  EXPECT_EQ(m.out_g, tr.value(0, 0));
  EXPECT_NEAR(m.out_g, 32768, 40);
}

// A one-clock reset in the middle of a frame's taxels (output stalled)
// returns the block to taking magnitudes: nothing of that frame comes out
// after it, and the next frames are bit-exact.
TEST(TaxelReconstructRtl, ResetMidFrame) {
  auto r = std::make_unique<TaxelRun<Vtaxel_reconstruct, 3, 3>>();
  auto& d = r->d;
  auto& m = d.m;
  d.reset();
  m.mask_we = 0, m.sites_done = 1;
  m.cfg_rows = 3, m.cfg_cols = 3, m.cfg_recip = 26843, m.cfg_recip_shift = 14, m.cfg_ghost = 0, m.cfg_release = 0;
  for (int k = 0; k < 6; ++k) {
    m.in_valid = 1, m.in_k = uint8_t(k), m.in_mag = uint16_t(1000 * (k + 1)), m.in_last = k == 5;
    d.tick();
  }
  m.in_valid = 0;
  m.out_ready = 1;
  int taken = 0;
  for (int c = 0; c < 100 && taken < 4; ++c) {
    m.eval();
    taken += m.out_valid;
    d.tick();
  }
  ASSERT_EQ(taken, 4);
  m.out_ready = 0;
  d.tick();
  m.eval();
  ASSERT_TRUE(m.out_valid);
  ASSERT_FALSE(m.in_ready);
  m.rst = 1;
  d.tick();
  m.rst = 0;
  m.sites_done = 0;
  m.eval();
  EXPECT_FALSE(m.out_valid);
  EXPECT_TRUE(m.in_ready);
  const auto frames = ghost_frames<3, 3>(3, 3, 200, 51);
  r->stream(frames, 0.7, 0.5, 0.7, 52, false, false);
  r->expect_bit_exact(frames);
}

}  // namespace
