// rtl/izhikevich_pipe.v against hls/izhikevich_layer.h, update by update:
// the block keeps a layer's state, and each of its outputs must equal
// IzhikevichLayer<N>::update(n, x) applied in input order (spike, v, U),
// at N = 9 (the 3x3 skin; fewer neurons than stages: every frame updates
// neurons still in flight) and N = 4096 (64x64).
//
// Bound: exact (no tolerance: the block forms every C++ intermediate at a
// width that holds it, rounds and saturates at the same points). Inputs:
// random configurations over the ranges of neuron_params() (as
// tests/rtl/izhikevich_layer_test.cpp draws them), both input modes; x over
// all 32-bit values, over the taxel range (0..65535) and over the synapse's
// (|x| < 2^19); neuron order row-major frame after frame (the chain's) and
// random (repeats back to back included); random input gaps and output
// back-pressure. The state starts from init (v_init, u_init, x_prev 0)
// and evolves only through updates, so every operand is a stored state.
// Timing: with nothing stalled an update taken at edge E is out after edge
// E + 7, one a clock; init takes N clocks.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <vector>

#include "Vizhikevich_pipe.h"
#include "Vizhikevich_pipe_4096.h"
#include "clocked_dut.h"
#include "hls/izhikevich_layer.h"
#include "ucode/dtmf_engine_image.h"

namespace {

using eskin::hls::IzhikevichConfig;
namespace izh = eskin::hls::izh;

IzhikevichConfig random_config(std::mt19937& g, bool change) {
  auto uni = [&g](int64_t lo, int64_t hi) {
    return std::uniform_int_distribution<int64_t>(lo, hi)(g);
  };
  auto shift = [&](int hi) { return int(uni(0, 1) ? uni(0, hi) : uni(0, std::min(hi, 16))); };
  IzhikevichConfig c;
  c.v_init = int32_t(uni(izh::kVMin, izh::kVPeak - 1));
  c.u_init = int32_t(uni(izh::kUMin, izh::kUMax));
  c.v_reset = int32_t(uni(-(int64_t(1) << 29), (int64_t(30) << 22) - 1));
  c.u_jump = int32_t(uni(izh::kUMin, izh::kUMax));
  c.u_frac = uint8_t(uni(22, 30));
  c.c_const = int32_t(uni(-68157440, 0));
  c.m2 = int16_t(uni(-32768, 32767)), c.s2 = uint8_t(shift(40));
  c.m3 = int16_t(uni(-32768, 32767)), c.s3 = uint8_t(shift(40));
  c.m4 = int16_t(uni(-32768, 32767)), c.s4 = uint8_t(shift(40));
  c.gain = int16_t(uni(-32768, 32767));
  c.gain_shift = int8_t(uni(0, 1) ? uni(-15, 40) : uni(-15, 2));
  c.x_shift = uint8_t(uni(0, 16));
  c.input_change = change;
  return c;
}

template <class V, int N>
struct Pipe : ClockedDut<V> {
  using ClockedDut<V>::m;
  using ClockedDut<V>::cycle;
  using ClockedDut<V>::tick;
  std::mt19937 rng;
  explicit Pipe(uint32_t seed) : rng(seed) {
    m.cfg_we = 0;
    m.init = 0;
    this->reset();
  }
  bool coin(double p) { return p >= 1.0 || std::uniform_real_distribution<double>(0, 1)(rng) < p; }
  void configure(const IzhikevichConfig& c) {
    const auto w = eskin::hls::neuron_block(c);
    for (int a = 0; a <= 16; ++a) {
      m.cfg_we = 1, m.cfg_addr = uint8_t(a), m.cfg_data = uint32_t(w[size_t(a)]);
      tick();
    }
    m.cfg_we = 0;
  }
  // init; returns the clocks busy is high for (one write each).
  uint64_t init() {
    m.init = 1;
    tick();
    m.init = 0;
    const uint64_t start = cycle;
    while (m.busy && cycle < start + N + 10) tick();
    return cycle - start;
  }

