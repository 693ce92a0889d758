// Which build of the FPGA top (rtl/dtmf_top.v) a scene needs: its plan and
// Verilog parameters from the project's one derivation
// (common/eskin/dtmf_top_plan.h via sim/dtmf_top_spec.h), and a key naming the
// build. The key covers the integer parameters (sizes, clock, rates) only:
// the scene's microcode and constants are files the model reads when it is
// constructed (UCODE_HEX, KROM_HEX), written by fpga_build_for() into the
// build's directory, so one Verilated model serves every scene of its
// sizes. The prebuilt eskin-vboard is the default scene's build, key
// "default".
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "sim/scene.h"

namespace eskin::vboard {

struct FpgaBuild {
  hls::DtmfTopPlan plan;
  std::vector<hls::VerilogParam> params;  // every parameter, as -G overrides
  std::string key;                        // "default" or "p" + hash of the integer params

  double clk_hz() const { return double(plan.spec.clk_hz); }
  double baud() const { return double(plan.spec.baud); }
  int adc_shift() const { return 12 - plan.spec.adc_bits; }  // scene code -> 12-bit code
  std::vector<std::string> verilator_args() const;           // -Gname=value ...
};

// The frame engine of a build (hls::DtmfTopSpec::engine_fast_shift,
// neuron_unit): the iCEBreaker's bit-serial engine with the microcode's
// neurons unless `eskin bitstream`'s board chose another for the scene
// (fpga::choose_core_clock), whose clocks a frame the clock was chosen for.
struct EngineOptions {
  bool fast_shift = false;
  bool neuron_unit = false;
};

// The build for `scene` at FPGA clock `clk_hz` and UART rate `baud`
// (default: the UP5K's 18 MHz, 3 Mbaud) with `engine`;
// throws ConfigError naming the field when the top cannot be built for it.
// With a `dir`, its microcode and constants are written there
// (KEY.ucode.hex, KEY.krom.hex, each replaced atomically) and `params` name
// them; without, only the plan and key are derived.
FpgaBuild fpga_build_for(const sim::Scene& scene, const std::string& dir = "",
                         long clk_hz = hls::kDtmfTopClkHz, long baud = 3000000,
                         EngineOptions engine = {});

// An exclusive lock on one build's files (DIR/KEY.lock, flock): boards of
// the same build running different scenes hold it from writing their files
// until their model has read them, so none reads another's constants.
class BuildLock {
 public:
  BuildLock(const std::string& dir, const std::string& key);
  ~BuildLock();
  BuildLock(const BuildLock&) = delete;
  BuildLock& operator=(const BuildLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace eskin::vboard
