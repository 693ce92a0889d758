// Which build of the Hall top (rtl/hall_top.v) a Hall scene needs on the
// virtual board: its buses, sensors, MLX90393 registers, waits and decoding
// (sim/hall_top_spec.h, the generator `eskin hall-top` prints), at the
// board's 12 MHz oscillator, as Verilator -G overrides, and a key naming
// the build ("h" + FNV-1a of the overrides). Every Hall build is made the
// first time a scene needs it (sim/vboard/vboard_build.h).
#pragma once

#include <string>
#include <vector>

#include "sim/hall_top_spec.h"
#include "sim/scene.h"

namespace eskin::vboard {

struct HallBuild {
  sim::HallTopSpec spec;
  long clk_hz = 12000000;  // hall_top runs on the oscillator (docs/hall_fpga.md, Clock)
  long baud = 3000000;
  std::vector<std::string> params;  // -GNAME=VALUE, every override
  std::string key;
};

// Throws ConfigError naming the field when the scene has no hall: section or
// the top cannot carry its sensors. `baud`: the UART's (a board's clock may
// not divide into 3 Mbaud; `eskin bitstream` passes its own).
HallBuild hall_build_for(const sim::Scene& scene, long clk_hz = 12000000, long baud = 3000000);

}  // namespace eskin::vboard
