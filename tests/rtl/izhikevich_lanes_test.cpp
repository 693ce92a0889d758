// rtl/izhikevich_lanes.v against ucode/dtmf_engine_image.h (IzhikevichLanesPort,
// the C++ models' view of the lanes, whose neurons are
// hls/izhikevich_layer.h's IzhikevichLayer::update), clock for clock.
//
// Bound: exact, every clock. Each clock the same bus operation goes to both
// (an x write, an initialisation, the next neuron, a constant word), and
// the RTL's registered read of a random flag column (flag_q), its idle
// (the engine's kEvIzDone) and, once idle, its event count and every event
// must equal the port model's. Why exact: the RTL's arithmetic is the
// unchanged izhikevich_layer (bit-exact with the C++: its own test), and
// the lanes only store and sequence, so there is no tolerance to allow;
// the timing (write-back at c + 15, flags, events and idle from c + 16)
// is the model's spec, which the microcode's loops rely on. The flags are
// the strongest check of the state: a spike depends on v and U, so a
// lane writing back the wrong neuron, or a stale x_prev, shows within a
// few frames.
// Schedule: the microcode's (nu layer loop: starts 2 and 4 clocks apart;
// synapse_weights: every 6 to 8) and random gaps, each start at or after
// the clock its lane takes one (the model throws on an earlier one: the
// contract the microcode keeps).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "Vizhikevich_lanes.h"
#include "clocked_dut.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/engine_ports.h"
#include "hls/izhikevich_layer_config.h"

namespace {

using eskin::hls::IzhikevichLanesPort;
namespace hls = eskin::hls;

// The Verilated build's parameters (izhikevich_lanes_test.cmake).
constexpr int kLanes = 5, kColumns = 7, kRows = 4, kTaxels = kRows * kColumns;
constexpr int kIndexBits = 6;  // 2 T = 56 <= 64

struct Lanes : ClockedDut<Vizhikevich_lanes> {
  IzhikevichLanesPort port;
  std::mt19937 g{5};
  uint64_t checked_reads = 0, checked_events = 0, collisions = 0;

