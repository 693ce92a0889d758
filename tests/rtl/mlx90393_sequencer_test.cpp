// rtl/mlx90393_sequencer.v + rtl/i2c_master.v (tests/rtl/mlx90393_sequencer_tb.v)
// on the simulated bus with MLX90393 models: sensors 0 and 2 share address
// 0x0C behind channels 0 and 1 of a TCA9548A, sensor 1 (0x0D) is direct. Every data token must equal what
// the device model sent, token for token; each fault of issue 9 is a test.
//
// Rates: in burst mode a round reads each sensor once when its DRDY rises.
// At 12 MHz / 400 kHz one RM transaction (START, 2 bytes, Sr, 8 bytes,
// STOP) takes about 93 bit times of 34 clocks = 0.26 ms, so a bus keeps up
// with 2053 us conversions for up to 7 sensors; with 3 sensors every sensor
// must deliver one token per 2053 us after the configuration round.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <vector>

#include "Vmlx90393_sequencer_tb.h"
#include "Vmlx90393_sequencer_tb_single.h"
#include "clocked_dut.h"
#include "sim/i2c_pin_bus.h"
#include "sim/mlx90393_model.h"
#include "sim/tca9548a_model.h"

namespace {

namespace mlx = eskin::mlx90393;
using eskin::sim::I2cPinBus;
using eskin::sim::Mlx90393Model;
using eskin::sim::Mlx90393Options;
using eskin::sim::Tca9548aModel;

constexpr double kClkNs = 1e9 / 12e6;
constexpr uint64_t kConvCyc = 24636;  // 2053 us at 12 MHz

enum Flag { SATX = 1, SATY = 2, SATZ = 4, MISSING = 8, ERROR = 16, REPLY = 32, BUS = 64,
            RECOVERED = 128 };

// Bx ramps, different per sensor, so every token is distinct.
struct RampField : eskin::sim::HallFieldSource {
  std::array<double, 3> extra{0, 0, 0};
  std::array<double, 3> field_uT(int sensor, double t_s) const override {
    return {20.0 * sensor + 3000.0 * t_s + extra[0], -40.0 + sensor + extra[1],
            100.0 + extra[2]};
  }
};

struct Token {
  uint8_t id, flags;
  uint32_t t;
  uint16_t x, y, z;
};

template <class V>
struct SeqBench {
  ClockedDut<V> d;
  I2cPinBus pins;
  RampField field;
  Tca9548aModel mux;
  std::vector<std::unique_ptr<Mlx90393Model>> dev;  // by sensor id; null = absent
  std::vector<Token> tokens;

  explicit SeqBench(std::vector<bool> present = {true, true, true})
      : mux(pins.bus, 0, 0, 0) {
    Mlx90393Options o0, o1, o2;
    o1.a0 = 1;  // 0x0D
    const int segs[3] = {mux.channel_segment(0), 0, mux.channel_segment(1)};
    const Mlx90393Options opts[3] = {o0, o1, o2};
    for (int k = 0; k < 3; ++k)
      dev.push_back(present[k] ? std::make_unique<Mlx90393Model>(pins.bus, field, k, opts[k],
                                                                 segs[k])
                               : nullptr);
    d.m.rst = 1;
    d.m.s_ready = 1;
    d.m.drdy = 0;
    step();
    step();
    d.m.rst = 0;
  }
  void step() {
    const double t = double(d.cycle) * kClkNs;
    bool scl, sda;
    pins.before(t, scl, sda);
    d.m.scl_i = scl;
    d.m.sda_i = sda;
    uint32_t drdy = 0;
    for (size_t k = 0; k < dev.size(); ++k)
      if (dev[k] && dev[k]->drdy()) drdy |= 1u << k;
    d.m.drdy = drdy;
    if (d.m.s_valid && d.m.s_ready)
      tokens.push_back({d.m.s_id, d.m.s_flags, d.m.s_t, d.m.s_x, d.m.s_y, d.m.s_z});
    d.tick();
    pins.after(t, d.m.scl_oe, d.m.sda_oe);
  }
  void run(uint64_t cycles) {
    for (uint64_t i = 0; i < cycles; ++i) step();
  }
  std::vector<Token> of(int id, bool data_only = true) const {
    std::vector<Token> r;
    for (const auto& t : tokens)
      if (t.id == id && (!data_only || (t.flags & 0x78) == 0)) r.push_back(t);
    return r;
  }
  // Every data token of sensor id equals what its model delivered, in order.
  // The model counts a reading when it executes RM; the token follows at the
  // end of that transaction, so one reading may still be in flight.
  void expect_tokens_equal_device(int id) const {
    const auto got = of(id);
    const auto& want = dev[id]->delivered();
    ASSERT_TRUE(got.size() == want.size() || got.size() + 1 == want.size())
        << "sensor " << id << ": " << got.size() << " tokens, " << want.size() << " readings";
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].x, want[i].x) << "sensor " << id << " token " << i;
      EXPECT_EQ(got[i].y, want[i].y) << "sensor " << id << " token " << i;
      EXPECT_EQ(got[i].z, want[i].z) << "sensor " << id << " token " << i;
    }
  }
};

