// TCA9548A 1-to-8 I2C switch on an I2cBus. Its upstream side sits on the
// master's segment; each of its 8 channels is a segment of its own that the
// model joins to the upstream net when the channel is enabled.
//
// Datasheet behaviour: 7-bit address 0x70 + (A2 A1 A0); one control register
// (bit i enables channel i, several may be on at once); a write stores the
// byte, a read returns it; a newly written selection takes effect at the
// next STOP (not at a repeated START), so the write that selects a channel
// never reaches devices behind it.
#pragma once

#include <array>
#include <cstdint>

#include "sim/i2c_target.h"

namespace eskin::sim {

class Tca9548aModel : public I2cTarget {
 public:
  static constexpr uint8_t kBaseAddress = 0x70;

  Tca9548aModel(I2cBus& bus, int a2, int a1, int a0, int segment = 0, double t_out_ns = 300.0)
      : I2cTarget(bus, "TCA9548A", uint8_t(kBaseAddress + (a2 << 2 | a1 << 1 | a0)), segment,
                  t_out_ns) {
    for (auto& s : channel_) s = bus.add_segment();
  }

  int channel_segment(int ch) const { return channel_[ch]; }
  uint8_t control() const { return control_; }
  size_t selections() const { return selections_; }

 protected:
  bool address_match(double, bool) override { return true; }
  bool write_byte(double, uint8_t b) override {
    pending_ = b;
    have_pending_ = true;
    return true;
  }
  uint8_t read_byte(double) override { return control_; }
  void transaction_end(double, bool) override {}

 public:
  // Any STOP on the upstream bus applies a selection written since the last
  // one (also when the write was followed by a repeated START to another
  // device).
  void on_stop(double t) override {
    I2cTarget::on_stop(t);
    if (!have_pending_) return;
    have_pending_ = false;
    control_ = pending_;
    ++selections_;
    for (int i = 0; i < 8; ++i) bus_.connect(channel_[i], (control_ >> i) & 1);
  }

 private:
  std::array<int, 8> channel_{};
  uint8_t control_ = 0, pending_ = 0;
  bool have_pending_ = false;
  size_t selections_ = 0;
};

}  // namespace eskin::sim
