// rtl/synapse_weights.v against hls/synapse_weights.h (SynapseWeights::input),
// output for output, at the 3x3 default (Vsynapse_weights) and at 64x64
// (Vsynapse_weights_64, synapse_weights_test.cmake).
//
// Bound: exact. The block's sum is exact integer arithmetic (no rounding,
// no saturation), so every out_x must equal the kernel's input(i, j) for
// the frame's flags, and out_last must mark exactly each frame's last
// taxel. Checked:
//   - random flag frames (empty, full, sparse, dense) with random in_valid
//     and out_ready (seeded), extreme weights included; out_x and out_last
//     hold while the output stalls;
//   - edges by a hand rule independent of the kernel: one spike at (a, b)
//     gives x_ij = W[a-i+1][b-j+1] inside its 3x3 neighbourhood, 0 outside,
//     at every position of the grid (the first and last row and column);
//   - timing with out_ready high: output o is on out_valid exactly 3 edges
//     after the handshake edge of the last input it needs, d(o) = (min(i+1,
//     R-1), min(j+1, C-1)), or one edge after output o - 1 if later; with
//     in_valid high too, in_ready never drops and the outputs of many frames
//     come one a clock without a gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "Vsynapse_weights.h"
#include "Vsynapse_weights_64.h"
#include "clocked_dut.h"
#include "hls/synapse_weights.h"

namespace {

namespace hls = eskin::hls;
using Weights = std::array<int16_t, 9>;
using Frame = std::vector<uint8_t>;  // row-major flags

template <class V, int R, int C>
struct Bench : ClockedDut<V> {
  static constexpr int kR = R, kC = C, kT = R * C;
  using ClockedDut<V>::m;
  using ClockedDut<V>::cycle;
  using ClockedDut<V>::tick;

  Weights w{};
  hls::SynapseWeights<R, C> kernel;
  std::mt19937 rng;
  double p_in = 1.0, p_out = 1.0;  // chance of in_valid / out_ready per clock

  // Per output, in stream order over all frames.
  std::vector<int32_t> expect;
  std::vector<bool> expect_last;
  std::vector<uint64_t> in_edge;   // per input: the edge it was taken at
  std::vector<uint64_t> out_edge;  // per output: the edge after which it showed
  std::vector<int32_t> got;
  std::vector<bool> got_last;
  std::vector<uint8_t> inputs;     // every flag, stream order
  bool ready_dropped = false;      // in_ready low while in_valid was offered

  explicit Bench(const Weights& weights, uint32_t seed) : w(weights), rng(seed) {
    hls::SynapseWeightsConfig c;
    c.rows = R;
    c.cols = C;
    std::copy(w.begin(), w.end(), c.w);
    EXPECT_TRUE(kernel.configure(c));
    for (int k = 0; k < 9; ++k) {
      const uint32_t v = uint16_t(w[k]);
      const int bit = 16 * k;
      m.w[bit / 32] = (m.w[bit / 32] & ~(0xFFFFu << (bit % 32))) | (v << (bit % 32));
    }
    this->reset();
  }

  void add_frame(const Frame& f) {
    bool s[kT];
    for (int i = 0; i < kT; ++i) s[i] = f[i] != 0;
    for (int i = 0; i < kT; ++i) {
      expect.push_back(kernel.input(s, i / C, i % C));
      expect_last.push_back(i == kT - 1);
    }
    inputs.insert(inputs.end(), f.begin(), f.end());
  }

  bool coin(double p) { return p >= 1.0 || std::uniform_real_distribution<double>(0, 1)(rng) < p; }

