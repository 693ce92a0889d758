// A one-bit SystemC channel whose writes take effect at once, with no
// update phase and no event: the virtual board binds the Verilated FPGA
// top's ports to these and clocks the model itself, many cycles per
// SystemC wait (docs/vboard.md: one SystemC delta cycle per clock edge
// costs more than the Verilated model's own evaluation).
#pragma once

#include <systemc>

namespace eskin::vboard {

class DirectWire : public sc_core::sc_prim_channel, public sc_core::sc_signal_inout_if<bool> {
 public:
  explicit DirectWire(const char* name, bool init = false)
      : sc_core::sc_prim_channel(name), value_(init) {}

  void write(const bool& v) override { value_ = v; }
  const bool& read() const override { return value_; }
  const bool& get_data_ref() const override { return value_; }
  // Never notified: nothing in SystemC waits on a pin of the FPGA.
  const sc_core::sc_event& default_event() const override { return never_; }
  const sc_core::sc_event& value_changed_event() const override { return never_; }
  const sc_core::sc_event& posedge_event() const override { return never_; }
  const sc_core::sc_event& negedge_event() const override { return never_; }
  bool event() const override { return false; }
  bool posedge() const override { return false; }
  bool negedge() const override { return false; }

 private:
  bool value_;
  sc_core::sc_event never_;
};

}  // namespace eskin::vboard
