// MLX90393: the datasheet facts in common/eskin/mlx90393_config.h (timing
// formula, legality, sensitivity, code formats) and the device model on the
// I2C bus (commands, status byte, DRDY, burst timing, saturation, faults).
#include "sim/mlx90393_model.h"

#include <gtest/gtest.h>

#include <cmath>

#include "i2c_soft_master.h"

namespace eskin::sim {
namespace {

namespace mlx = eskin::mlx90393;
using testing::SoftMaster;

TEST(Mlx90393Config, ConversionTimeFromTheDatasheetFormula) {
  mlx::Config c;  // OSR 0, DIG_FILT 2, OSR2 0
  // TCONVM = 67 + 64 * 1 * (2 + 4) = 451 us; TCONVT = 67 + 192 = 259 us.
  EXPECT_EQ(mlx::tconvm_us(0, 2), 451.0);
  EXPECT_EQ(mlx::tconvt_us(0), 259.0);
  EXPECT_EQ(mlx::tconvm_us(3, 7), 67.0 + 64 * 8 * 130);
  // XYZ: 220 + 360 + 3 * 451 + 120 = 2053 us -> 487.1 Hz (the "about 490 Hz").
  EXPECT_EQ(mlx::conversion_us(c, mlx::kXYZ), 2053.0);
  EXPECT_NEAR(mlx::max_output_rate_hz(c, mlx::kXYZ), 487.09, 0.01);
  EXPECT_EQ(mlx::conversion_us(c, mlx::kXYZT), 2053.0 + 259.0);
  EXPECT_EQ(mlx::conversion_us(c, mlx::kZ), 220 + 360 + 451 + 120.0);
  c.burst_data_rate = 1;  // 20 ms interval dominates
  EXPECT_EQ(mlx::burst_period_us(c, mlx::kXYZ), 20000.0);
}

TEST(Mlx90393Config, IllegalOsrDigFiltPairsAreRefusedNamingTheField) {
  for (auto [osr, df, legal] : {std::tuple{0, 0, false}, {0, 1, false}, {1, 0, false},
                                {0, 2, true}, {1, 1, true}, {2, 0, true}}) {
    mlx::Config c;
    c.osr = osr;
    c.dig_filt = df;
    const std::string why = mlx::illegal_reason(c, "sensors[3]");
    EXPECT_EQ(why.empty(), legal) << osr << "/" << df;
    if (!legal) {
      EXPECT_EQ(why.rfind("sensors[3].dig_filt:", 0), 0u) << why;
      try {
        mlx::validate(c, "sensors[3]");
        ADD_FAILURE() << "accepted OSR " << osr << " DIG_FILT " << df;
      } catch (const ConfigError& e) {
        EXPECT_EQ(e.field(), "sensors[3].dig_filt");
      }
    }
  }
  mlx::Config c;
  c.hallconf = 0x0;  // no restriction at HALLCONF 0x0
  c.dig_filt = 0;
  EXPECT_EQ(mlx::illegal_reason(c), "");
  c.gain_sel = 8;
  EXPECT_EQ(mlx::illegal_reason(c).rfind("mlx90393.gain_sel:", 0), 0u);
}

TEST(Mlx90393Config, SensitivityAndCodeFormats) {
  // Datasheet table, HALLCONF 0xC: GAIN_SEL 7 RES 0 is 0.150 (XY) and 0.242 (Z)
  // uT/LSB; each RES step doubles it.
  EXPECT_DOUBLE_EQ(mlx::sensitivity_uT(0xC, 7, 0, 0), 0.150);
  EXPECT_DOUBLE_EQ(mlx::sensitivity_uT(0xC, 7, 0, 2), 0.242);
  EXPECT_DOUBLE_EQ(mlx::sensitivity_uT(0xC, 0, 3, 1), 0.751 * 8);
  EXPECT_DOUBLE_EQ(mlx::sensitivity_uT(0x0, 0, 0, 2), 1.267);

  mlx::Config c;  // RES 0: two's complement
  EXPECT_EQ(mlx::encode_uT(c, 0, 15.0).code, 100);  // 15 / 0.15
  EXPECT_EQ(mlx::encode_uT(c, 0, -0.15).code, 0xFFFF);
  EXPECT_EQ(mlx::decode_uT(c, 0, 0xFFFF), -0.15);
  const mlx::Code big = mlx::encode_uT(c, 0, 10000.0);  // 66667 LSB > 32767
  EXPECT_EQ(big.code, 0x7FFF);
  EXPECT_TRUE(big.saturated);
  EXPECT_TRUE(mlx::code_saturated(c, 0, 0x7FFF));
  EXPECT_FALSE(mlx::code_saturated(c, 0, 100));
  c.res_x = 2;  // unsigned, zero field at 0x8000
  EXPECT_EQ(mlx::encode_uT(c, 0, 0.0).code, 0x8000);
  EXPECT_EQ(mlx::encode_uT(c, 0, 0.6).code, 0x8001);  // LSB 0.6 uT at RES 2
  c.res_x = 3;  // unsigned, zero at 0x4000, 0..0x7FFF
  EXPECT_EQ(mlx::encode_uT(c, 0, 0.0).code, 0x4000);
  EXPECT_EQ(mlx::encode_uT(c, 0, 1e6).code, 0x7FFF);
  EXPECT_EQ(mlx::encode_uT(c, 0, -1e6).code, 0x0000);
  c.res_x = 0;
  c.tcmp_en = true;  // temperature compensation: 0x8000 offset at any RES
  EXPECT_EQ(mlx::encode_uT(c, 0, 0.0).code, 0x8000);
  EXPECT_EQ(mlx::code_to_lsb(c, 0, 0x7FFF), -1);
}

// A field that is constant per sensor, or scripted in time.
struct TestField : HallFieldSource {
  std::array<double, 3> b{30.0, -45.0, 121.0};
  double slope_uT_per_s = 0;  // added to Bx
  std::array<double, 3> field_uT(int sensor, double t_s) const override {
    return {b[0] + slope_uT_per_s * t_s + 1000.0 * sensor, b[1], b[2]};
  }
};

uint16_t be16(const std::vector<uint8_t>& r, int i) { return uint16_t(r[i] << 8 | r[i + 1]); }

struct Bench {
  I2cBus bus;
  TestField field;
  Mlx90393Model dev;
  SoftMaster m;
  explicit Bench(Mlx90393Options o = {}) : dev(bus, field, 0, o), m(bus) {}
  uint8_t addr() const { return dev.address(); }
  std::vector<uint8_t> cmd(std::vector<uint8_t> c, int n) {
    std::vector<uint8_t> r;
    EXPECT_TRUE(m.command(addr(), c, n, r));
    return r;
  }
};

TEST(Mlx90393Model, SingleMeasurementDrdyAndReadout) {
  Bench b;
  EXPECT_EQ(b.addr(), 0x0C);
  auto r = b.cmd({mlx::kSM | mlx::kXYZ}, 1);
  EXPECT_EQ(r[0], mlx::kStatusSm);
  r = b.cmd({mlx::kRM | mlx::kXYZ}, 7);  // too early: ERROR, D = 2
  EXPECT_EQ(r[0], mlx::kStatusSm | mlx::kStatusError | 2);
  EXPECT_FALSE(b.dev.drdy());
  b.m.wait(2053e3);  // TCONV for XYZ at OSR 0 / DIG_FILT 2
  EXPECT_TRUE(b.dev.drdy());
  r = b.cmd({mlx::kRM | mlx::kXYZ}, 7);
  EXPECT_EQ(r[0], 2);  // SM ended by itself; 6 data bytes
  // 30 / 0.150 = 200, -45 / 0.150 = -300, 121 / 0.242 = 500 LSB
  EXPECT_EQ(be16(r, 1), 200);
  EXPECT_EQ(be16(r, 3), uint16_t(-300));
  EXPECT_EQ(be16(r, 5), 500);
  EXPECT_FALSE(b.dev.drdy());
  ASSERT_EQ(b.dev.delivered().size(), 1u);
  EXPECT_EQ(b.dev.delivered()[0].x, 200);
  EXPECT_EQ(b.bus.violation_count(), 0u);
}

TEST(Mlx90393Model, RegistersWriteReadAndIllegalWriteRefused) {
  Bench b;
  mlx::Config c;
  c.osr = 1;
  c.dig_filt = 1;
  c.res_z = 2;
  auto r = b.cmd({mlx::kWR, uint8_t(c.reg2() >> 8), uint8_t(c.reg2()), mlx::kReg2 << 2}, 1);
  EXPECT_EQ(r[0], 0);
  r = b.cmd({mlx::kRR, mlx::kReg2 << 2}, 3);
  EXPECT_EQ(r[0], 0);
  EXPECT_EQ(be16(r, 1), c.reg2());
  c.osr = 0;  // OSR 0 with DIG_FILT 1: not permitted at HALLCONF 0xC
  r = b.cmd({mlx::kWR, uint8_t(c.reg2() >> 8), uint8_t(c.reg2()), mlx::kReg2 << 2}, 1);
  EXPECT_EQ(r[0], mlx::kStatusError);
  EXPECT_EQ(b.dev.config().osr, 1);  // unchanged
  r = b.cmd({mlx::kWR, 0x12, 0x34, 0x20 << 2}, 1);  // Melexis area: refused
  EXPECT_EQ(r[0], mlx::kStatusError);
  r = b.cmd({mlx::kRR, mlx::kRegTref << 2}, 3);
  EXPECT_EQ(be16(r, 1), 46244);
  r = b.cmd({mlx::kRT}, 1);  // reset: registers back, RS reported once
  EXPECT_EQ(r[0], mlx::kStatusRs);
  EXPECT_EQ(b.dev.config().osr, 0);
  r = b.cmd({mlx::kNOP}, 1);
  EXPECT_EQ(r[0], 0);
  r = b.cmd({0x70}, 1);  // not a command
  EXPECT_EQ(r[0], mlx::kStatusError);
  EXPECT_EQ(b.bus.violation_count(), 0u);
}

TEST(Mlx90393Model, BurstModeRunsAtTheConversionRate) {
  Bench b;
  const double t0 = b.m.now();
  auto r = b.cmd({mlx::kSB | mlx::kXYZ}, 1);
  EXPECT_EQ(r[0], mlx::kStatusBurst);
  r = b.cmd({mlx::kSM | mlx::kXYZ}, 1);  // another mode while bursting: ERROR
  EXPECT_EQ(r[0], mlx::kStatusBurst | mlx::kStatusError);
  b.m.wait(20 * 2053e3);
  // Conversions complete every 2053 us after the SB command's last byte.
  const auto& done = b.dev.measurements();
  ASSERT_GE(done.size(), 20u);
  for (size_t k = 1; k < done.size(); ++k)
    EXPECT_NEAR(done[k].t_done_ns - done[k - 1].t_done_ns, 2053e3, 1e-3);
  EXPECT_GT(done[0].t_done_ns - t0, 2053e3);
  // + the SB write: START and 18 clocks of about 2.67 us each (~49 us)
  EXPECT_LT(done[0].t_done_ns - t0, 2053e3 + 60e3);
  r = b.cmd({mlx::kEX}, 1);
  EXPECT_EQ(r[0], 0);
  const size_t n = done.size();
  b.m.wait(5 * 2053e3);
  EXPECT_EQ(b.dev.measurements().size(), n);  // stopped
}

TEST(Mlx90393Model, SaturationIsFlaggedAndClamped) {
  Bench b;
  b.field.b = {10000.0, 0.0, -10000.0};  // 10 mT: beyond the RES 0 range
  b.cmd({mlx::kSM | mlx::kXYZ}, 1);
  b.m.wait(2100e3);
  auto r = b.cmd({mlx::kRM | mlx::kXYZ}, 7);
  EXPECT_EQ(be16(r, 1), 0x7FFF);
  EXPECT_EQ(be16(r, 5), 0x8000);
  const auto& d = b.dev.delivered().back();
  EXPECT_TRUE(d.saturated[0]);
  EXPECT_FALSE(d.saturated[1]);
  EXPECT_TRUE(d.saturated[2]);
}

TEST(Mlx90393Model, AddressPinsAndInjectedFaults) {
  Mlx90393Options o;
  o.a1 = 1;
  Bench b(o);
  EXPECT_EQ(b.addr(), 0x0E);
  std::vector<uint8_t> r;
  EXPECT_FALSE(b.m.command(0x0C, {mlx::kNOP}, 1, r));  // nobody at 0x0C
  b.cmd({mlx::kSM | mlx::kXYZ}, 1);
  b.m.wait(2100e3);
  b.dev.inject_status_error(1);
  r = b.cmd({mlx::kRM | mlx::kXYZ}, 7);
  EXPECT_EQ(r[0], mlx::kStatusError | 2);
  b.cmd({mlx::kSM | mlx::kXYZ}, 1);
  b.m.wait(2100e3);
  b.dev.inject_byte_count_error(1);
  r = b.cmd({mlx::kRM | mlx::kXYZ}, 7);
  EXPECT_EQ(r[0] & mlx::kStatusD, 1);  // says 4 data bytes, sends 6
  b.dev.set_absent(true);
  EXPECT_FALSE(b.m.command(0x0E, {mlx::kNOP}, 1, r));
}

TEST(Mlx90393Model, NoiseAndOffsetAreTheDevicesOwn) {
  Mlx90393Options o;
  o.offset_uT = {1.5, 0, 0};
  o.noise_rms_uT = {0, 3.0, 0};
  o.seed = 7;
  Bench b(o);
  b.cmd({mlx::kSB | mlx::kXYZ}, 1);
  b.m.wait(400 * 2053e3);
  const auto& done = b.dev.measurements();
  ASSERT_GE(done.size(), 399u);
  double sum = 0, sum2 = 0;
  for (const auto& d : done) {
    EXPECT_EQ(d.x, 210);  // (30 + 1.5) / 0.15, noise-free axis
    const double y = int16_t(d.y) * 0.150 + 45.0;
    sum += y;
    sum2 += y * y;
  }
  const double n = double(done.size());
  const double mean = sum / n, rms = std::sqrt(sum2 / n - mean * mean);
  // 3 uT rms over >= 399 samples: the mean's standard error is 0.15 uT (bound
  // 5 sigma), the rms estimate's about 0.11 uT plus the 0.15 uT quantisation
  // (bound 0.6 uT).
  EXPECT_NEAR(mean, 0.0, 0.75);
  EXPECT_NEAR(rms, 3.0, 0.6);
}

}  // namespace
}  // namespace eskin::sim