  // Runs until every output came (or a deadline in clocks passes).
  void run() {
    size_t next_in = 0;
    bool held = false;  // an output was stalled last clock: it must hold
    int32_t held_x = 0;
    bool held_last = false, shown = false;
    const uint64_t deadline = cycle + 40 * inputs.size() + 1000;
    while (got.size() < expect.size() && cycle < deadline) {
      m.in_valid = next_in < inputs.size() && coin(p_in);
      m.in_flag = m.in_valid ? inputs[next_in] : 0;
      m.out_ready = coin(p_out);
      m.eval();
      if (m.in_valid && !m.in_ready) ready_dropped = true;
      if (held) {
        EXPECT_TRUE(m.out_valid) << "output withdrawn while stalled, output " << got.size();
        EXPECT_EQ(int32_t(m.out_x << 12) >> 12, held_x) << "out_x changed while stalled";
        EXPECT_EQ(bool(m.out_last), held_last) << "out_last changed while stalled";
      }
      const bool in_take = m.in_valid && m.in_ready;
      const bool out_take = m.out_valid && m.out_ready;
      if (m.out_valid && !shown) out_edge.push_back(cycle), shown = true;
      if (out_take) {
        got.push_back(int32_t(m.out_x << 12) >> 12);  // 20-bit two's complement
        got_last.push_back(m.out_last);
        shown = false;
      }
      held = m.out_valid && !m.out_ready;
      held_x = int32_t(m.out_x << 12) >> 12;
      held_last = m.out_last;
      tick();
      if (in_take) in_edge.push_back(cycle), ++next_in;
    }
  }

  void check_values() {
    ASSERT_EQ(got.size(), expect.size()) << "outputs missing (deadline)";
    for (size_t o = 0; o < expect.size(); ++o) {
      ASSERT_EQ(got[o], expect[o]) << "output " << o << ": frame " << o / kT << ", taxel ("
                                   << (o % kT) / C << ", " << o % C << ")";
      ASSERT_EQ(got_last[o], expect_last[o]) << "out_last of output " << o;
    }
  }