  struct In {
    int n;
    int32_t x;
  };
  struct Out {
    int n;
    bool spike;
    int32_t v, U;
  };
  // Runs the inputs through; returns the outputs and each one's edge, and
  // the edge of each input's handshake.
  void run(const std::vector<In>& ins, double p_in, double p_out, std::vector<Out>& outs,
           std::vector<uint64_t>& in_edge, std::vector<uint64_t>& out_edge) {
    size_t i = 0;
    const uint64_t deadline = cycle + 20 * ins.size() + 100;
    while (outs.size() < ins.size() && cycle < deadline) {
      m.in_valid = i < ins.size() && coin(p_in);
      if (m.in_valid) {
        m.in_n = uint32_t(ins[i].n);
        m.in_x = uint32_t(ins[i].x);
        m.in_last = i + 1 == ins.size();
      }
      m.out_ready = coin(p_out);
      m.clk = 0;
      m.eval();
      const bool take = m.in_valid && m.in_ready;
      const bool give = m.out_valid && m.out_ready;
      Out o{int(m.out_n), m.out_spike != 0, int32_t(m.out_v), int32_t(m.out_u)};
      tick();
      if (take) ++i, in_edge.push_back(cycle);
      if (give) outs.push_back(o), out_edge.push_back(cycle - 1);
    }
    m.in_valid = 0;
    ASSERT_EQ(outs.size(), ins.size()) << "the block did not finish";
  }
};

struct Reach {
  long spikes = 0, quiet = 0, v_floor = 0, u_sat = 0, repeats = 0;
};

template <class V, int N>
void random_run(uint32_t seed, int configs, int per_config, bool row_major, double p_in, double p_out,
                Reach& reach) {
  std::mt19937 g(seed);
  auto p = std::make_unique<Pipe<V, N>>(seed + 1);
  for (int c = 0; c < configs; ++c) {
    const IzhikevichConfig cfg = random_config(g, c % 2 == 1);
    p->configure(cfg);
    ASSERT_EQ(p->init(), uint64_t(N)) << "init clocks";
    auto layer = std::make_unique<eskin::hls::IzhikevichLayer<N>>(cfg);
    std::vector<typename Pipe<V, N>::In> ins;
    const int range = c % 3;  // x: any, taxel, synapse
    for (int k = 0; k < per_config; ++k) {
      int n = row_major ? k % N : int(g() % N);
      if (!row_major && !ins.empty() && g() % 4 == 0) n = ins.back().n, ++reach.repeats;
      int32_t x = range == 0 ? int32_t(g()) : range == 1 ? int32_t(g() % 65536)
                                                        : int32_t(g() % (1 << 20)) - (1 << 19);
      ins.push_back({n, x});
    }
    std::vector<typename Pipe<V, N>::Out> outs;
    std::vector<uint64_t> ie, oe;
    p->run(ins, p_in, p_out, outs, ie, oe);
    for (size_t k = 0; k < ins.size(); ++k) {
      eskin::hls::IzhikevichOut want;
      layer->update(ins[k].n, ins[k].x, &want);
      ASSERT_EQ(outs[k].n, ins[k].n) << "config " << c << " update " << k;
      ASSERT_EQ(outs[k].spike, want.spike) << "config " << c << " update " << k;
      ASSERT_EQ(outs[k].v, want.v) << "config " << c << " update " << k;
      ASSERT_EQ(outs[k].U, want.U) << "config " << c << " update " << k;
      want.spike ? ++reach.spikes : ++reach.quiet;
      reach.v_floor += !want.spike && want.v == izh::kVMin;
      reach.u_sat += want.U == izh::kUMax || want.U == izh::kUMin;
    }
  }
}

TEST(IzhikevichPipe, N9RowMajorAndRandomOrderMatchHls) {
  Reach r;
  random_run<Vizhikevich_pipe, 9>(1, 40, 400, true, 0.7, 0.6, r);
  random_run<Vizhikevich_pipe, 9>(2, 40, 400, false, 0.8, 0.5, r);
  random_run<Vizhikevich_pipe, 9>(3, 20, 400, true, 1.0, 1.0, r);
  EXPECT_GT(r.spikes, 100);
  EXPECT_GT(r.quiet, 100);
  EXPECT_GT(r.v_floor, 10);
  EXPECT_GT(r.u_sat, 10);
  EXPECT_GT(r.repeats, 100);
}

TEST(IzhikevichPipe, N4096MatchesHls) {
  Reach r;
  random_run<Vizhikevich_pipe_4096, 4096>(4, 6, 3 * 4096, true, 0.8, 0.7, r);
  random_run<Vizhikevich_pipe_4096, 4096>(5, 6, 4096, false, 0.9, 0.9, r);
  EXPECT_GT(r.spikes, 100);
  EXPECT_GT(r.quiet, 100);
}

// Nothing stalled: out 7 edges after the handshake, one a clock (N = 4096,
// no neuron repeats within the pipeline).
TEST(IzhikevichPipe, LatencySevenOneAClock) {
  std::mt19937 g(6);
  auto p = std::make_unique<Pipe<Vizhikevich_pipe_4096, 4096>>(7);
  p->configure(random_config(g, false));
  p->init();
  std::vector<Pipe<Vizhikevich_pipe_4096, 4096>::In> ins;
  for (int k = 0; k < 300; ++k) ins.push_back({k, int32_t(g())});
  std::vector<Pipe<Vizhikevich_pipe_4096, 4096>::Out> outs;
  std::vector<uint64_t> ie, oe;
  p->run(ins, 1.0, 1.0, outs, ie, oe);
  for (size_t k = 0; k < ins.size(); ++k) {
    ASSERT_EQ(oe[k], ie[k] + 7) << "update " << k;
    if (k > 0) {
      ASSERT_EQ(ie[k], ie[k - 1] + 1) << "update " << k;
    }
  }
}

}  // namespace
