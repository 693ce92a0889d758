// A bit-banged I2C master for model tests: drives an I2cBus with chosen
// timing (ns), honours clock stretching (waits for SCL to read high before
// timing its high phase) and samples SDA in the middle of SCL high. Used to
// exercise the bus checker and the device models without the RTL master;
// its timing fields can be set illegal on purpose (negative controls).
#pragma once

#include <cstdint>
#include <vector>

#include "sim/i2c_bus.h"

namespace eskin::sim::testing {

struct SoftMasterTiming {
  double t_low = 1500, t_high = 900;      // SCL low / high phases
  double t_hold = 300;                    // SDA change after SCL falls
  double t_hd_sta = 700, t_su_sta = 700;  // START hold, repeated START setup
  double t_su_sto = 700, t_buf = 1700;    // STOP setup, bus free after STOP
};

class SoftMaster {
 public:
  SoftMaster(I2cBus& bus, SoftMasterTiming tm = {}, double t0 = 1000)
      : bus_(bus), id_(bus.attach("soft master")), tm_(tm), t_(t0) {
    bus_.advance_to(t_);
  }
  double now() const { return t_; }
  void wait(double ns) { at(t_ + ns); }
  SoftMasterTiming& timing() { return tm_; }

  void start() {  // from idle (SCL and SDA high)
    bus_.drive_sda(id_, t_, true);
    wait(tm_.t_hd_sta);
    bus_.drive_scl(id_, t_, true);
  }
  void repeated_start() {  // SCL low on entry
    wait(tm_.t_hold);
    bus_.drive_sda(id_, t_, false);
    wait(tm_.t_low - tm_.t_hold);
    release_scl();
    wait(tm_.t_su_sta);
    bus_.drive_sda(id_, t_, true);
    wait(tm_.t_hd_sta);
    bus_.drive_scl(id_, t_, true);
  }
  void stop() {  // SCL low on entry
    wait(tm_.t_hold);
    bus_.drive_sda(id_, t_, true);
    wait(tm_.t_low - tm_.t_hold);
    release_scl();
    wait(tm_.t_su_sto);
    bus_.drive_sda(id_, t_, false);
    wait(tm_.t_buf);
  }
  // One bit: SDA released for 1, pulled for 0; returns SDA read at mid-high.
  bool bit(bool b) {
    wait(tm_.t_hold);
    bus_.drive_sda(id_, t_, !b);
    wait(tm_.t_low - tm_.t_hold);
    release_scl();
    wait(tm_.t_high / 2);
    const bool v = bus_.sda();
    wait(tm_.t_high / 2);
    bus_.drive_scl(id_, t_, true);
    return v;
  }
  bool write(uint8_t b) {  // true if ACKed
    for (int i = 7; i >= 0; --i) bit((b >> i) & 1);
    return !bit(true);
  }
  uint8_t read(bool ack) {
    uint8_t v = 0;
    for (int i = 0; i < 8; ++i) v = uint8_t(v << 1 | (bit(true) ? 1 : 0));
    bit(!ack);
    return v;
  }
  // Whole transactions; false if any byte was NACKed (then it sends STOP).
  bool write_bytes(uint8_t addr, const std::vector<uint8_t>& bytes, bool stop_after = true) {
    start();
    bool ok = write(uint8_t(addr << 1));
    for (size_t i = 0; ok && i < bytes.size(); ++i) ok = write(bytes[i]);
    if (stop_after || !ok) stop();
    return ok;
  }
  // Command then reply after a repeated START, as the MLX90393 expects.
  bool command(uint8_t addr, const std::vector<uint8_t>& cmd, int nreply,
               std::vector<uint8_t>& reply) {
    reply.clear();
    if (!write_bytes(addr, cmd, false)) return false;
    repeated_start();
    if (!write(uint8_t(addr << 1 | 1))) {
      stop();
      return false;
    }
    for (int i = 0; i < nreply; ++i) reply.push_back(read(i + 1 < nreply));
    stop();
    return true;
  }

 private:
  void at(double t) {
    t_ = t;
    bus_.advance_to(t_);
  }
  void release_scl() {  // then wait while someone stretches the clock
    bus_.drive_scl(id_, t_, false);
    while (!bus_.scl()) wait(10);
  }

  I2cBus& bus_;
  int id_;
  SoftMasterTiming tm_;
  double t_;
};

}  // namespace eskin::sim::testing
