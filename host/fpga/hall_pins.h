// The pins of a scene's Hall sensors on a board: two per I2C bus (SCL,
// SDA; open drain, rtl/i2c_pads.v) and one DRDY line per sensor, taken in
// order from the board's free header pins (the boards' published
// constraint files: icebreaker-fpga's icebreaker.pcf, emard/ulx3s's
// ulx3s_v20.lpf), and written as constraints beside the board's own
// (constraints/icebreaker.pcf, constraints/ulx3s.lpf).
#pragma once

#include <string>
#include <vector>

#include "host/fpga/board.h"

namespace eskin::fpga {

struct BoardPin {
  std::string site;       // package pin: "43" (iCE40), "A7" (ECP5)
  std::string connector;  // where a wire goes: "PMOD1B pin 1", "J1 pin 13+ (gp[4])"
};

// The board's pins free for Hall sensors, in the order they are given out,
// and where they are ("PMOD1B and PMOD2"). Empty for a board without.
const std::vector<BoardPin>& hall_pin_pool(const Board& b);
std::string hall_pin_pool_where(const Board& b);

struct PinAssignment {
  std::string signal;  // the wrapper's port bit: "i2c_scl[0]", "drdy[3]" ("drdy": one bit)
  BoardPin pin;
  bool i2c = false;    // an open-drain bus line (pull-up on)
};

struct HallPins {
  std::vector<PinAssignment> pins;  // buses first (SCL, SDA), then DRDY
  int needed = 0;                   // 2 NB + NB NSB
  std::string failure;              // the numbers, when the board has too few
};

// Bus b's SCL and SDA on the next two pins, for b = 0 .. nb-1, then sensor
// s's DRDY on the next, s = 0 .. nb*nsb-1 (hall_top's slot order).
HallPins assign_hall_pins(const Board& b, int nb, int nsb);

// The constraints file of a Hall build: the board's own (`base`, the text
// of Board::constraints) and the Hall pins, each with its connector; the
// bus lines with the FPGA's weak pull-up on (no substitute for the bus's
// real pull-ups, which the file says), DRDY lines as plain inputs (ECP5:
// pulled down, so a missing sensor's line reads idle).
std::string hall_constraints(const Board& b, const std::string& base, const HallPins& p);

}  // namespace eskin::fpga