  // The input output o waits for: d(o) in stream order.
  static size_t needs(size_t o) {
    const size_t f = o / kT;
    const int i = int(o % kT) / C, j = int(o % kT) % C;
    return f * kT + size_t(std::min(i + 1, R - 1)) * C + size_t(std::min(j + 1, C - 1));
  }
};

using B3 = Bench<Vsynapse_weights, 3, 3>;
using B64 = Bench<Vsynapse_weights_64, 64, 64>;

Frame random_frame(int t, double p, std::mt19937& rng) {
  Frame f(size_t(t), 0);
  std::bernoulli_distribution b(p);
  for (auto& x : f) x = b(rng);
  return f;
}

Weights random_weights(std::mt19937& rng) {
  Weights w;
  for (auto& x : w) x = int16_t(rng());
  return w;
}

// The default centre-surround (scenes' default: centre +, neighbours -) and
// the extremes, whose nine-term sums need all 20 bits.
const Weights kCentreSurround = {-1024, -1024, -1024, -1024, 8192, -1024, -1024, -1024, -1024};
const Weights kAllMin = {-32768, -32768, -32768, -32768, -32768, -32768, -32768, -32768, -32768};
const Weights kAllMax = {32767, 32767, 32767, 32767, 32767, 32767, 32767, 32767, 32767};

template <class B>
void random_stream(uint32_t seed, int frames, double p_in, double p_out) {
  std::mt19937 rng(seed);
  for (const Weights& w : {random_weights(rng), kCentreSurround, kAllMin, kAllMax}) {
    B b(w, seed);
    b.p_in = p_in;
    b.p_out = p_out;
    for (int f = 0; f < frames; ++f) {
      const double p = f % 4 == 0 ? 0.0 : f % 4 == 1 ? 1.0 : f % 4 == 2 ? 0.1 : 0.6;
      b.add_frame(random_frame(B::kT, p, rng));
    }
    b.run();
    b.check_values();
  }
}

TEST(SynapseWeights, Default3x3BitExactUnderRandomValidAndBackPressure) {
  random_stream<B3>(1, 200, 0.6, 0.5);
  random_stream<B3>(2, 200, 0.9, 0.2);
  random_stream<B3>(3, 200, 0.2, 0.9);
}

TEST(SynapseWeights, Skin64x64BitExactUnderRandomValidAndBackPressure) {
  random_stream<B64>(4, 6, 0.6, 0.5);
  random_stream<B64>(5, 6, 0.95, 0.3);
}

// One spike at each position: the weights land where the hand rule says.
template <class B>
void single_spikes(const std::vector<int>& positions) {
  std::mt19937 rng(7);
  const Weights w = random_weights(rng);
  B b(w, 8);
  b.p_in = 0.7;
  b.p_out = 0.7;
  for (int p : positions) {
    Frame f(size_t(B::kT), 0);
    f[size_t(p)] = 1;
    b.add_frame(f);
  }
  b.run();
  b.check_values();
  ASSERT_EQ(b.got.size(), positions.size() * B::kT);
  for (size_t n = 0; n < positions.size(); ++n) {
    const int a = positions[n] / B::kC, c = positions[n] % B::kC;
    for (int i = 0; i < B::kR; ++i)
      for (int j = 0; j < B::kC; ++j) {
        const int di = a - i, dj = c - j;
        const int32_t want =
            (std::abs(di) <= 1 && std::abs(dj) <= 1) ? w[size_t((di + 1) * 3 + dj + 1)] : 0;
        ASSERT_EQ(b.got[n * B::kT + size_t(i * B::kC + j)], want)
            << "spike at (" << a << ", " << c << "), taxel (" << i << ", " << j << ")";
      }
  }
}

TEST(SynapseWeights, Default3x3EverySingleSpikeByHandRule) {
  std::vector<int> all(9);
  for (int i = 0; i < 9; ++i) all[size_t(i)] = i;
  single_spikes<B3>(all);
}

TEST(SynapseWeights, Skin64x64EdgeAndCornerSpikesByHandRule) {
  std::vector<int> pos;
  for (int r : {0, 1, 31, 62, 63})
    for (int c : {0, 1, 40, 62, 63}) pos.push_back(r * 64 + c);
  single_spikes<B64>(pos);
}

// Exact timing with out_ready high: output o shows max(in_edge[d(o)] + 3,
// out_edge[o - 1] + 1).
template <class B>
void exact_latency(double p_in, int frames, bool expect_full_rate) {
  std::mt19937 rng(9);
  B b(random_weights(rng), 10);
  b.p_in = p_in;
  b.p_out = 1.0;
  for (int f = 0; f < frames; ++f) b.add_frame(random_frame(B::kT, 0.3, rng));
  b.run();
  b.check_values();
  ASSERT_EQ(b.out_edge.size(), b.expect.size());
  for (size_t o = 0; o < b.out_edge.size(); ++o) {
    uint64_t want = b.in_edge[B::needs(o)] + 3;
    if (o > 0) want = std::max(want, b.out_edge[o - 1] + 1);
    ASSERT_EQ(b.out_edge[o], want) << "output " << o;
  }
  if (expect_full_rate) {
    EXPECT_FALSE(b.ready_dropped) << "in_ready dropped with the output never stalled";
    // One element a clock: the inputs on consecutive edges, the outputs too.
    for (size_t n = 1; n < b.in_edge.size(); ++n)
      ASSERT_EQ(b.in_edge[n], b.in_edge[0] + n) << "input " << n;
    for (size_t o = 1; o < b.out_edge.size(); ++o)
      ASSERT_EQ(b.out_edge[o], b.out_edge[0] + o) << "output " << o;
    // The first output: 3 edges after input (1, 1) (3x3: C + 1 = 4 inputs in).
    EXPECT_EQ(b.out_edge[0], b.in_edge[size_t(B::kC + 1)] + 3);
  }
}

TEST(SynapseWeights, Default3x3ExactLatencyOneElementPerClock) {
  exact_latency<B3>(1.0, 300, true);
  exact_latency<B3>(0.5, 300, false);
}

TEST(SynapseWeights, Skin64x64ExactLatencyOneElementPerClock) {
  exact_latency<B64>(1.0, 4, true);
  exact_latency<B64>(0.5, 2, false);
}

}  // namespace
