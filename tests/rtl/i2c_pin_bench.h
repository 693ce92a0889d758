// Glue between a Verilated module's open-drain I2C pins and sim/i2c_bus:
// each clock, the bus is advanced to the edge's time and its levels are
// given to the module (scl_i/sda_i); after the edge the module's pull-downs
// (scl_oe/sda_oe) drive the bus from that same time on. One I2cPinBus per
// bus the module masters.
#pragma once

#include <string>

#include "sim/i2c_bus.h"

struct I2cPinBus {
  eskin::sim::I2cBus bus;
  int master;
  explicit I2cPinBus(eskin::sim::I2cTiming tm = eskin::sim::I2cTiming::fast(),
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
