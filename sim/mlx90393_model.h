// MLX90393 device model on an I2cBus: the command set (SB, SW, SM, RM, RR,
// WR, EX, RT, NOP, HR, HS), the status byte, the register map, conversion
// timing from the datasheet formula, the DRDY/INT pin, address pins A0/A1,
// output codes per RES/TCMP with saturation. It reads the field from a
// HallFieldSource and adds its own offset and white noise before quantising.
//
// Protocol (I2C): the master writes a command (1 byte; RR 2, WR 4), then
// reads the reply after a repeated START (or in a later transaction): the
// status byte, then the data bytes, MSB first (RM: T, X, Y, Z of the
// requested axes; RR: the register). A command takes effect at its last
// byte. Choices where the datasheet leaves room:
//  * RM without a new measurement since the last RM, or for an axis that was
//    not measured, sets ERROR and returns the stale values.
//  * A mode command (SB/SW/SM) while another mode runs sets ERROR and is
//    ignored; SM ends by itself when its conversion is done.
//  * WR of a combination illegal_reason() refuses (e.g. OSR 0 with
//    DIG_FILT 1 at HALLCONF 0xC), or of a register above 0x1F, sets ERROR
//    and changes nothing.
//  * DRDY (INT) rises when a measurement completes and falls at the next RM.
//  * The field is sampled at the middle of the magnetic conversion.
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "eskin/mlx90393_config.h"
#include "sim/hall_field_source.h"
#include "sim/i2c_target.h"

namespace eskin::sim {

struct Mlx90393Options {
  int a1 = 0, a0 = 0;                         // address pins
  uint8_t base_address = mlx90393::kBaseAddress;
  mlx90393::Config config;                    // power-on register contents
  std::array<double, 3> offset_uT = {0, 0, 0};
  std::array<double, 3> noise_rms_uT = {0, 0, 0};
  uint16_t tref = 46244;  // register 0x24
  double temperature_c = 25.0;
  uint64_t seed = 1;
  double t_out_ns = 300.0;
};

class Mlx90393Model : public I2cTarget {
 public:
  // One completed conversion, as the device would send it.
  struct Measurement {
    double t_done_ns;
    uint8_t zyxt;
    uint16_t t, x, y, z;
    std::array<bool, 3> saturated;
  };

  Mlx90393Model(I2cBus& bus, const HallFieldSource& field, int sensor, Mlx90393Options opt = {},
                int segment = 0);

  bool drdy() const { return drdy_; }
  uint16_t reg(int a) const { return regs_[a]; }
  mlx90393::Config config() const {
    return mlx90393::Config::from_registers(regs_[0], regs_[1], regs_[2]);
  }
  const std::vector<Measurement>& measurements() const { return done_; }
  // Measurements delivered by an RM without ERROR, in order.
  const std::vector<Measurement>& delivered() const { return delivered_; }
  size_t commands() const { return commands_; }
  size_t error_replies() const { return error_replies_; }

  // Faults: the next n RM replies carry ERROR (data otherwise fine) / a
  // wrong D1:D0 byte count.
  void inject_status_error(int n) { inject_error_ = n; }
  void inject_byte_count_error(int n) { inject_count_ = n; }

  void advance(double t) override;

 protected:
  bool address_match(double t, bool read) override;
  bool write_byte(double t, uint8_t b) override;
  uint8_t read_byte(double t) override;
  void transaction_end(double t, bool repeated_start) override;

 private:
  enum class Mode { Idle, Burst, Woc, Single };
  void execute(double t);
  void start_conversion(double t);
  void complete_conversion();
  uint8_t status(bool error, int data_bytes);
  void reply_status(bool error) { reply_[0] = status(error, 0), nreply_ = 1; }

  const HallFieldSource& field_;
  const int sensor_;
  Mlx90393Options opt_;
  std::mt19937_64 rng_;
  std::array<uint16_t, mlx90393::kRegisterCount> regs_{}, nv_{};

  Mode mode_ = Mode::Idle;
  uint8_t sel_ = 0;           // axes of the running measurement
  double conv_start_ = 0, conv_done_ = 0;
  bool converting_ = false;
  bool data_ready_ = false, drdy_ = false, rs_ = false;
  Measurement last_{};
  std::array<int, 3> woc_ref_{};
  bool woc_have_ref_ = false;

  uint8_t cmd_[4] = {};
  int ncmd_ = 0;
  uint8_t reply_[9] = {};
  int nreply_ = 0, rpos_ = 0;
  int inject_error_ = 0, inject_count_ = 0;
  size_t commands_ = 0, error_replies_ = 0;
  std::vector<Measurement> done_, delivered_;
};

}  // namespace eskin::sim
