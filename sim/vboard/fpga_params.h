// Which build of the FPGA top (rtl/dtmf_top.v) a scene needs: its Verilog
// parameters, taken from the project's one derivation
// (hls/dtmf_top_config.h via sim/dtmf_top_spec.h), and a key naming the
// build. The virtual board's build cache is keyed by it; the prebuilt
// eskin-vboard is the top's Verilog defaults, which are the default
// scene's derivation (tests/hls/dtmf_top_config_test.cpp), key "default".
#pragma once

#include <string>
#include <vector>

#include "hls/dtmf_top_config.h"
#include "sim/scene.h"

namespace eskin::vboard {

struct FpgaBuild {
  hls::DtmfTopPlan plan;
  std::vector<hls::VerilogParam> params;  // every parameter, as -G overrides
  std::string key;                        // "default" or "p" + hash of params

  double clk_hz() const { return double(plan.spec.clk_hz); }
  double baud() const { return double(plan.spec.baud); }
  int adc_shift() const { return 12 - plan.spec.adc_bits; }  // scene code -> 12-bit code
  std::vector<std::string> verilator_args() const;           // -Gname=value ...
};

// The build for `scene`; throws ConfigError naming the field when the top
// cannot be built for it.
FpgaBuild fpga_build_for(const sim::Scene& scene);

}  // namespace eskin::vboard
