// TCA9548A: channel register, selection effective only after STOP, devices
// with the same address behind different channels and muxes.
#include "sim/tca9548a_model.h"

#include <gtest/gtest.h>

#include "i2c_soft_master.h"
#include "sim/mlx90393_model.h"

namespace eskin::sim {
namespace {

namespace mlx = eskin::mlx90393;
using testing::SoftMaster;

struct SensorField : HallFieldSource {
  std::array<double, 3> field_uT(int sensor, double) const override {
    return {15.0 * (sensor + 1), 0, 0};  // sensor k reads Bx = 100 (k + 1) LSB
  }
};

TEST(Tca9548aModel, SelectionTakesEffectAfterStop) {
  I2cBus bus;
  SensorField field;
  Tca9548aModel mux0(bus, 0, 0, 0), mux1(bus, 0, 0, 1);
  EXPECT_EQ(mux0.address(), 0x70);
  EXPECT_EQ(mux1.address(), 0x71);
  // Two sensors with the same address 0x0C: behind mux0 ch 2 and mux1 ch 5.
  Mlx90393Model s0(bus, field, 0, {}, mux0.channel_segment(2));
  Mlx90393Model s1(bus, field, 1, {}, mux1.channel_segment(5));
  SoftMaster m(bus);
  std::vector<uint8_t> r;
  EXPECT_FALSE(m.command(0x0C, {mlx::kNOP}, 1, r));  // nothing selected

  // Select ch 2, then a repeated START to the sensor: not yet connected.
  ASSERT_TRUE(m.write_bytes(0x70, {0x04}, false));
  m.repeated_start();
  EXPECT_FALSE(m.write(0x0C << 1));
  m.stop();
  EXPECT_EQ(mux0.control(), 0x04);  // applied at that STOP
  ASSERT_TRUE(m.command(0x0C, {mlx::kSM | mlx::kX}, 1, r));
  m.wait(2e6);
  ASSERT_TRUE(m.command(0x0C, {mlx::kRM | mlx::kX}, 3, r));
  EXPECT_EQ(int(r[1] << 8 | r[2]), 100);  // sensor 0

  // Read the control register back.
  m.start();
  ASSERT_TRUE(m.write(0x70 << 1 | 1));
  EXPECT_EQ(m.read(false), 0x04);
  m.stop();

  // Switch to mux1 ch 5 only.
  ASSERT_TRUE(m.write_bytes(0x70, {0x00}));
  ASSERT_TRUE(m.write_bytes(0x71, {0x20}));
  ASSERT_TRUE(m.command(0x0C, {mlx::kSM | mlx::kX}, 1, r));
  m.wait(2e6);
  ASSERT_TRUE(m.command(0x0C, {mlx::kRM | mlx::kX}, 3, r));
  EXPECT_EQ(int(r[1] << 8 | r[2]), 200);  // sensor 1
  EXPECT_EQ(s0.commands(), 2u);
  EXPECT_EQ(s1.commands(), 2u);
  for (const auto& v : bus.violations()) ADD_FAILURE() << v;
}

TEST(Tca9548aModel, SameAddressOnTwoEnabledChannelsCollides) {
  // Enabling two channels joins both sensors to one net: both ACK and drive
  // SDA together (wired-AND), so the reply is the AND of the two; the
  // sequencer must never do this, and this shows the model would expose it.
  I2cBus bus;
  SensorField field;
  Tca9548aModel mux(bus, 0, 0, 0);
  Mlx90393Model s0(bus, field, 0, {}, mux.channel_segment(0));
  Mlx90393Model s1(bus, field, 1, {}, mux.channel_segment(1));
  SoftMaster m(bus);
  std::vector<uint8_t> r;
  ASSERT_TRUE(m.write_bytes(0x70, {0x03}));
  ASSERT_TRUE(m.command(0x0C, {mlx::kSM | mlx::kX}, 1, r));
  m.wait(2e6);
  ASSERT_TRUE(m.command(0x0C, {mlx::kRM | mlx::kX}, 3, r));
  EXPECT_EQ(int(r[1] << 8 | r[2]), 100 & 200);
}

}  // namespace
}  // namespace eskin::sim
