// Which build of the mixed top (rtl/mixed_top.v) a scene with both a DTMF
// skin and Hall sensors needs on the virtual board: the skin's dtmf_top
// build (sim/vboard/fpga_params.h) and the Hall sensors' hall_top build
// (sim/vboard/hall_build.h) at the same clock, the DTMF build's, since the
// two tops share it; mixed_top takes both parameter sets by their own names.
// The key is "m" + FNV-1a of both sets.
#pragma once

#include <string>
#include <vector>

#include "sim/vboard/fpga_params.h"
#include "sim/vboard/hall_build.h"

namespace eskin::vboard {

struct MixedBuild {
  FpgaBuild dtmf;
  HallBuild hall;
  std::string key;
  std::vector<std::string> verilator_args() const;  // both sets, CLK_HZ and BAUD once
};

// Throws ConfigError naming the field when the scene lacks the skin or the
// hall: section, or when the Hall top cannot run at the DTMF build's clock.
MixedBuild mixed_build_for(const sim::Scene& scene, const FpgaBuild& dtmf);

}  // namespace eskin::vboard
