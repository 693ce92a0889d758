// A valid/ready stream driver shared by the Hall decoding RTL tests: offers
// input tokens with random gaps, accepts outputs with random back-pressure,
// checks that a stalled output holds its data, and records each handshake's
// cycle. `Dut` is a ClockedDut<V> whose module has in_valid/in_ready and
// out_valid/out_ready.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "clocked_dut.h"

template <class V, class In, class Out>
struct HallStream {
  std::function<void(V&, const In&)> drive;   // set the input data ports
  std::function<Out(const V&)> read;          // read the output data ports
  std::function<bool(const Out&, const Out&)> same;
  std::function<void(V&)> every_cycle;        // optional: side inputs per cycle

  std::vector<Out> outs;
  std::vector<uint64_t> in_cycles, out_cycles;

  void run(ClockedDut<V>& d, const std::vector<In>& ins, double p_valid, double p_ready,
           uint64_t seed, uint64_t max_cycles = 50'000'000) {
    std::mt19937_64 rng(seed);
    std::bernoulli_distribution offer(p_valid), accept(p_ready);
    size_t next = 0;
    bool held = false;
    Out last{};
    uint64_t idle = 0;
    while ((next < ins.size() || d.m.out_valid || idle < 400) && d.cycle < max_cycles) {
      const bool give = next < ins.size() && offer(rng);
      d.m.in_valid = give;
      if (give) drive(d.m, ins[next]);
      d.m.out_ready = accept(rng);
      if (every_cycle) every_cycle(d.m);
      d.m.eval();
      const bool in_hs = give && d.m.in_ready;
      const bool out_v = d.m.out_valid;
      const bool out_hs = out_v && d.m.out_ready;
      if (out_v) {
        const Out o = read(d.m);
        if (held) {
          EXPECT_TRUE(same(o, last)) << "output changed while stalled, cycle " << d.cycle;
        }
        last = o;
        held = !out_hs;
        if (out_hs) outs.push_back(o), out_cycles.push_back(d.cycle);
      } else {
        EXPECT_FALSE(held) << "out_valid dropped while stalled, cycle " << d.cycle;
        held = false;
      }
      if (in_hs) in_cycles.push_back(d.cycle), ++next;
      idle = (next >= ins.size() && !out_v) ? idle + 1 : 0;
      d.tick();
    }
    d.m.in_valid = 0;
    ASSERT_EQ(next, ins.size()) << "inputs not all accepted in " << max_cycles << " cycles";
  }
};
