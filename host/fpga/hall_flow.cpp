// `eskin bitstream` for a scene with Hall sensors: hall_top (or mixed_top,
// with the scene's skin) in the board's Hall wrapper, its parameters derived
// as the virtual board derives them (sim/vboard/hall_build.h,
// sim/vboard/mixed_build.h), its I2C and DRDY pins from hall_pins.h.
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "host/fpga/core_flows.h"
#include "host/fpga/core_wrapper.h"
#include "host/fpga/hall_pins.h"
#include "host/fpga/tool_run.h"
#include "sim/vboard/hall_build.h"
#include "sim/vboard/mixed_build.h"

namespace eskin::fpga {

namespace fs = std::filesystem;

bool prepare_hall_build(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                        FlowReport& r, ToolRun& t) {
  const bool mixed = r.core == Core::Mixed;
  const HallConfig& hc = scene.hall.config;
  // The buses first (the spec names a hall: field it cannot build): a scene
  // with more pins than the board has stops here, before any tool.
  r.hall.spec = sim::hall_top_spec(hc);
  for (HallDecode d : hc.decode) r.hall.decode.push_back(to_string(d));
  r.hall.pins_available = int(hall_pin_pool(b).size());
  r.hall.pins = assign_hall_pins(b, r.hall.spec.nb, r.hall.spec.nsb);
  if (!r.hall.pins.failure.empty()) {
    r.failure = r.hall.pins.failure;
    return false;
  }

  std::vector<hls::VerilogParam> core;
  Clocking clk;
  if (mixed) {
    // One clock for both tops: the DTMF build's (the slowest the skin keeps
    // up at, or --clk-mhz), which hall_top needs in whole MHz.
    vboard::FpgaBuild dtmf;
    if (!plan_dtmf_core(b, scene, opt, r, clk, dtmf.params, false)) return false;  // one clock
    dtmf.plan.spec = r.spec;
    const vboard::MixedBuild m = vboard::mixed_build_for(scene, dtmf);  // names the field
    r.hall.spec = m.hall.spec;
    core = from_g_args(m.verilator_args());
    for (const auto& p : dtmf.params)  // the microcode files, which the virtual board loads itself
      if (p.name == "UCODE_HEX" || p.name == "KROM_HEX") core.push_back(p);
    clk = choose_hall_clock(b, clk.clk_hz);  // the same clock, the Hall wrapper's parameters
  } else {
    clk = choose_hall_clock(b, opt.clk_hz);
    const vboard::HallBuild h = vboard::hall_build_for(scene, clk.clk_hz, clk.baud);
    r.hall.spec = h.spec;
    core = from_g_args(h.params);
  }
  r.clk_hz = clk.clk_hz;
  r.baud = clk.baud;
  r.pll = !(b.hall_osc_clock && clk.clk_hz == b.osc_hz);

  const fs::path out = fs::absolute(opt.out_dir);
  fs::create_directories(out);
  const std::string name = mixed ? "mixed_scene" : "hall_scene";
  const fs::path wrapper = out / (name + ".v");
  const int nb = r.hall.spec.nb, nsb = r.hall.spec.nsb;
  std::ofstream(wrapper) << (mixed ? mixed_core_wrapper(name, nb, nsb, core)
                                   : hall_core_wrapper(name, nb, nsb, core));
  const bool ice = b.family == Family::Ice40;
  const fs::path pins = out / (b.hall_wrapper + (ice ? ".pcf" : ".lpf"));
  const fs::path base = fs::path(opt.source_dir) / b.constraints;
  if (!fs::exists(base)) throw std::runtime_error("cannot read " + base.string());
  std::ofstream(pins) << hall_constraints(b, slurp(base.string()), r.hall.pins);

  t.top = b.hall_wrapper;
  t.reads = {wrapper.string()};
  t.defines = {"ESKIN_HALL_CORE=" + name};
  if (mixed) t.defines.push_back("ESKIN_MIXED=1");
  t.constraints = pins.string();
  t.clk_hz = clk.clk_hz;
  t.params = {{"NB", std::to_string(nb)}, {"NSB", std::to_string(nsb)}};
  t.params.insert(t.params.end(), clk.wrapper_params.begin(), clk.wrapper_params.end());
  r.params = core;
  r.params.insert(r.params.end(), t.params.begin(), t.params.end());
  return true;
}

void run_hall_flow(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                   FlowReport& r) {
  ToolRun t;
  if (prepare_hall_build(b, scene, opt, r, t)) run_tools(b, opt, t, r);
}

}  // namespace eskin::fpga
