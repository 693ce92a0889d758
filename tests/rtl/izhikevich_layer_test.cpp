// rtl/izhikevich_layer.v against hls/izhikevich_layer.h, update by update.
//
// Bound: bit-exact (out_spike, out_v, out_u of every update; the next
// x_prev, x or x_prev by input_change, is the microcode's, and the tests
// here keep it as nu_layer does).
// Why exact: the RTL forms every C++ intermediate at a width that holds it
// (module header), rounds with the same rnd and saturates at the same
// points, so there is no tolerance to allow. Domain: any x, x_prev and any
// configuration in the ranges of neuron_params() (ucode/dtmf_engine_image.h);
// v in [-2^29 - 2^13, 2^29 - 2^13) and U in [-2^30, 2^30), the range where the
// C++ is free of int32 overflow (beyond it w^2 and m3 * vh overflow int32,
// undefined behaviour, so there is nothing to compare with). It contains
// the stored ranges (v in [V_MIN, V_PEAK), v_reset; U saturated), and
// Realistic checks that the outputs never leave them.
// Timing: every update asserts the 13-edge handshake (Unit::update), and
// that the outputs keep the previous update's results until then.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <unistd.h>

#include "Vizhikevich_layer.h"
#include "clocked_dut.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/engine_ports.h"
#include "hls/izhikevich_layer.h"
#include "hls/izhikevich_layer_config.h"