TEST(Mlx90393Sequencer, BurstTokensEqualDeviceOutputsAtTheConversionRate) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.run(22 * kConvCyc);
  for (int k = 0; k < 3; ++k) b.expect_tokens_equal_device(k);
  for (const auto& v : b.pins.bus.violations()) ADD_FAILURE() << v;
  // Configuration round, then one token per sensor per conversion: after the
  // first data token, consecutive data tokens of a sensor are exactly one
  // conversion (24636 clocks) apart when read in the same position.
  for (int k = 0; k < 3; ++k) {
    const auto t = b.of(k);
    ASSERT_GE(t.size(), 19u) << k;
    for (size_t i = 2; i < t.size(); ++i)
      EXPECT_EQ(t[i].t - t[i - 1].t, kConvCyc) << "sensor " << k << " token " << i;
  }
  EXPECT_EQ(b.d.m.nacks, 0);
  EXPECT_EQ(b.d.m.status_errors, 0);
}

TEST(Mlx90393Sequencer, MissingSensorIsFlaggedOthersKeepStreaming) {
  SeqBench<Vmlx90393_sequencer_tb> b({true, false, true});
  b.run(12 * kConvCyc);
  const auto miss = b.of(1, false);
  ASSERT_GE(miss.size(), 10u);
  for (const auto& t : miss) EXPECT_TRUE(t.flags & MISSING);
  EXPECT_GE(b.d.m.nacks, 10);
  b.expect_tokens_equal_device(0);
  b.expect_tokens_equal_device(2);
  EXPECT_GE(b.of(0).size(), 10u);
  EXPECT_GE(b.of(2).size(), 10u);
  EXPECT_EQ(b.pins.bus.violation_count(), 0u);
}

TEST(Mlx90393Sequencer, SensorThatStopsAnsweringDoesNotStallTheOthers) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.run(6 * kConvCyc);
  b.dev[1]->set_absent(true);
  const size_t before0 = b.of(0).size();
  b.run(10 * kConvCyc);
  EXPECT_GE(b.of(0).size() - before0, 9u);  // still one per conversion
  const auto t1 = b.of(1, false);
  int missing = 0;
  for (const auto& t : t1) missing += (t.flags & MISSING) != 0;
  EXPECT_GE(missing, 8);
  b.expect_tokens_equal_device(0);
  b.expect_tokens_equal_device(2);
}

TEST(Mlx90393Sequencer, StatusErrorDropsTheSampleAndCounts) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.run(5 * kConvCyc);
  b.dev[2]->inject_status_error(2);
  b.run(5 * kConvCyc);
  int errors = 0;
  for (const auto& t : b.of(2, false)) errors += (t.flags & ERROR) != 0;
  EXPECT_EQ(errors, 2);
  EXPECT_EQ(b.d.m.status_errors, 2);
  b.expect_tokens_equal_device(2);  // the dropped ones were never delivered
}

TEST(Mlx90393Sequencer, UnexpectedByteCountIsReportedNotTrusted) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.run(5 * kConvCyc);
  b.dev[0]->inject_byte_count_error(1);
  b.run(3 * kConvCyc);
  int reply = 0;
  for (const auto& t : b.of(0, false))
    if (t.flags & REPLY && t.t > 5 * kConvCyc) {
      ++reply;
      EXPECT_EQ(t.x, 0);  // data not passed on
    }
  EXPECT_EQ(reply, 1);
  EXPECT_EQ(b.d.m.reply_errors, 1);
}

TEST(Mlx90393Sequencer, SaturationIsFlagged) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.field.extra = {20000.0, 0.0, -20000.0};  // beyond the RES 0 range
  b.run(5 * kConvCyc);
  const auto t = b.of(1);
  ASSERT_GE(t.size(), 3u);
  for (const auto& s : b.of(1, false))
    if ((s.flags & 0x78) == 0) {
      EXPECT_EQ(s.flags & 7, SATX | SATZ);
      EXPECT_EQ(s.x, 0x7FFF);
      EXPECT_EQ(s.z, 0x8000);
    }
  b.expect_tokens_equal_device(1);
}

TEST(Mlx90393Sequencer, SdaHeldLowIsRecoveredAndCounted) {
  SeqBench<Vmlx90393_sequencer_tb> b;
  b.run(5 * kConvCyc);
  // Wait until the bus has been idle for 200 clocks (the sequencer waits for
  // DRDY between readings) and make sensor 1 believe it is in the middle of
  // sending a 0x00 byte.
  for (int idle = 0; idle < 200; b.step())
    idle = (b.d.m.owned || b.d.m.scl_oe || !b.pins.bus.sda()) ? 0 : idle + 1;
  const int clamp = b.pins.bus.attach("clamp");
  const double t = double(b.d.cycle) * kClkNs;
  b.pins.bus.drive_scl(clamp, t, true);
  b.dev[1]->stick_in_read(t);
  b.pins.bus.drive_scl(clamp, t + 2000, false);
  b.run(5 * kConvCyc);
  EXPECT_EQ(b.d.m.recoveries, 1);
  int recovered = 0;
  for (const auto& s : b.tokens) recovered += (s.flags & RECOVERED) != 0;
  EXPECT_EQ(recovered, 1);
  for (int k = 0; k < 3; ++k) b.expect_tokens_equal_device(k);
  EXPECT_GE(b.of(0).size(), 8u);
}

TEST(Mlx90393Sequencer, SingleMeasurementModeWaitsTheComputedConversionTime) {
  SeqBench<Vmlx90393_sequencer_tb_single> b;
  b.run(12 * kConvCyc);
  for (int k = 0; k < 3; ++k) {
    b.expect_tokens_equal_device(k);
    EXPECT_GE(b.of(k).size(), 5u);
  }
  EXPECT_EQ(b.d.m.status_errors, 0);
  for (const auto& v : b.pins.bus.violations()) ADD_FAILURE() << v;
}

}  // namespace
