// Glue between a Verilated module's open-drain I2C pins and sim/i2c_bus:
// each clock, the bus is advanced to the edge's time and its levels are
// given to the module (scl_i/sda_i); after the edge the module's pull-downs
// (scl_oe/sda_oe) drive the bus from that same time on. One I2cPinBus per
// bus the module masters.
#pragma once

#include "sim/i2c_bus.h"

namespace eskin::sim {

struct I2cPinBus {
  I2cBus bus;
  int master;
  explicit I2cPinBus(I2cTiming tm = I2cTiming::fast(),
                     double pullup_ohm = 2200, double cap_pf = 100)
      : bus(tm, pullup_ohm, cap_pf), master(bus.attach("FPGA master")) {}
  // Levels for the inputs, just before the edge at t_ns.
  void before(double t_ns, bool& scl, bool& sda) {
    bus.advance_to(t_ns);
    scl = bus.scl();
    sda = bus.sda();
  }
  // Pull-downs after the edge at t_ns.
  void after(double t_ns, bool scl_oe, bool sda_oe) { bus.drive(master, t_ns, scl_oe, sda_oe); }
};

}  // namespace eskin::sim
