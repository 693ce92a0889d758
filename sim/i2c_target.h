// The byte-level half of an I2C target (device) on an I2cBus: address match,
// ACK/NACK, receiving and sending bytes. Device models (MLX90393, TCA9548A)
// derive from it and supply what the bytes mean.
//
// Pin behaviour: the target samples SDA at SCL's rising edge (VIH) and
// changes its own SDA output `t_out` ns after SCL's falling edge (a device's
// internal hold, within UM10204's tVD;DAT of 0.9 µs). A START or STOP anywhere
// resets it to wait for its address.
//
// Faults for tests: set_absent() (never ACKs: a missing or dead sensor from
// that time on) and stick_in_read() (the device believes it is sending a
// 0x00 byte and holds SDA low: what a master reset in the middle of a read
// leaves behind; only clocking it out frees the bus).
#pragma once

#include <cstdint>
#include <string>

#include "sim/i2c_bus.h"

namespace eskin::sim {

class I2cTarget : public I2cListener {
 public:
  I2cTarget(I2cBus& bus, const std::string& name, uint8_t address, int segment = 0,
            double t_out_ns = 300.0)
      : bus_(bus), id_(bus.attach(name, segment, this)), address_(address), t_out_(t_out_ns) {}

  uint8_t address() const { return address_; }
  void set_absent(bool absent) { absent_ = absent; }
  void stick_in_read(double t) {
    phase_ = Phase::Send;
    byte_ = 0x00;
    bit_ = 7;
    drive_bit(t, 0);
  }

  void on_start(double t) override {
    release(t);
    if (active_) transaction_end(t, true);
    active_ = false;
    phase_ = Phase::Addr;
    bits_ = 0;
    shift_ = 0;
  }
  void on_stop(double t) override {
    release(t);
    if (active_) transaction_end(t, false);
    active_ = false;
    phase_ = Phase::Idle;
  }
  void on_scl_rise(double /*t*/, bool sda) override {
    switch (phase_) {
      case Phase::Addr:
      case Phase::Recv:
        shift_ = uint8_t(shift_ << 1 | (sda ? 1 : 0));
        ++bits_;
        break;
      case Phase::MasterAck: master_ack_ = !sda; break;
      default: break;
    }
  }
  void on_scl_fall(double t) override {
    switch (phase_) {
      case Phase::Addr:
        if (bits_ < 8) break;
        if (!absent_ && (shift_ >> 1) == address_ && address_match(t, shift_ & 1)) {
          reading_ = shift_ & 1;
          active_ = true;
          drive_bit(t, 0);  // ACK
          phase_ = Phase::AckOut;
        } else {
          phase_ = Phase::Idle;  // not ours: wait for the next START
        }
        break;
      case Phase::Recv:
        if (bits_ < 8) break;
        if (write_byte(t, shift_)) drive_bit(t, 0);
        phase_ = Phase::AckOut;
        break;
      case Phase::AckOut:
        release(t);
        if (reading_) {
          load_and_send(t);
        } else {
          phase_ = Phase::Recv;
          bits_ = 0;
        }
        break;
      case Phase::Send:
        if (--bit_ >= 0) {
          drive_bit(t, (byte_ >> bit_) & 1);
        } else {
          release(t);
          phase_ = Phase::MasterAck;
          master_ack_ = false;
        }
        break;
      case Phase::MasterAck:
        if (master_ack_) load_and_send(t);
        else phase_ = Phase::Idle;  // NACK: the master wants no more
        break;
      case Phase::Idle: break;
    }
  }

 protected:
  // The address byte matched; return false to NACK it.
  virtual bool address_match(double t, bool read) = 0;
  // A written data byte; return true to ACK it.
  virtual bool write_byte(double t, uint8_t b) = 0;
  // The next byte to send.
  virtual uint8_t read_byte(double t) = 0;
  // A transaction addressed to us ended with a STOP or a repeated START.
  virtual void transaction_end(double t, bool repeated_start) = 0;

  I2cBus& bus_;
  const int id_;

 private:
  enum class Phase { Idle, Addr, AckOut, Recv, Send, MasterAck };
  void drive_bit(double t, int bit) { bus_.drive_sda(id_, t + t_out_, bit == 0); }
  void release(double t) { bus_.drive_sda(id_, t + t_out_, false); }
  void load_and_send(double t) {
    byte_ = read_byte(t);
    bit_ = 7;
    drive_bit(t, (byte_ >> 7) & 1);
    phase_ = Phase::Send;
  }

  uint8_t address_;
  double t_out_;
  bool absent_ = false;
  Phase phase_ = Phase::Idle;
  int bits_ = 0, bit_ = 0;
  uint8_t shift_ = 0, byte_ = 0;
  bool reading_ = false, master_ack_ = false, active_ = false;
};

}  // namespace eskin::sim