namespace {

using eskin::hls::IzhikevichConfig;
namespace izh = eskin::hls::izh;

// Edges from the handshake to the results: the clocks the top's C++ models
// count for an update (hls::IzhikevichUnitPort).
constexpr int kLatency = eskin::hls::kIzhikevichUnitClocks;
constexpr int32_t kVLo = -(int32_t(1) << 29) - (1 << 13);     // domain of v (see above)
constexpr int32_t kVHi = (int32_t(1) << 29) - (1 << 13);      // exclusive

// The layer's constant block as the engine's DMEM holds it
// (hls::neuron_block), words 2..16.
std::vector<std::pair<int, uint32_t>> config_words(const IzhikevichConfig& c) {
  const auto w = eskin::hls::neuron_block(c);
  std::vector<std::pair<int, uint32_t>> out;
  for (int i = 2; i <= 16; ++i) out.emplace_back(i, uint32_t(w[size_t(i)]));
  return out;
}

struct Operands {
  int32_t x = 0, x_prev = 0, v = 0, U = 0;
};
struct Result {
  bool spike = false;
  int32_t v = 0, U = 0;
  bool operator==(const Result& o) const {
    return spike == o.spike && v == o.v && U == o.U;
  }
};
std::ostream& operator<<(std::ostream& s, const Result& r) {
  return s << "{spike " << r.spike << ", v " << r.v << ", U " << r.U << "}";
}

// Golden for one neuron in an arbitrary state: IzhikevichLayer::update
// from that state (set_state), both input modes.
Result golden(const IzhikevichConfig& c, const Operands& o) {
  eskin::hls::IzhikevichLayer<1> one(c);
  one.set_state(0, o.v, o.U, o.x_prev);
  Result r;
  r.spike = one.update(0, o.x);
  r.v = one.v(0), r.U = one.U(0);
  return r;
}

// The unit has no out_ready, so ClockedDut's reset() does not fit: its own.
struct Unit : ClockedDut<Vizhikevich_layer> {
  Unit() { reset(); }
  void reset() {
    m.rst = 1, m.in_valid = 0, m.cfg_we = 0;
    tick();
    tick();
    m.rst = 0;
  }
  void write(int addr, uint32_t data) {
    m.cfg_we = 1, m.cfg_addr = uint8_t(addr), m.cfg_data = data;
    tick();
    m.cfg_we = 0;
  }
  void configure(const IzhikevichConfig& c) {
    for (const auto& [a, d] : config_words(c)) write(a, d);
  }
  void drive(const Operands& o) {
    m.in_x = uint32_t(o.x), m.in_x_prev = uint32_t(o.x_prev);
    m.in_v = uint32_t(o.v), m.in_u = uint32_t(o.U);
  }
  Result out() const {
    return Result{m.out_spike != 0, int32_t(m.out_v), int32_t(m.out_u)};
  }
  // One update; `during(k)` runs before edge E+k (k = 1..14) to test writes
  // while busy. Asserts the timing: idle before, busy (in_ready = 0,
  // out_valid = 0) right after edges E .. E+12, done right after E+13; and
  // that the previous results hold while busy (the microcode reads them
  // while the unit computes the next neuron).
  template <class F>
  Result update(const Operands& o, F during) {
    EXPECT_TRUE(m.in_ready && m.out_valid);
    const Result before = out();
    drive(o);
    m.in_valid = 1;
    tick();  // E
    m.in_valid = 0;
    for (int k = 1; k <= kLatency; ++k) {
      EXPECT_FALSE(m.in_ready) << "after edge E+" << k - 1;
      EXPECT_FALSE(m.out_valid) << "after edge E+" << k - 1;
      EXPECT_EQ(out(), before) << "the previous results, after edge E+" << k - 1;
      during(k);
      tick();
    }
    EXPECT_TRUE(m.in_ready && m.out_valid);
    return out();
  }
  Result update(const Operands& o) {
    return update(o, [](int) {});
  }
};

// A configuration drawn from the ranges of neuron_params(); shifts either
// anywhere in 0..40 or small (where products reach the saturations).
IzhikevichConfig random_config(std::mt19937& g, bool change) {
  auto uni = [&g](int64_t lo, int64_t hi) {
    return std::uniform_int_distribution<int64_t>(lo, hi)(g);
  };
  auto shift = [&](int hi) { return int(uni(0, 1) ? uni(0, hi) : uni(0, std::min(hi, 16))); };
  IzhikevichConfig c;
  c.v_init = 0, c.u_init = 0;  // not the unit's
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

// What the random cases reach (so that they cannot pass vacuously).
struct Reach {
  long spikes = 0, quiet = 0, v_floor = 0, u_hi = 0, u_lo = 0;
  void count(const Result& r) {
    r.spike ? ++spikes : ++quiet;
    v_floor += !r.spike && r.v == izh::kVMin;
    u_hi += r.U == izh::kUMax;
    u_lo += r.U == izh::kUMin;
  }
  void expect_all(long n) const {
    EXPECT_GT(spikes, n) << "spikes";
    EXPECT_GT(quiet, n) << "no spike";
    EXPECT_GT(v_floor, n) << "v clamped at V_MIN";
    EXPECT_GT(u_hi, n) << "U at its upper saturation";
    EXPECT_GT(u_lo, n) << "U at its lower saturation";
  }
};

// (1) Bound: exact. 40000 updates, a new random in-range configuration
// every 40, both input modes; x, x_prev uniform over all 32-bit values, U
// uniform over [-2^30, 2^30); v uniform over the whole domain half of the
// time, over the stored range [V_MIN, V_PEAK) otherwise.
TEST(IzhikevichLayerRtl, RandomOperandsAndConfigsMatchHls) {
  std::mt19937 g(20240611);
  Unit u;
  std::uniform_int_distribution<int32_t> any(INT32_MIN, INT32_MAX), uu(izh::kUMin, izh::kUMax);
  std::uniform_int_distribution<int32_t> vd(kVLo, kVHi - 1), vs(izh::kVMin, izh::kVPeak - 1);
  Reach reach;
  long bad = 0;
  for (int n = 0; n < 1000; ++n) {
    const IzhikevichConfig c = random_config(g, n % 2 == 1);
    u.configure(c);
    for (int i = 0; i < 40; ++i) {
      const Operands o{any(g), any(g), i % 2 ? vd(g) : vs(g), uu(g)};
      const Result want = golden(c, o), got = u.update(o);
      reach.count(want);
      if (!(got == want) && ++bad <= 5)
        ADD_FAILURE() << "config " << n << " x " << o.x << " x_prev " << o.x_prev << " v " << o.v
                      << " U " << o.U << ": got " << got << ", want " << want;
    }
  }
  EXPECT_EQ(bad, 0);
  reach.expect_all(500);
}

// (3) Bound: exact. Every field at its extremes, in random combinations:
// v at the domain ends, V_MIN, V_MIN - 1, V_PEAK - 1 and around 0; U at the
// saturation bounds; x, x_prev at INT32_MIN/MAX; each shift 0 or 40,
// gain_shift -15 or 40, u_frac 22 or 30, x_shift 0 or 16, mantissas at
// -32768, -1, 0, 1, 32767; v_reset, u_jump, c_const at their range ends.
TEST(IzhikevichLayerRtl, ExtremeOperandsAndConfigsMatchHls) {
  std::mt19937 g(7);
  auto pick = [&g](const auto& set) {
    return set[std::uniform_int_distribution<size_t>(0, set.size() - 1)(g)];
  };
  const std::array<int32_t, 9> vs = {kVLo,       kVHi - 1,         izh::kVMin, izh::kVMin - 1,
                                     izh::kVPeak - 1, izh::kVPeak, 0, -1, 1};
  const std::array<int32_t, 5> us = {izh::kUMin, izh::kUMax, 0, -1, 1};
  const std::array<int32_t, 6> xs = {INT32_MIN, INT32_MAX, 0, -1, 1, INT32_MIN + 1};
  const std::array<int16_t, 5> ms = {-32768, -1, 0, 1, 32767};
  const std::array<uint8_t, 2> sh = {0, 40};
  const std::array<int8_t, 2> gs = {-15, 40};
  const std::array<uint8_t, 2> fu = {22, 30}, xsh = {0, 16};
  const std::array<int32_t, 2> vr = {-(int32_t(1) << 29), (int32_t(30) << 22) - 1};
  const std::array<int32_t, 2> uj = {izh::kUMin, izh::kUMax}, cc = {-68157440, 0};
  Unit u;
  long bad = 0, spikes = 0, quiet = 0;
  for (int n = 0; n < 1500; ++n) {
    IzhikevichConfig c;
    c.v_reset = pick(vr), c.u_jump = pick(uj), c.u_frac = pick(fu), c.c_const = pick(cc);
    c.m2 = pick(ms), c.s2 = pick(sh), c.m3 = pick(ms), c.s3 = pick(sh);
    c.m4 = pick(ms), c.s4 = pick(sh), c.gain = pick(ms), c.gain_shift = pick(gs);
    c.x_shift = pick(xsh), c.input_change = n % 2 == 1;
    u.configure(c);
    for (int i = 0; i < 16; ++i) {
      const Operands o{pick(xs), pick(xs), pick(vs), pick(us)};
      const Result want = golden(c, o), got = u.update(o);
      want.spike ? ++spikes : ++quiet;
      if (!(got == want) && ++bad <= 5)
        ADD_FAILURE() << "config " << n << " x " << o.x << " x_prev " << o.x_prev << " v " << o.v
                      << " U " << o.U << ": got " << got << ", want " << want;
    }
  }
  EXPECT_EQ(bad, 0);
  EXPECT_GT(spikes, 1000);
  EXPECT_GT(quiet, 1000);
}

// (3b) Bound: exact, at the points where a rounding carry meets a
// saturation or truncation (random operands hit them with probability
// ~2^-16 or less): xs = sat16(rnd(x >> x_shift)) for x around +-2^(15 +
// x_shift), every x_shift, seen through J = xs (gain 1) in v; and c2w2 =
// int32(rnd(m2 sq >> s2)) where the rounded value is exactly 2^31 (wraps to
// INT32_MIN), found by scanning w for square_term() == INT32_MIN.
TEST(IzhikevichLayerRtl, RoundingCarriesAtSaturationAndWrapEdges) {
  Unit u;
  IzhikevichConfig c;
  c.gain = 1, c.gain_shift = 0, c.u_frac = 22, c.v_reset = 0;
  const int32_t v0 = -(int32_t(60) << izh::kFrac);
  long n = 0;
  for (int xsh = 0; xsh <= 16; ++xsh) {
    c.x_shift = uint8_t(xsh);
    u.configure(c);
    for (const int64_t k : {32766, 32767, 32768, -32767, -32768, -32769})
      for (int64_t d = -2; d <= 2; ++d)
        for (const int64_t half : {int64_t(0), xsh ? (int64_t(1) << (xsh - 1)) : 0}) {
          const int64_t x = (k << xsh) + d + half;
          if (x < INT32_MIN || x > INT32_MAX) continue;
          const Operands o{int32_t(x), 0, v0, 0};
          EXPECT_EQ(u.update(o), golden(c, o)) << "x_shift " << xsh << " x " << x;
          ++n;
        }
  }
  EXPECT_GT(n, 900);
  // m2 sq = 2^32 - 1 (s2 = 1: q = 2^31 - 1 with a rounding carry) and
  // m2 sq = 2^32 (q = 2^31): wh = 4104, 4096 and the wl that hit.
  long wraps = 0;
  for (const auto& [m2, wh] : {std::pair<int16_t, int32_t>{255, 4104}, {256, 4096}}) {
    c = IzhikevichConfig{};
    c.m2 = m2, c.s2 = 1, c.u_frac = 22, c.v_reset = 0;
    u.configure(c);
    for (int32_t wl = 0; wl < 32768; ++wl) {
      const int32_t v = (wh << 15) + wl - izh::kWOffset;
      if (izh::square_term(c, v) != INT32_MIN) continue;
      const Operands o{0, 0, v, 0};
      EXPECT_EQ(u.update(o), golden(c, o)) << "m2 " << m2 << " v " << v;
      ++wraps;
    }
  }
  EXPECT_GE(wraps, 2);
}

// (2) Bound: exact, and identical spike trains. One neuron of a realistic
// layer (make_izhikevich_config, 35 kHz steps) fed back its own state by the
// test, next to IzhikevichLayer<1> (the class itself, x_prev included), 1 s
// each: RS in level mode on a staircase input, RA in change mode on a random
// walk of presses with jumps over the whole int32 range. Every output also
// stays in the stored ranges (the domain is closed).
TEST(IzhikevichLayerRtl, RealisticNeuronSpikeTrainsMatchHls) {
  std::mt19937 g(3);
  for (const bool change : {false, true}) {
    SCOPED_TRACE(change ? "RA, rectified change" : "RS, level");
    auto cfg = eskin::hls::make_izhikevich_config(
        eskin::hls::izhikevich_fixed_preset(change ? "RA" : "RS"), 1.0 / 35.0, 1.0 / 1024, 1);
    cfg.input_change = change;
    eskin::hls::IzhikevichLayer<1> h(cfg);
    Unit u;
    u.configure(cfg);
    Operands o{0, 0, cfg.v_init, cfg.u_init};
    std::vector<long> want, got;
    int32_t x = 0;
    long bad = 0;
    for (long n = 0; n < 35000; ++n) {
      if (change) {  // presses: small steps, now and then a jump anywhere
        const int r = std::uniform_int_distribution<int>(0, 99)(g);
        x = r == 0 ? std::uniform_int_distribution<int32_t>(INT32_MIN, INT32_MAX)(g)
                   : r < 20 ? std::uniform_int_distribution<int32_t>(0, 60000)(g) : x;
      } else {  // 0, then 5, 10, 20 units of input for 11000 steps each (x: 1/1024 units)
        x = n < 2000 ? 0 : int32_t((5L << ((n - 2000) / 11000)) * 1024);
      }
      o.x = x;
      const Result r = u.update(o);
      if (h.update(0, x)) want.push_back(n);
      if (r.spike) got.push_back(n);
      const Result w{!want.empty() && want.back() == n, h.v(0), h.U(0)};
      if (!(r == w) && ++bad <= 5) ADD_FAILURE() << "step " << n << ": got " << r << ", want " << w;
      EXPECT_TRUE((r.v >= izh::kVMin && r.v < izh::kVPeak) || r.v == cfg.v_reset) << n;
      EXPECT_TRUE(r.U >= izh::kUMin && r.U <= izh::kUMax) << n;
      o.v = r.v, o.U = r.U, o.x_prev = change ? x : o.x_prev;  // as nu_layer keeps it
      EXPECT_EQ(o.x_prev, h.x_prev(0)) << n;
    }
    EXPECT_EQ(bad, 0);
    EXPECT_EQ(got, want);
    EXPECT_GT(want.size(), 20u);
  }
}

// (4) Bound: the handshake timing exactly (13 edges), asserted in every
// update() above; here: an in_valid held high while busy is not accepted
// (the results are those of the first operands, and the second operands
// are taken only after E+13, at E+14), and back-to-back updates run at one
// per 14 clocks, each with its own exact result.
TEST(IzhikevichLayerRtl, HandshakeTimingAndBackToBack) {
  std::mt19937 g(11);
  Unit u;
  const IzhikevichConfig c = random_config(g, true);
  u.configure(c);
  std::uniform_int_distribution<int32_t> any(INT32_MIN, INT32_MAX), uu(izh::kUMin, izh::kUMax);
  std::uniform_int_distribution<int32_t> vs(izh::kVMin, izh::kVPeak - 1);
  std::vector<Operands> ops;
  for (int i = 0; i < 50; ++i) ops.push_back(Operands{any(g), any(g), vs(g), uu(g)});
  // in_valid high throughout, the operands changing every clock while busy.
  size_t next = 0;
  uint64_t accepted_at = 0;
  Result shown = u.out();  // what the outputs hold: the last finished update's
  u.drive(ops[0]);
  u.m.in_valid = 1;
  while (next < ops.size()) {
    const bool accept = u.m.in_valid && u.m.in_ready;
    if (accept) u.drive(ops[next]);
    u.tick();
    if (accept) {
      if (next > 0) {
        EXPECT_EQ(u.cycle - accepted_at, uint64_t(kLatency + 1)) << next;
      }
      accepted_at = u.cycle;
      EXPECT_FALSE(u.m.in_ready);
      EXPECT_FALSE(u.m.out_valid);
      ++next;
    } else {
      u.drive(Operands{any(g), any(g), vs(g), uu(g)});  // ignored: busy
      const uint64_t k = u.cycle - accepted_at;
      EXPECT_EQ(u.m.out_valid != 0, k == uint64_t(kLatency)) << k;
      EXPECT_EQ(u.m.in_ready != 0, k == uint64_t(kLatency)) << k;
      if (k == uint64_t(kLatency)) {
        EXPECT_EQ(u.out(), golden(c, ops[next - 1])) << next - 1;
        shown = u.out();
      } else {
        EXPECT_EQ(u.out(), shown) << "busy with " << next - 1 << ": the previous results hold";
      }
    }
  }
  u.m.in_valid = 0;
  for (int k = 0; k < kLatency; ++k) u.tick();
  ASSERT_TRUE(u.m.out_valid);
  EXPECT_EQ(u.out(), golden(c, ops.back()));
  // Idle: the results hold, whatever the inputs do.
  const Result held = u.out();
  for (int k = 0; k < 20; ++k) {
    u.drive(Operands{any(g), any(g), vs(g), uu(g)});
    u.tick();
    EXPECT_EQ(u.out(), held);
    EXPECT_TRUE(u.m.in_ready && u.m.out_valid);
  }
}

// (5) Bound: exact. The unit reads its constants during an update, so the
// contract is: words are written between updates. Configuration B written
// word by word from the update's last edge (E+13, where the results are
// taken: the first word lands there) through the clocks after it does not
// change that update (result = golden with A); the next update uses B
// entirely. Forward order puts v_reset (word 2), read at that last edge,
// on the boundary; reversed order, input_change (word 16).
TEST(IzhikevichLayerRtl, ConfigWrittenBetweenUpdatesAppliesToTheNextUpdate) {
  std::mt19937 g(5);
  Unit u;
  std::uniform_int_distribution<int32_t> any(INT32_MIN, INT32_MAX), uu(izh::kUMin, izh::kUMax);
  std::uniform_int_distribution<int32_t> vs(izh::kVMin, izh::kVPeak - 1);
  long changed = 0, reset_on_boundary = 0;
  for (int n = 0; n < 400; ++n) {
    const IzhikevichConfig a = random_config(g, n % 2), b = random_config(g, n % 3 == 0);
    u.configure(a);
    auto wb = config_words(b);
    if (n % 2) std::reverse(wb.begin(), wb.end());
    const Operands o{any(g), any(g), vs(g), uu(g)};
    Result r = u.update(o, [&](int k) {
      if (k != kLatency) return;
      u.m.cfg_we = 1, u.m.cfg_addr = uint8_t(wb[0].first), u.m.cfg_data = wb[0].second;
    });
    u.m.cfg_we = 0;
    for (size_t w = 1; w < wb.size(); ++w) u.write(wb[w].first, wb[w].second);
    EXPECT_EQ(r, golden(a, o)) << n;
    reset_on_boundary += r.spike && n % 2 == 0 && a.v_reset != b.v_reset;
    const Operands o2{any(g), any(g), vs(g), uu(g)};
    r = u.update(o2);
    EXPECT_EQ(r, golden(b, o2)) << n;
    changed += !(golden(a, o2) == golden(b, o2));
  }
  EXPECT_GT(changed, 300);  // B's result differs from A's: the check can fail
  EXPECT_GT(reset_on_boundary, 10);  // v_reset, written at the last edge, was read there
}

// The C++ models' side of the same contract (hls::IzhikevichUnitPort): a
// constant word written in the clocks of an update (after the start's
// clock c, before c + kIzhikevichUnitClocks, when the results come) throws;
// from that clock on, the write lands at or after the unit's last edge,
// which the test above shows to be safe. A start in those clocks, and in
// clock c + kLatency itself, throws (the unit, not ready, would ignore it:
// its in_ready comes with the results, at edge E + kLatency, so the
// earliest start it takes is at the next edge); from c + kLatency + 1 on
// it starts the next update, kLatency + 1 clocks after the first as the
// handshake test's back-to-back updates.
TEST(IzhikevichLayerRtl, ModelRefusesConstantsAndStartsWhileBusy) {
  eskin::hls::IzhikevichUnitPort p;
  p.present = true;
  const uint16_t vreset = eskin::hls::kIoIzCfg + 2;
  EXPECT_NO_THROW(p.write(vreset, 5, 90));
  ASSERT_TRUE(p.write(eskin::hls::kIoIzGo, 0, 100));
  EXPECT_THROW(p.write(vreset, 5, 101), std::logic_error);
  EXPECT_THROW(p.write(vreset, 5, 100 + kLatency - 1), std::logic_error);
  EXPECT_NO_THROW(p.write(vreset, 5, 100 + kLatency));
  EXPECT_THROW(p.write(eskin::hls::kIoIzGo, 0, 101), std::logic_error);
  EXPECT_THROW(p.write(eskin::hls::kIoIzGo, 0, 100 + kLatency), std::logic_error);
  // rtl/dtmf_top.v registers the U write's start: it lands a clock later.
  EXPECT_THROW(p.write(eskin::hls::kIoIzUGo, 0, 100 + kLatency - 1), std::logic_error);
  EXPECT_NO_THROW(p.write(eskin::hls::kIoIzUGo, 0, 100 + kLatency));  // starts at 101 + kLatency
  EXPECT_THROW(p.write(eskin::hls::kIoIzGo, 0, 101 + 2 * kLatency), std::logic_error);
  EXPECT_NO_THROW(p.write(eskin::hls::kIoIzGo, 0, 102 + 2 * kLatency));
  // The U write's start carries no x_prev: refused for a change-input layer.
  EXPECT_NO_THROW(p.write(eskin::hls::kIoIzCfg + 16, 1, 200));
  EXPECT_THROW(p.write(eskin::hls::kIoIzUGo, 0, 300), std::logic_error);
  EXPECT_NO_THROW(p.write(eskin::hls::kIoIzGo, 0, 300));
}

// The RTL's side of the same contract (this build has --assert, as every
// top's): a constant word written during an update before its last clock,
// or in the handshake's clock, stops the simulation with the assertion's
// message. A write in the last clock is allowed: the test above writes
// there, with the assertion on, in every one of its updates.
TEST(IzhikevichLayerRtl, AssertionStopsConstantsWrittenWhileBusy) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  const auto write_at = [](int at) {
    dup2(2, 1);  // Verilator prints the assertion on stdout
    Unit u;
    u.update(Operands{}, [&](int k) {
      u.m.cfg_we = k == at;
      u.m.cfg_addr = 2;
      u.m.cfg_data = 5;
    });
  };
  EXPECT_DEATH(write_at(1), "izhikevich_layer: constant word 2 written while an update runs");
  EXPECT_DEATH(write_at(kLatency - 1), "izhikevich_layer: constant word 2 written while an update runs");
  const auto write_in_handshake = [] {
    dup2(2, 1);
    Unit u;
    u.m.in_valid = 1;
    u.m.cfg_we = 1, u.m.cfg_addr = 3, u.m.cfg_data = 5;
    u.tick();
  };
  EXPECT_DEATH(write_in_handshake(), "izhikevich_layer: constant word 3 written while an update runs");
}

// (6) Bound: the reset state exactly: out_valid 1, in_ready 1, outputs 0;
// also from the middle of an update, which is abandoned.
TEST(IzhikevichLayerRtl, ResetState) {
  std::mt19937 g(1);
  Unit u;
  auto check = [&u] {
    EXPECT_TRUE(u.m.out_valid);
    EXPECT_TRUE(u.m.in_ready);
    EXPECT_EQ(u.out(), Result{});
  };
  check();
  const IzhikevichConfig c = random_config(g, true);
  u.configure(c);
  const Operands o{123456789, -5, izh::kVPeak - 1, izh::kUMax};
  EXPECT_FALSE(u.update(o) == Result{});  // the outputs really move
  u.drive(o);
  u.m.in_valid = 1;
  u.tick();
  u.m.in_valid = 0;
  for (int k = 0; k < 5; ++k) u.tick();
  ASSERT_FALSE(u.m.out_valid);
  u.reset();
  check();
  for (int k = 0; k < 20; ++k) {
    u.tick();
    check();
  }
}

}  // namespace
