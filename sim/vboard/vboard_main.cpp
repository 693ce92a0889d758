// eskin-vboard SCENE.yaml: the scene on the SystemC virtual board, its
// FPGA's serial port on a pseudo-terminal (docs/vboard.md).
//
// This file is compiled once per FPGA parameter set, with the Verilated
// SystemC model of rtl/dtmf_top.v built for that set (class Vdtmf_top,
// VBOARD_PARAMS_KEY naming the set); everything else is in eskin_vboard.
//
// stdout carries one JSON object per line for the program that started the
// board: {"event":"ready",...} once the pty exists, {"event":"done",...}
// when every byte is in it. Messages go to stderr.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>
#include <memory>
#include <systemc>

#include "Vdtmf_top.h"
#include "verilated_fst_c.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/direct_wire.h"
#include "sim/vboard/virtual_board.h"
#include "sim/world_model.h"

#ifndef VBOARD_PARAMS_KEY
#error "VBOARD_PARAMS_KEY: the FPGA parameter set this board is built for"
#endif
#if !defined(VBOARD_CLK_HZ) || !defined(VBOARD_BAUD)
#error "VBOARD_CLK_HZ, VBOARD_BAUD: the FPGA clock and UART rate of this board's build"
#endif
#ifndef VBOARD_BUILD_DIR
#error "VBOARD_BUILD_DIR: where the model reads KEY.ucode.hex and KEY.krom.hex"
#endif

namespace {

using eskin::vboard::DirectWire;
FILE* json_out = stdout;

// Verilator's SystemC model evaluates itself in an SC_METHOD sensitive to
// its input ports, i.e. one SystemC delta cycle per clock edge, which costs
// more than the evaluation (docs/vboard.md). The board clocks it directly
// instead, through the model's own eval_step(), which Verilator declares
// private; an explicit instantiation may name a private member (C++17
// [temp.explicit]/14), which hands its address to eval_step_of().
using EvalStep = void (Vdtmf_top::*)();
EvalStep eval_step_of();
template <EvalStep M>
struct ExposeEvalStep {
  friend EvalStep eval_step_of() { return M; }
};
template struct ExposeEvalStep<&Vdtmf_top::eval_step>;

class VerilatedFpga final : public eskin::vboard::FpgaModel {
 public:
  VerilatedFpga()
      : clk_("clk"), rst_n_("rst_n", true), sdata_("adc_sdata"), rxd_("uart_rxd", true),
        cs_n_("adc_cs_n", true), sclk_("adc_sclk", true), txd_("uart_txd", true), top_("fpga") {
    top_.clk(clk_);
    top_.rst_n(rst_n_);
    top_.adc_sdata(sdata_);
    top_.uart_rxd(rxd_);
    top_.adc_cs_n(cs_n_);
    top_.adc_sclk(sclk_);
    top_.uart_txd(txd_);
  }
  ~VerilatedFpga() override { close_trace(); }

  eskin::vboard::FpgaOutputs cycle(const eskin::vboard::FpgaInputs& in, uint64_t t_ps) override {
    sdata_.write(in.adc_sdata);
    rxd_.write(in.uart_rxd);
    clk_.write(true);
    (top_.*eval_)();
    if (fst_) fst_->dump(t_ps);
    clk_.write(false);
    (top_.*eval_)();
    if (fst_) fst_->dump(t_ps + half_ps_);
    return {cs_n_.read(), sclk_.read(), txd_.read()};
  }

  void open_trace(const std::string& path) override {
    Verilated::traceEverOn(true);
    fst_ = std::make_unique<VerilatedFstC>();
    top_.trace(fst_.get(), 99);
    fst_->open(path.c_str());
  }
  void close_trace() override {
    if (fst_) fst_->close();
    fst_.reset();
  }
  void set_half_period_ps(uint64_t h) { half_ps_ = h; }

 private:
  DirectWire clk_, rst_n_, sdata_, rxd_, cs_n_, sclk_, txd_;
  Vdtmf_top top_;
  EvalStep eval_ = eval_step_of();
  std::unique_ptr<VerilatedFstC> fst_;
  uint64_t half_ps_ = 0;
};

struct Args {
  std::string scene, pty_link, trace;
  bool no_wait = false;
  double reader_timeout_s = 60;
  double tail_s = 0.002;
};

int run(const Args& a) {
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.scene);
  const eskin::vboard::FpgaBuild params = eskin::vboard::fpga_build_for(scene, "", VBOARD_CLK_HZ, VBOARD_BAUD);
  if (params.key != VBOARD_PARAMS_KEY)
    throw std::runtime_error(fmt::format(
        "{}: this scene needs the FPGA build '{}', this virtual board is '{}' (run the scene "
        "with `eskin simulate`, which builds the board it needs)",
        a.scene, params.key, VBOARD_PARAMS_KEY));

