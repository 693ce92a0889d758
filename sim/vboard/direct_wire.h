// SystemC channels whose writes take effect at once, with no update phase
// and no event: the virtual board binds the Verilated FPGA top's ports to
// these and clocks the model itself, many cycles per SystemC wait
// (docs/vboard.md: one SystemC delta cycle per clock edge costs more than
// the Verilated model's own evaluation). DirectWire is a one-bit pin;
// DirectBus<T> a vector port as Verilator types it (uint32_t up to 32 bits,
// uint64_t up to 64); DirectPort<T> picks the one for a port's type.
#pragma once

#include <systemc>

#include <type_traits>

namespace eskin::vboard {

template <class T>
class DirectBus : public sc_core::sc_prim_channel, public sc_core::sc_signal_inout_if<T> {
 public:
  explicit DirectBus(const char* name, T init = T())
      : sc_core::sc_prim_channel(name), value_(init) {}

  void write(const T& v) override { value_ = v; }
  const T& read() const override { return value_; }
  const T& get_data_ref() const override { return value_; }
  // Never notified: nothing in SystemC waits on a pin of the FPGA.
  const sc_core::sc_event& default_event() const override { return never_; }
  const sc_core::sc_event& value_changed_event() const override { return never_; }
  bool event() const override { return false; }

 private:
  T value_;
  sc_core::sc_event never_;
};

class DirectWire : public DirectBus<bool> {
 public:
  explicit DirectWire(const char* name, bool init = false) : DirectBus<bool>(name, init) {}
  const sc_core::sc_event& posedge_event() const override { return default_event(); }
  const sc_core::sc_event& negedge_event() const override { return default_event(); }
  bool posedge() const override { return false; }
  bool negedge() const override { return false; }
};

// The channel for a port of Verilator's type T (a one-bit port is bool).
template <class T>
using DirectPort = std::conditional_t<std::is_same_v<T, bool>, DirectWire, DirectBus<T>>;

}  // namespace eskin::vboard
