// rtl/byte_fifo.v, the frame engine's output queue: bytes come out in order
// through a valid/ready stream under random back-pressure (data stable
// while stalled), `free` is exactly DEPTH minus the bytes held in the RAM
// (the test keeps its own count: the one byte in the output register is
// not counted), and a byte written while full is dropped and counted
// without disturbing the queue. DEPTH 16 here (the top uses 512).
// The cycle level's C++ model (sim/cycle/byte_fifo.h) gives the same
// outputs as the RTL at every clock (bound: exact, it models the same
// registers).
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "Vbyte_fifo_small.h"
#include "clocked_dut.h"
#include "sim/cycle/byte_fifo.h"

namespace {

struct Bench : ClockedDut<Vbyte_fifo_small> {
  Bench() {
    m.in_valid = 0;
    m.out_ready = 0;
    reset();
  }
  void reset() {
    m.rst = 1;
    tick();
    tick();
    m.rst = 0;
  }
};

TEST(ByteFifo, OrderFreeCountAndOverflow) {
  Bench b;
  std::mt19937 rng(9);
  std::deque<uint8_t> want;  // bytes written and not yet read, in order
  bool out_reg = false;       // the output register holds a byte
  int overflows = 0;
  uint8_t next = 0;
  bool stalled = false;
  uint8_t held = 0;
  for (int cycle = 0; cycle < 20000; ++cycle) {
    // Bursts of writes, then of reads, so that the queue fills and empties.
    const bool write_phase = (cycle / 500) % 2 == 0;
    const bool wr = rng() % 100 < (write_phase ? 60 : 10);
    const bool rd = rng() % 100 < (write_phase ? 10 : 60);
    b.m.in_valid = wr;
    b.m.in_data = next;
    b.m.out_ready = rd;
    b.m.eval();
    if (stalled) {
      ASSERT_TRUE(b.m.out_valid);
      ASSERT_EQ(b.m.out_data, held) << "data changed while stalled";
    }
    // free counts RAM bytes only: the queue minus the byte in the output register.
    const int in_ram = int(want.size()) - (out_reg ? 1 : 0);
    ASSERT_EQ(b.m.free, 16 - in_ram) << "cycle " << cycle;
    if (b.m.out_valid && rd) {
      ASSERT_FALSE(want.empty());
      ASSERT_EQ(b.m.out_data, want.front());
      want.pop_front();
    }
    if (wr) {
      if (in_ram == 16) ++overflows;
      else want.push_back(next++);
    }
    stalled = b.m.out_valid && !rd;
    held = b.m.out_data;
    b.tick();
    out_reg = b.m.out_valid;
  }
  EXPECT_GT(overflows, 10);
  EXPECT_EQ(b.m.overflows, overflows);
}

TEST(ByteFifo, CycleModelEqualsTheRtlEveryClock) {
  Bench b;
  eskin::cycle::ByteFifo model(16);
  model.reset();
  std::mt19937 rng(11);
  long compared = 0;
  for (int cycle = 0; cycle < 20000; ++cycle) {
    const bool write_phase = (cycle / 300) % 2 == 0;
    const bool wr = rng() % 100 < (write_phase ? 70 : 15);
    const bool rd = rng() % 100 < (write_phase ? 15 : 70);
    const uint8_t d = uint8_t(rng());
    b.m.in_valid = wr;
    b.m.in_data = d;
    b.m.out_ready = rd;
    b.m.eval();
    ASSERT_EQ(bool(b.m.out_valid), model.out_valid()) << "cycle " << cycle;
    if (model.out_valid()) {
      ASSERT_EQ(b.m.out_data, model.out_data()) << "cycle " << cycle;
    }
    ASSERT_EQ(b.m.free, model.free()) << "cycle " << cycle;
    ASSERT_EQ(b.m.overflows, model.overflows()) << "cycle " << cycle;
    compared += model.out_valid() && rd;
    model.clock(wr, d, rd);
    b.tick();
  }
  EXPECT_GT(model.overflows(), 10) << "the drive must fill the FIFO";
  EXPECT_GT(compared, 3000) << "the drive must read thousands of bytes through";
}

}  // namespace
