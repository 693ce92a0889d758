// dtmf_top: the FPGA of the virtual board's `cycle` fidelity level
// (docs/vboard.md, "Fidelity levels"): rtl/dtmf_top.v as clock-exact C++
// models of its blocks (sim/cycle/*.h, each held to its RTL clock by clock
// in tests/rtl) around the frame engine's instruction-set model
// (ucode/frame_engine.h, clock-exact with rtl/frame_engine.v), joined as the
// top joins them: the power-on reset, the carrier writes to the DFT and the
// ADC's enable, the registered IO reads and their partial decode, the word
// port's second byte, the counters. The same pins, clock for clock, as the
// Verilated top (tests/vboard/fidelity_test.cpp).
//
// How the engine and the rest keep step. The instruction-set model runs an
// instruction at a time and names the clock of each bus access: a read in
// its cycle A (the value is what the top's read register takes at that
// clock's edge), a write in the clock its io_we is high, events in each
// clock of a wait. The rest of the top is advanced edge by edge to the
// clock of each read and event, and writes are queued for the edge of
// their clock. The top never runs past the engine's earliest next access
// (its clock count less one, for the overlap of cycle A), and the engine
// starts an instruction only when every clock it can read in has the
// board's inputs: so cycle() for clock T runs the engine to at least T + 2
// and the rest of the top through the edge of T.
//
// The builds it models: the frame engine's datapath (not STREAM), one DFT
// lane without a sample FIFO, the ADC on the core clock sampling at the
// rising edge (below 35 MHz: adc_ad7476's LAG 0), the microcode's neurons
// or the neuron unit (its port's clock-exact model, ucode/engine_ports.h;
// not the unit's lanes), the top's own link. Any other build is refused at
// construction, naming the parameter.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "sim/vboard/fpga_model.h"

namespace eskin::cycle {

class DtmfTop final : public vboard::FpgaModel {
 public:
  // Throws std::invalid_argument naming the parameter for a build it does
  // not model.
  explicit DtmfTop(const hls::DtmfTopPlan& plan);
  ~DtmfTop() override;

  vboard::FpgaOutputs cycle(const vboard::FpgaInputs& in, uint64_t t_ps) override;
  // No waveform at this level: refused (std::runtime_error).
  void open_trace(const std::string& path) override;
  void close_trace() override {}

  uint64_t clocks() const;  // clocks run
  // The clocks at whose edge a carrier table's last write reached the DFT
  // (rtl/dtmf_top.v's cfg_done, its probe p_cfg_done): the boot's, and
  // each reload's. The engine's timing before its first wait shows only here.
  const std::vector<uint64_t>& carrier_loads() const;
  // A build the class does not model: the parameter and why ("" if it does).
  static std::string unsupported(const hls::DtmfTopPlan& plan);

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace eskin::cycle
