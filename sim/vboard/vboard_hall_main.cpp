// eskin-vboard-hKEY SCENE.yaml: a Hall scene on the SystemC virtual board:
// rtl/hall_top.v at the scene's build, the scene's MLX90393s (and
// TCA9548As) on its I2C buses, its UART on a pseudo-terminal
// (docs/vboard.md, "Hall skins").
//
// Compiled once per Hall build (sim/vboard/hall_build.h), with the
// Verilated SystemC model of rtl/hall_top.v for it (class Vhall_top,
// VBOARD_PARAMS_KEY naming the build). The `done` line adds, per FPGA
// sensor slot, the time (ns) each conversion the FPGA read completed
// (DRDY rose): the start of the DRDY -> host latency.

#include <cmath>
#include <cstdio>
#include <memory>
#include <systemc>
#include <type_traits>

#include "Vhall_top.h"
#include "sim/hall_sensor_array.h"
#include "sim/hall_world.h"
#include "sim/scene.h"
#include "sim/vboard/direct_wire.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/vboard_cli.h"
#include "sim/vboard/verilated_step.h"
#include "sim/vboard/verilated_top.h"
#include "sim/vboard/virtual_board.h"

#ifndef VBOARD_PARAMS_KEY
#error "VBOARD_PARAMS_KEY: the Hall build this board is made for"
#endif
#if !defined(VBOARD_CLK_HZ) || !defined(VBOARD_BAUD)
#error "VBOARD_CLK_HZ, VBOARD_BAUD: the FPGA clock and UART rate of this board's build"
#endif

ESKIN_EXPOSE_EVAL_STEP(Vhall_top)

namespace {

using eskin::vboard::DirectPort;
using eskin::vboard::DirectWire;
// Verilator types a port by its width (bool, uint32_t, uint64_t): the bus
// and sensor vectors' widths are the build's NB and NB * NSB.
template <class Port>
using PortValue = typename std::remove_reference_t<Port>::data_type;
using BusBits = PortValue<decltype(std::declval<Vhall_top>().scl_i)>;
using SensorBits = PortValue<decltype(std::declval<Vhall_top>().drdy)>;

class VerilatedHallFpga final : public eskin::vboard::VerilatedTop<Vhall_top> {
 public:
  VerilatedHallFpga()
      : rst_("rst", true), rxd_("uart_rxd", true), txd_("uart_txd", true), scl_i_("scl_i"),
        sda_i_("sda_i"), scl_oe_("scl_oe"), sda_oe_("sda_oe"), drdy_("drdy"),
        pkt_valid_("pkt_valid"), pkt_ready_("pkt_ready"), pkt_data_("pkt_data") {
    top_.rst(rst_);
    top_.uart_rxd(rxd_);
    top_.uart_txd(txd_);
    top_.scl_i(scl_i_);
    top_.sda_i(sda_i_);
    top_.scl_oe(scl_oe_);
    top_.sda_oe(sda_oe_);
    top_.drdy(drdy_);
    // The top owns its link (EXT_LINK = 0): no packet stream to take.
    top_.pkt_valid(pkt_valid_);
    top_.pkt_ready(pkt_ready_);
    top_.pkt_data(pkt_data_);
  }

  eskin::vboard::FpgaOutputs cycle(const eskin::vboard::FpgaInputs& in, uint64_t t_ps) override {
    rst_.write(cycles_ < 2 || in.reset);  // hall_top's synchronous reset, two clocks at power-up
    rxd_.write(in.uart_rxd);
    scl_i_.write(BusBits(in.scl_i));
    sda_i_.write(BusBits(in.sda_i));
    drdy_.write(SensorBits(in.drdy));
    clock(t_ps);
    ++cycles_;
    eskin::vboard::FpgaOutputs out;
    out.uart_txd = txd_.read();
    out.scl_oe = uint64_t(scl_oe_.read());
    out.sda_oe = uint64_t(sda_oe_.read());
    return out;
  }

 private:
  DirectWire rst_, rxd_, txd_;
  DirectPort<BusBits> scl_i_, sda_i_, scl_oe_, sda_oe_;
  DirectPort<SensorBits> drdy_;
  DirectWire pkt_valid_, pkt_ready_;
  DirectPort<PortValue<decltype(std::declval<Vhall_top>().pkt_data)>> pkt_data_;
  uint64_t cycles_ = 0;
};

int run(const eskin::vboard::VboardArgs& a, FILE* json) {
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.scene);
  const eskin::vboard::HallBuild build = eskin::vboard::hall_build_for(scene, VBOARD_CLK_HZ);
  eskin::vboard::require_build(a.scene, "Hall", build.key, VBOARD_PARAMS_KEY);
  if (scene.has_skin)
    throw std::runtime_error(a.scene + ": a scene with a DTMF skin and Hall sensors needs both "
                             "tops on one board, which the virtual board does not have yet");

  const eskin::sim::HallWorld world(scene.hall);
  eskin::sim::HallSensorArray sensors(world, scene.hall.config, build.spec);
  eskin::vboard::BoardConfig cfg;
  cfg.clk_hz = double(build.clk_hz);
  cfg.baud = double(build.baud);
  cfg.hall = &sensors;
  cfg.cycles = uint64_t(std::llround((scene.duration_s + a.tail_s) * cfg.clk_hz));
  eskin::vboard::apply_start_options(a, cfg, 0, scene.hall.config.bus_count());

  eskin::vboard::PtyPort pty;
  if (!a.pty_link.empty()) pty.link(a.pty_link);
  VerilatedHallFpga fpga;
  fpga.set_half_period_ps(uint64_t(std::llround(0.5e12 / cfg.clk_hz)));
  return eskin::vboard::run_to_end(
      a, json, fpga, pty, cfg, VBOARD_PARAMS_KEY,
      {{"top", "hall_top"},
       {"sensors", sensors.size()},
       {"buses", sensors.bus_count()},
       {"duration_s", scene.duration_s},
       {"cycles", cfg.cycles}},
      [&sensors] { return nlohmann::json{{"drdy_ns", eskin::vboard::drdy_times_ns(sensors)}}; });
}

}  // namespace

int sc_main(int argc, char** argv) {
  return eskin::vboard::vboard_cli_main(
      argc, argv,
      "eskin-vboard: a Hall scene on the SystemC virtual board (Hall build " VBOARD_PARAMS_KEY
      "); its serial port is a pseudo-terminal",
      0.01, run);
}
