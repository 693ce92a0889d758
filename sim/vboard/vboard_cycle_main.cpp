// eskin-vboard-cycle SCENE.yaml --clk-hz F --baud B [...]: the scene on the
// SystemC virtual board with the FPGA at the `cycle` fidelity level
// (docs/vboard.md, "Fidelity levels"): sim/cycle/dtmf_top.h's clock-exact
// C++ models instead of the Verilated top, the same pins at every clock.
// One executable for every build it models (the build comes from the
// options, as `eskin simulate` chose it), so no scene waits for a model to
// be compiled. Everything else is the Verilated boards' (eskin_vboard):
// the skin, the ADC and USB bridge models, line and board faults, the pty,
// the JSON lines on stdout.

#include <cstdio>
#include <systemc>

#include "sim/cycle/dtmf_top.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/vboard_cli.h"
#include "sim/vboard/virtual_board.h"

namespace {

int run(const eskin::vboard::VboardArgs& a, FILE* json) {
  if (!a.trace.empty())
    throw std::invalid_argument("--trace: the cycle level has no waveforms (--fidelity rtl has)");
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.scene);
  if (!scene.has_skin || scene.has_hall)
    throw std::invalid_argument(a.scene + ": the cycle level models the DTMF top alone");
  const eskin::vboard::FpgaBuild params = eskin::vboard::fpga_build_for(
      scene, "", a.build.clk_hz, a.build.baud, {a.build.fast_shift, a.build.neuron_unit});
  eskin::cycle::DtmfTop fpga(params.plan);  // refuses a build it does not model

  eskin::vboard::BoardConfig cfg;
  nlohmann::json ready =
      eskin::vboard::dtmf_board_config(a, scene, params.clk_hz(), params.baud(), params.adc_shift(), cfg);
  ready["fidelity"] = "cycle";

  eskin::vboard::PtyPort pty;
  if (!a.pty_link.empty()) pty.link(a.pty_link);
  return eskin::vboard::run_to_end(a, json, fpga, pty, cfg, params.key, ready,
                                   [] { return nlohmann::json{{"fidelity", "cycle"}}; });
}

}  // namespace

int sc_main(int argc, char** argv) {
  return eskin::vboard::vboard_cli_main(
      argc, argv,
      "eskin-vboard-cycle: a scene on the SystemC virtual board with the FPGA's clock-exact C++ "
      "models (the cycle level); its serial port is a pseudo-terminal",
      eskin::vboard::kSkinTailS, run, true);
}