  eskin::vboard::BoardConfig cfg;
  cfg.clk_hz = params.clk_hz();
  cfg.baud = params.baud();
  eskin::sim::WorldModel world(scene);
  for (int c : world.all_codes()) cfg.codes.push_back(uint16_t(c << params.adc_shift()));
  // A tail of mid-scale samples after the scene lets the last frames out.
  const size_t tail = size_t(std::ceil(a.tail_s * scene.skin.adc.rate_hz));
  cfg.codes.resize(cfg.codes.size() + tail, uint16_t(1u << 11));
  cfg.samples = cfg.codes.size();
  cfg.codes.resize(cfg.codes.size() + 64, uint16_t(1u << 11));  // a batch may end past it
  cfg.wait_for_reader = !a.no_wait;
  cfg.reader_timeout_s = a.reader_timeout_s;
  cfg.trace = a.trace;

  eskin::vboard::PtyPort pty;
  if (!a.pty_link.empty()) pty.link(a.pty_link);
  // The model reads the scene's microcode and constants (UCODE_HEX,
  // KROM_HEX: fixed paths in VBOARD_BUILD_DIR) when it is constructed;
  // another board of this build may be about to write its own there.
  std::unique_ptr<eskin::vboard::BuildLock> lock =
      std::make_unique<eskin::vboard::BuildLock>(VBOARD_BUILD_DIR, VBOARD_PARAMS_KEY);
  eskin::vboard::fpga_build_for(scene, VBOARD_BUILD_DIR, VBOARD_CLK_HZ, VBOARD_BAUD);
  VerilatedFpga fpga;
  lock.reset();
  fpga.set_half_period_ps(uint64_t(std::llround(0.5e12 / params.clk_hz())));
  eskin::vboard::VirtualBoard board("board", fpga, pty, cfg);

  std::fprintf(json_out,
      "{\"event\":\"ready\",\"pty\":\"%s\",\"params\":\"%s\",\"clk_hz\":%.0f,\"baud\":%.0f,"
      "\"sample_hz\":%.0f,\"samples\":%llu,\"scene_samples\":%zu}\n",
      pty.slave_path().c_str(), VBOARD_PARAMS_KEY, params.clk_hz(), params.baud(),
      scene.skin.adc.rate_hz, (unsigned long long)cfg.samples, world.total_samples());
  std::fflush(json_out);

  sc_core::sc_start();
  fpga.close_trace();
  const auto& s = board.stats();
  if (!s.error.empty()) throw std::runtime_error(s.error);
  std::string frames;
  for (double t : s.frame_end_ns) frames += fmt::format("{}{:.1f}", frames.empty() ? "" : ",", t);
  std::fprintf(json_out,
      "{\"event\":\"done\",\"cycles\":%llu,\"sim_s\":%.9f,\"wall_s\":%.6f,\"cpu_s\":%.6f,"
      "\"samples\":%llu,\"adc_violations\":%llu,\"adc_first_violation\":\"%s\","
      "\"bytes_to_host\":%llu,\"bytes_to_fpga\":%llu,\"usb_framing_errors\":%llu,"
      "\"reader_baud\":%.0f,\"baud_mismatches\":%llu,\"reader_closed\":%s,"
      "\"frame_end_ns\":[%s]}\n",
      (unsigned long long)s.cycles, s.sim_s, s.wall_s, s.cpu_s, (unsigned long long)s.samples,
      (unsigned long long)s.adc_violations, s.first_adc_violation.c_str(),
      (unsigned long long)s.bytes_to_host, (unsigned long long)s.bytes_to_fpga,
      (unsigned long long)s.usb_framing_errors, s.reader_baud,
      (unsigned long long)s.baud_mismatches, s.reader_closed ? "true" : "false", frames.c_str());
  std::fflush(json_out);
  // The reader may still be draining the pty: closing the master now would
  // hang up its side. Wait until it closes (or the timeout).
  for (int i = 0; i < int(a.reader_timeout_s * 100) && !pty.reader_closed() && s.reader_baud > 0; ++i)
    usleep(10000);
  return 0;
}

}  // namespace

int sc_main(int argc, char** argv) {
  // stdout is for the JSON lines only: keep it on its own stream and send
  // everything else written to fd 1 (SystemC's banner) to stderr.
  json_out = fdopen(dup(1), "w");
  dup2(2, 1);
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  Args a;
  CLI::App app{"eskin-vboard: a scene on the SystemC virtual board (FPGA build " VBOARD_PARAMS_KEY
               "); its serial port is a pseudo-terminal"};
  app.add_option("scene", a.scene, "scene file (YAML, docs/scenes.md)")->required()->check(CLI::ExistingFile);
  app.add_option("--pty-link", a.pty_link, "also make this path a symlink to the pty");
  app.add_option("--trace", a.trace, "write an FST waveform of the FPGA (GTKWave; ~7x slower)");
  app.add_flag("--no-wait", a.no_wait,
               "start at once instead of waiting for a reader to set a baud rate");
  app.add_option("--reader-timeout", a.reader_timeout_s, "seconds to wait for a reader")
      ->capture_default_str();
  app.add_option("--tail", a.tail_s, "seconds of idle input after the scene (last frames out)")
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "eskin-vboard: error: %s\n", e.what());
    return 2;
  }
}
