// Which build of the FPGA top (rtl/dtmf_top.v) a scene needs: its plan and
// Verilog parameters from the project's one derivation
// (common/eskin/dtmf_top_plan.h via sim/dtmf_top_spec.h), and a key naming the
// build. The key covers the integer parameters (sizes, clock, rates) only:
// the scene's microcode and constants are files the model reads at its
// first evaluation (+UCODE_HEX, +KROM_HEX: RunFiles below), so one
// Verilated model serves every scene of its sizes. The prebuilt eskin-vboard is the default scene's build, key
// "default".
#pragma once

#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "eskin/user_dirs.h"
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

// An exclusive lock on DIR/KEY.lock (flock): `eskin simulate` holds the
// build tree's list of boards with it while it adds a board and runs CMake
// (sim/vboard/vboard_build.cpp), one writer at a time.
class BuildLock {
 public:
  BuildLock(const std::string& dir, const std::string& key);
  ~BuildLock();
  BuildLock(const BuildLock&) = delete;
  BuildLock& operator=(const BuildLock&) = delete;

 private:
  int fd_ = -1;
};

// One board run's microcode and constants: written by fpga_build_for()
// into a fresh directory of the user's cache (eskin/user_dirs.h) and given
// to the Verilated model as plusargs (rtl/frame_engine.v reads
// +UCODE_HEX=PATH and +KROM_HEX=PATH at its first evaluation); removed
// when the run ends. Per run, so boards of one build never read each
// other's files, and a user runs the boards of a build tree another user
// (root, say) owns without writing to it.
class RunFiles {
 public:
  RunFiles(const sim::Scene& scene, long clk_hz, long baud, EngineOptions engine);
  const FpgaBuild& build() const { return build_; }
  // "+UCODE_HEX=DIR/KEY.ucode.hex", "+KROM_HEX=DIR/KEY.krom.hex", for
  // Verilated::commandArgsAdd before the model's first evaluation.
  std::vector<std::string> plusargs() const;

 private:
  ScratchDir dir_;
  FpgaBuild build_;
};

}  // namespace eskin::vboard
