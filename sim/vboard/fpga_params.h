// Which build of the FPGA top (rtl/dtmf_top.v) a scene needs: its
// parameter overrides (-G), the clock and baud rate the board must run it
// at, and a key naming the build (the virtual board cache is keyed by it).
//
// Until the lead's derivation of the top's parameters from a scene lands
// (issue 7), this knows the parameter sets that exist and are tested: the
// defaults (the default scene, 3x3) and the 16x16 set of
// tests/rtl/dtmf_top_test.cmake. dtmf_top_params() is the one place to
// switch to the derivation.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sim/scene.h"

namespace eskin::vboard {

struct FpgaParams {
  std::string name;                                        // "default", "skin16x16", ...
  std::vector<std::pair<std::string, std::string>> overrides;  // -Gname=value, in order
  double clk_hz = 12e6;    // CLK_HZ
  double baud = 3e6;       // BAUD
  int adc_shift = 2;       // scene code << adc_shift = the AD7476A's 12-bit code

  // "default" for the top's defaults, else name-hash of the overrides.
  std::string key() const;
  std::vector<std::string> verilator_args() const;  // -Gname=value ...
};

// The build for `scene`; throws ConfigError naming the field no parameter
// set fits.
FpgaParams dtmf_top_params(const sim::Scene& scene);

}  // namespace eskin::vboard
