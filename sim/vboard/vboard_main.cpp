// eskin-vboard SCENE.yaml: the scene on the SystemC virtual board, its
// FPGA's serial port on a pseudo-terminal (docs/vboard.md).
//
// This file is compiled once per FPGA parameter set, with the Verilated
// SystemC model of rtl/dtmf_top.v built for that set (class Vdtmf_top,
// VBOARD_PARAMS_KEY naming the set); everything else is in eskin_vboard.
//
// stdout carries one JSON object per line for the program that started the
// board: {"event":"ready",...} once the pty exists, {"event":"done",...}
// when every byte is in it; then, once the reader has read them, the board
// hangs up (closes the pty). Messages go to stderr.

#include <cmath>
#include <cstdio>
#include <memory>
#include <systemc>
#include <type_traits>

#include "Vdtmf_top.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/direct_wire.h"
#include "sim/vboard/vboard_cli.h"
#include "sim/vboard/verilated_step.h"
#include "sim/vboard/verilated_top.h"
#include "sim/vboard/virtual_board.h"

#ifndef VBOARD_PARAMS_KEY
#error "VBOARD_PARAMS_KEY: the FPGA parameter set this board is built for"
#endif
#if !defined(VBOARD_CLK_HZ) || !defined(VBOARD_BAUD)
#error "VBOARD_CLK_HZ, VBOARD_BAUD: the FPGA clock and UART rate of this board's build"
#endif
#if !defined(VBOARD_ENGINE_FAST_SHIFT) || !defined(VBOARD_NEURON_UNIT)
#error "VBOARD_ENGINE_FAST_SHIFT, VBOARD_NEURON_UNIT: the frame engine of this board's build (0/1)"
#endif

ESKIN_EXPOSE_EVAL_STEP(Vdtmf_top)

namespace {

constexpr eskin::vboard::EngineOptions kEngine{VBOARD_ENGINE_FAST_SHIFT != 0,
                                               VBOARD_NEURON_UNIT != 0};

using eskin::vboard::DirectWire;
template <class Port>
using PortValue = typename std::remove_reference_t<Port>::data_type;

class VerilatedFpga final : public eskin::vboard::VerilatedTop<Vdtmf_top> {
 public:
  VerilatedFpga()
      : rst_n_("rst_n", true), sdata_("adc_sdata"), rxd_("uart_rxd", true), cs_n_("adc_cs_n", true),
        sclk_("adc_sclk", true), txd_("uart_txd", true), pkt_valid_("pkt_valid"),
        pkt_ready_("pkt_ready"), pkt_data_("pkt_data") {
    top_.adc_clk(clk_);  // ADC_CLK_HZ = 0: the ADC runs on clk (this port is unused)
    top_.rst_n(rst_n_);
    top_.adc_sdata(sdata_);
    top_.uart_rxd(rxd_);
    top_.adc_cs_n(cs_n_);
    top_.adc_sclk(sclk_);
    top_.uart_txd(txd_);
    // The top owns its link (EXT_LINK = 0): no packet stream to take.
    top_.pkt_valid(pkt_valid_);
    top_.pkt_ready(pkt_ready_);
    top_.pkt_data(pkt_data_);
  }

  eskin::vboard::FpgaOutputs cycle(const eskin::vboard::FpgaInputs& in, uint64_t t_ps) override {
    rst_n_.write(!in.reset);
    sdata_.write(in.adc_sdata);
    rxd_.write(in.uart_rxd);
    clock(t_ps);
    eskin::vboard::FpgaOutputs out;
    out.adc_cs_n = cs_n_.read();
    out.adc_sclk = sclk_.read();
    out.uart_txd = txd_.read();
    return out;
  }

 private:
  DirectWire rst_n_, sdata_, rxd_, cs_n_, sclk_, txd_, pkt_valid_, pkt_ready_;
  eskin::vboard::DirectPort<PortValue<decltype(std::declval<Vdtmf_top>().pkt_data)>> pkt_data_;
};

int run(const eskin::vboard::VboardArgs& a, FILE* json) {
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.scene);
  const eskin::vboard::FpgaBuild params = eskin::vboard::fpga_build_for(scene, "", VBOARD_CLK_HZ, VBOARD_BAUD, kEngine);
  eskin::vboard::require_build(a.scene, "FPGA", params.key, VBOARD_PARAMS_KEY);

  eskin::vboard::BoardConfig cfg;
  const nlohmann::json ready =
      eskin::vboard::dtmf_board_config(a, scene, params.clk_hz(), params.baud(), params.adc_shift(), cfg);

  eskin::vboard::PtyPort pty;
  if (!a.pty_link.empty()) pty.link(a.pty_link);
  // The scene's microcode and constants, this run's own files, read by the
  // model at its first evaluation (during sc_start).
  const eskin::vboard::RunFiles files(scene, VBOARD_CLK_HZ, VBOARD_BAUD, kEngine);
  add_plusargs(files);
  VerilatedFpga fpga;
  fpga.set_half_period_ps(uint64_t(std::llround(0.5e12 / params.clk_hz())));
  return eskin::vboard::run_to_end(a, json, fpga, pty, cfg, VBOARD_PARAMS_KEY, ready);
}

}  // namespace

int sc_main(int argc, char** argv) {
  return eskin::vboard::vboard_cli_main(
      argc, argv,
      "eskin-vboard: a scene on the SystemC virtual board (FPGA build " VBOARD_PARAMS_KEY
      "); its serial port is a pseudo-terminal",
      eskin::vboard::kSkinTailS, run);
}
