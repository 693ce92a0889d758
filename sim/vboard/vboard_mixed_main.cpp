// eskin-vboard-mKEY SCENE.yaml: a scene with both a DTMF skin and Hall
// sensors on the SystemC virtual board: rtl/mixed_top.v (dtmf_top and
// hall_top sharing one host link) at the scene's build, the AD7476A on its
// SPI pins fed with the skin's samples, the scene's MLX90393s (and
// TCA9548As) on its I2C buses, its UART on a pseudo-terminal (docs/vboard.md,
// "Mixed scenes").
//
// Compiled once per mixed build (sim/vboard/mixed_build.h), with the
// Verilated SystemC model of rtl/mixed_top.v for it. The run ends when the
// ADC has taken the skin's samples plus the tail. The `done` line carries
// drdy_ns per Hall sensor slot, as the Hall board's does.

#include <cmath>
#include <cstdio>
#include <memory>
#include <systemc>
#include <type_traits>

#include "Vmixed_top.h"
#include "sim/hall_sensor_array.h"
#include "sim/hall_world.h"
#include "sim/scene.h"
#include "sim/vboard/direct_wire.h"
#include "sim/vboard/mixed_build.h"
#include "sim/vboard/vboard_cli.h"
#include "sim/vboard/verilated_step.h"
#include "sim/vboard/verilated_top.h"
#include "sim/vboard/virtual_board.h"

#ifndef VBOARD_PARAMS_KEY
#error "VBOARD_PARAMS_KEY: the mixed build this board is made for"
#endif
#if !defined(VBOARD_ENGINE_FAST_SHIFT) || !defined(VBOARD_NEURON_UNIT)
#error "VBOARD_ENGINE_FAST_SHIFT, VBOARD_NEURON_UNIT: the frame engine of this board's build (0/1)"
#endif
#if !defined(VBOARD_CLK_HZ) || !defined(VBOARD_BAUD)
#error "VBOARD_CLK_HZ, VBOARD_BAUD: the build's clock and UART rate"
#endif

ESKIN_EXPOSE_EVAL_STEP(Vmixed_top)

namespace {

constexpr eskin::vboard::EngineOptions kEngine{VBOARD_ENGINE_FAST_SHIFT != 0,
                                               VBOARD_NEURON_UNIT != 0};

using eskin::vboard::DirectPort;
using eskin::vboard::DirectWire;
template <class Port>
using PortValue = typename std::remove_reference_t<Port>::data_type;
using BusBits = PortValue<decltype(std::declval<Vmixed_top>().scl_i)>;
using SensorBits = PortValue<decltype(std::declval<Vmixed_top>().drdy)>;

class VerilatedMixedFpga final : public eskin::vboard::VerilatedTop<Vmixed_top> {
 public:
  VerilatedMixedFpga()
      : rst_n_("rst_n", true), sdata_("adc_sdata"), cs_n_("adc_cs_n", true),
        sclk_("adc_sclk", true), rxd_("uart_rxd", true), txd_("uart_txd", true),
        scl_i_("scl_i"), sda_i_("sda_i"), scl_oe_("scl_oe"), sda_oe_("sda_oe"), drdy_("drdy") {
    top_.rst_n(rst_n_);
    top_.adc_sdata(sdata_);
    top_.adc_cs_n(cs_n_);
    top_.adc_sclk(sclk_);
    top_.uart_rxd(rxd_);
    top_.uart_txd(txd_);
    top_.scl_i(scl_i_);
    top_.sda_i(sda_i_);
    top_.scl_oe(scl_oe_);
    top_.sda_oe(sda_oe_);
    top_.drdy(drdy_);
  }

  eskin::vboard::FpgaOutputs cycle(const eskin::vboard::FpgaInputs& in, uint64_t t_ps) override {
    rst_n_.write(!in.reset);
    sdata_.write(in.adc_sdata);
    rxd_.write(in.uart_rxd);
    scl_i_.write(BusBits(in.scl_i));
    sda_i_.write(BusBits(in.sda_i));
    drdy_.write(SensorBits(in.drdy));
    clock(t_ps);
    eskin::vboard::FpgaOutputs out;
    out.adc_cs_n = cs_n_.read();
    out.adc_sclk = sclk_.read();
    out.uart_txd = txd_.read();
    out.scl_oe = uint64_t(scl_oe_.read());
    out.sda_oe = uint64_t(sda_oe_.read());
    return out;
  }

 private:
  DirectWire rst_n_, sdata_, cs_n_, sclk_, rxd_, txd_;
  DirectPort<BusBits> scl_i_, sda_i_, scl_oe_, sda_oe_;
  DirectPort<SensorBits> drdy_;
};

int run(const eskin::vboard::VboardArgs& a, FILE* json) {
  const eskin::sim::Scene scene = eskin::sim::load_scene(a.scene);
  const eskin::vboard::FpgaBuild dtmf =
      eskin::vboard::fpga_build_for(scene, "", VBOARD_CLK_HZ, VBOARD_BAUD, kEngine);
  const eskin::vboard::MixedBuild build = eskin::vboard::mixed_build_for(scene, dtmf);
  eskin::vboard::require_build(a.scene, "mixed", build.key, VBOARD_PARAMS_KEY);

  eskin::vboard::BoardConfig cfg;
  cfg.clk_hz = dtmf.clk_hz();
  cfg.baud = dtmf.baud();
  const eskin::sim::HallWorld hall_world(scene.hall);
  eskin::sim::HallSensorArray sensors(hall_world, scene.hall.config, build.hall.spec);
  cfg.hall = &sensors;
  eskin::vboard::apply_start_options(a, cfg, scene.skin.rows + scene.skin.cols,
                                     scene.hall.config.bus_count());
  const size_t scene_samples = eskin::vboard::load_skin_samples(cfg, scene, dtmf.adc_shift(), a.tail_s);

  eskin::vboard::PtyPort pty;
  if (!a.pty_link.empty()) pty.link(a.pty_link);
  // The DTMF part's microcode and constants, this run's own files (as in
  // vboard_main.cpp).
  const eskin::vboard::RunFiles files(scene, VBOARD_CLK_HZ, VBOARD_BAUD, kEngine);
  add_plusargs(files);
  VerilatedMixedFpga fpga;
  fpga.set_half_period_ps(uint64_t(std::llround(0.5e12 / cfg.clk_hz)));
  return eskin::vboard::run_to_end(
      a, json, fpga, pty, cfg, VBOARD_PARAMS_KEY,
      {{"top", "mixed_top"},
       {"sample_hz", scene.skin.adc.rate_hz},
       {"samples", cfg.samples},
       {"scene_samples", scene_samples},
       {"sensors", sensors.size()},
       {"buses", sensors.bus_count()}},
      [&sensors] { return nlohmann::json{{"drdy_ns", eskin::vboard::drdy_times_ns(sensors)}}; });
}

}  // namespace

int sc_main(int argc, char** argv) {
  return eskin::vboard::vboard_cli_main(
      argc, argv,
      "eskin-vboard: a scene with a DTMF skin and Hall sensors on the SystemC virtual board "
      "(mixed build " VBOARD_PARAMS_KEY "); its serial port is a pseudo-terminal",
      eskin::vboard::kSkinTailS, run);
}