  Lanes() {
    port.configure(kLanes, 2 * kTaxels, kColumns);
    m.rst = 1;
    idle_bus();
    tick();
    tick();
    m.rst = 0;
  }
  void idle_bus() {
    m.cfg_we = m.idx_we = m.x_we = m.sv_we = m.su_we = 0;
    m.cfg_addr = 0;
    m.data = 0;
  }
  // One clock: `op` (the IO address of the write, 0 none) with `d`, the
  // reads compared. The model's clock index is `cycle` (reset's two edges
  // come first; the timing is relative).
  void clock(uint16_t op = 0, uint32_t d = 0) {
    idle_bus();
    m.data = d;
    if ((op & 0xFFE0) == hls::kIoIzCfg) m.cfg_we = 1, m.cfg_addr = op & 31;
    m.idx_we = op == hls::kIoIzN;
    m.x_we = op == hls::kIoIzXGo;
    m.sv_we = op == hls::kIoIzSV;
    m.su_we = op == hls::kIoIzSU;
    // The reads of this clock see the state before its write, which lands
    // at its end (the engine's `wait` never shares a clock with an `out`).
    const bool idle = port.events(cycle) != 0;
    const uint32_t a = uint32_t(g() % (1u << (kIndexBits + 1)));
    m.flag_addr = a;
    m.ev_addr = uint32_t(g() % (1u << kIndexBits));
    m.eval();
    expect(bool(m.idle) == idle, "idle");
    const uint32_t count = m.ev_count;  // the register the top's io_reg samples at this clock's end
    // A column holding a flag written back in this clock is undefined in
    // the block RAM (the model throws; the microcode never reads one): not
    // compared.
    uint32_t want_flags = 0;
    bool defined = true;
    try {
      port.read(uint16_t(hls::kIoIzFlag + a), want_flags, cycle);
    } catch (const std::logic_error&) {
      defined = false;
      ++collisions;
    }
    uint32_t want_count = 0, want_ev = 0;
    if (idle) {
      port.read(hls::kIoIzEvN, want_count, cycle);
      if (m.ev_addr < want_count) port.read(uint16_t(hls::kIoIzEv + m.ev_addr), want_ev, cycle);
    }
    if (op) port.write(op, d, cycle);
    const uint64_t at = cycle;
    tick();
    if (defined) {
      expect(uint32_t(m.flag_q) == want_flags,
             "flag column " + std::to_string(a) + " (" + std::to_string(m.flag_q) + ", the model " +
                 std::to_string(want_flags) + ")",
             at);
      ++checked_reads;
    }
    if (idle) {
      expect(count == want_count,
             "event count (" + std::to_string(count) + ", the model " + std::to_string(want_count) + ")",
             at);
      if (m.ev_addr < want_count)
        expect(uint32_t(m.ev_q) == want_ev, "event " + std::to_string(m.ev_addr), at);
    }
  }
  // A difference ends the test (thrown: the loops around it stop too).
  void expect(bool same, const std::string& what, uint64_t at = ~uint64_t(0)) const {
    if (!same)
      throw std::runtime_error(what + " differs from the port model in clock " +
                               std::to_string(at == ~uint64_t(0) ? cycle : at));
  }
  void wait_idle() {
    while (port.events(cycle) == 0) clock();
  }
  // Every event of the layer, read in turn once idle.
  void check_events() {
    wait_idle();
    uint32_t n = 0;
    port.read(hls::kIoIzEvN, n, cycle);
    for (uint32_t i = 0; i < n; ++i) {
      uint32_t want = 0;
      port.read(uint16_t(hls::kIoIzEv + i), want, cycle);
      idle_bus();
      m.ev_addr = i;
      tick();
      expect(uint32_t(m.ev_q) == want, "event " + std::to_string(i) + " of " + std::to_string(n));
      ++checked_events;
    }
  }
  void constants(const hls::IzhikevichConfig& c) {
    const auto w = hls::neuron_block(c);
    for (int i = 2; i <= 16; ++i) clock(uint16_t(hls::kIoIzCfg + i), uint32_t(w[size_t(i)]));
  }
  // Neurons first .. first + T - 1 with inputs x, started at gaps from
  // `gap` (the clock after each start it waits, at least, before the next).
  template <class Gap>
  void layer(int first, const std::vector<int32_t>& x, Gap gap) {
    clock(hls::kIoIzN, uint32_t(first));
    for (size_t i = 0; i < x.size(); ++i) {
      // The lane of this start must take it: the model knows when.
      const int lane = port.next_lane;
      while (cycle + 1 < port.lane_ready[size_t(lane)]) clock();
      clock(hls::kIoIzXGo, uint32_t(x[i]));
      for (int k = gap(i); k > 1; --k) clock();
    }
    check_events();
  }
};

TEST(IzhikevichLanesRtl, EqualThePortModelClockForClock) {
  Lanes l;
  std::mt19937 g(7);
  for (const bool change : {false, true}) {
    SCOPED_TRACE(change ? "RA, rectified change" : "RS, level");
    auto c0 = hls::make_izhikevich_config(hls::izhikevich_fixed_preset(change ? "RA" : "RS"),
                                          1.0, 1.0 / 64, 0);
    c0.input_change = change;
    auto c1 = hls::make_izhikevich_config(hls::izhikevich_fixed_preset("RS"), 1.0, 1.0 / 64, 0);
    // Initialisation of every neuron (the microcode's boot).
    l.clock(hls::kIoIzN, 0);
    for (int n = 0; n < 2 * kTaxels; ++n) {
      const auto& c = n < kTaxels ? c0 : c1;
      l.clock(hls::kIoIzSV, uint32_t(c.v_init));
      l.clock(hls::kIoIzSU, uint32_t(c.u_init));
    }
    for (int frame = 0; frame < 150; ++frame) {
      std::vector<int32_t> x0(kTaxels), x1(kTaxels);
      for (auto& v : x0) v = int32_t(g() % 4000);  // pressed or not: many spike
      for (auto& v : x1) v = int32_t(g() % 3000) - 500;
      l.constants(c0);
      l.layer(0, x0, [](size_t i) { return i % 2 == 0 ? 2 : 4; });  // the layer loop
      l.constants(c1);
      if (frame % 2)
        l.layer(kTaxels, x1, [&g](size_t) { return 6 + int(g() % 3); });  // synapse_weights
      else
        l.layer(kTaxels, x1, [&g](size_t) { return 1 + int(g() % 5); });  // random gaps
    }
  }
  EXPECT_GT(l.checked_events, 2000u);  // layers that spike, in both modes
  EXPECT_GT(l.checked_reads, 50000u);
  std::printf("%llu clocks, %llu flag columns and %llu events equal (%llu reads in a "
              "write-back clock not compared)\n",
              (unsigned long long)l.cycle, (unsigned long long)l.checked_reads,
              (unsigned long long)l.checked_events, (unsigned long long)l.collisions);
}

// The contract's edge, on the model (the microcode's tests run into it
// there): a lane's next start 13 clocks after its last throws, 14 is
// taken; a flag read in its write-back clock throws; the events before the
// layer is written back throw.
TEST(IzhikevichLanesRtl, PortModelRefusesWhatTheRtlCannotDo) {
  IzhikevichLanesPort p;
  p.configure(2, 8, 2);
  p.write(hls::kIoIzN, 0, 10);
  p.write(hls::kIoIzXGo, 100, 20);  // lane 0
  p.write(hls::kIoIzXGo, 100, 21);  // lane 1
  EXPECT_THROW(p.write(hls::kIoIzXGo, 100, 33), std::logic_error);  // lane 0 at 13
  IzhikevichLanesPort q = p;
  EXPECT_NO_THROW(q.write(hls::kIoIzXGo, 100, 34));
  uint32_t d = 0;
  EXPECT_THROW(p.read(uint16_t(hls::kIoIzFlag + 2), d, 20 + 15), std::logic_error);
  EXPECT_NO_THROW(p.read(uint16_t(hls::kIoIzFlag + 2), d, 20 + 14));
  EXPECT_THROW(p.read(hls::kIoIzEvN, d, 21 + 15), std::logic_error);
  EXPECT_NO_THROW(p.read(hls::kIoIzEvN, d, 21 + 16));
  EXPECT_THROW(p.write(hls::kIoIzCfg + 2, 0, 30), std::logic_error);  // constants while busy
}

}  // namespace
