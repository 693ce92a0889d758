// `eskin bitstream`'s report (host/fpga/flow.h): OUT/bitstream_report.json
// and the table printed and written to OUT/bitstream_report.txt. A DTMF
// build reports its skin, clock budget and frame engine load; a Hall build
// its buses, sensors, decoding and pins; a mixed build both; every build
// the resources nextpnr used and each clock's Fmax against its requirement.
#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "host/fpga/flow.h"

namespace eskin::fpga {

namespace {

std::string mhz(double hz) { return fmt::format("{:.6g}", hz / 1e6); }

void dtmf_json(const FlowReport& r, nlohmann::json& j) {
  j["skin"] = {{"rows", r.spec.rows},
               {"cols", r.spec.cols},
               {"carriers", r.spec.rows + r.spec.cols},
               {"window", r.spec.window},
               {"sample_hz", r.spec.sample_hz},
               {"spikes", r.spec.spikes}};
  j["datapath"] = datapath_name(r.spec.datapath);
  j["clock"]["step"] = r.step;
  j["clock"]["sample_period_clocks"] = r.budget.period;
  j["clock"]["frame_clocks"] = r.budget.frame_clocks;
  j["clock"]["core_min_hz"] = r.core_min_hz;
  j["clock"]["core_min_reason"] = r.core_min_reason;
  // The DFT's lanes (host/fpga/flow.h choose_sdft_lanes), its clocks per
  // sample at them (KS = carriers + DC when demixing): a frame's sample,
  // any other (no tokens), and the least sample period those allow
  // (common/eskin/dtmf_top_plan.h's budget).
  j["dft"] = {{"lanes", r.spec.sdft_lanes},
              {"channels", r.spec.rows + r.spec.cols + (r.spec.demix ? 1 : 0)},
              {"frame_sample_clocks", r.budget.sdft_clocks},
              {"skipped_sample_clocks", r.budget.sdft_skip_clocks},
              {"min_sample_period_clocks", r.budget.sdft_min_period}};
  nlohmann::json cases = nlohmann::json::object();
  for (const auto& [name, clocks] : r.load.cases) cases[name] = clocks;
  nlohmann::json routines = nlohmann::json::array();
  for (const auto& [name, clocks] : r.load.stress_routines)
    routines.push_back({{"routine", name}, {"clocks", clocks}});
  j["engine"] = {{"policy", r.policy == LoadPolicy::Stress ? "stress" : "scene"},
                 {"fast_shift", r.spec.engine_fast_shift},
                 {"neuron_unit", r.spec.neuron_unit},
                 {"neuron_lanes", r.spec.neuron_lanes},
                 {"required_clocks", r.engine_clocks},
                 {"scene_longest_frame_clocks", r.load.scene_clocks},
                 {"scene_frames", r.load.scene_frames},
                 {"stress_longest_frame_clocks", r.load.stress_clocks},
                 {"stress_longest_frame_signal", r.load.stress_case},
                 {"stress_frames", r.load.stress_frames},
                 {"stress_other_clocks", r.load.stress_other_clocks},
                 {"stress_packet_clocks", r.load.stress_packet_clocks},
                 {"stress_bound_clocks", r.load.stress_bound()},
                 {"longest_command_clocks", r.load.command_clocks},
                 {"chain_clocks", r.load.chain_clocks},
                 {"longest_command", r.load.command_case},
                 {"cases", cases},
                 {"stress_longest_frame_by_routine", routines}};
  // The static bound (ucode/dtmf_frame_bound.h) and its limit.
  j["engine"]["bound"] = {{"frame_clocks", r.bound.frame},
                          {"command_clocks", r.bound.command},
                          {"chain_clocks", r.bound.chain},
                          {"total_clocks", r.bound.total()},
                          {"limit_percent", hls::dtmf_frame_bound_limit_percent(r.spec.datapath)},
                          {"limit_clocks", r.budget.bound_limit_clocks},
                          {"any_frame_clocks", r.bound.frame_any},
                          {"any_command_clocks", r.bound.command_any}};
}

void hall_json(const FlowReport& r, nlohmann::json& j) {
  nlohmann::json pins = nlohmann::json::array();
  for (const auto& p : r.hall.pins.pins)
    pins.push_back({{"signal", p.signal}, {"site", p.pin.site}, {"connector", p.pin.connector},
                    {"open_drain", p.i2c}});
  j["hall"] = {{"buses", r.hall.spec.nb},
               {"sensors_per_bus", r.hall.spec.nsb},
               {"sensors", r.hall.spec.nb * r.hall.spec.nsb},
               {"decode", r.hall.decode},
               {"pins_needed", r.hall.pins.needed},
               {"pins_available", r.hall.pins_available},
               {"pins", pins}};
}

std::string dtmf_table(const FlowReport& r) {
  const double frame = double(std::max(1L, r.budget.frame_clocks));
  const bool streaming = r.spec.datapath == hls::DtmfDatapath::Streaming;
  std::string t = fmt::format(
      "skin {}x{}, {} carriers, window {}, {:g} S/s, step {}\n"
      "clock {} MHz{} (the skin's core needs at least {} MHz: {}), UART {:g} Mbaud\n"
      "DFT: {} lane{}, a frame's sample {} clocks, the others {}: a period of {} or more, "
      "the sample's is {}\n"
      "{}"
      "{} ({} shifter, neurons on {}), clocks of the {} a frame has ({}):\n"
      "  scene's longest frame {:>9} ({:.0f} %, {} frames)\n"
      "  stress longest frame  {:>9} ({:.0f} %, {}){}\n"
      "  + longest command     {:>9} ({:.0f} %, {})\n{}"
      "  static bound          {:>9} ({:.0f} %: frame {} + command {}; at most {} % of a frame)\n"
      "  the clock carries the {}\n",
      r.spec.rows, r.spec.cols, r.spec.rows + r.spec.cols, r.spec.window, r.spec.sample_hz,
      r.step, mhz(double(r.spec.clk_hz)),
      r.spec.adc_clk_hz > 0
          ? fmt::format(", the ADC on its own {} MHz clock", mhz(double(r.spec.adc_clk_hz)))
          : std::string(),
      mhz(double(r.core_min_hz)), r.core_min_reason,
      double(r.spec.baud) / 1e6, r.spec.sdft_lanes, r.spec.sdft_lanes == 1 ? "" : "s",
      r.budget.sdft_clocks, r.budget.sdft_skip_clocks, r.budget.sdft_min_period, r.budget.period,
      streaming ? fmt::format("datapath: streaming (rtl/dtmf_chain.v, a taxel a clock; the frame "
                              "engine is its control plane): the chain's own {} clocks a frame "
                              "add to the engine's below\n",
                              r.load.chain_clocks)
                : std::string("datapath: the frame engine alone\n"),
      streaming ? "the control plane's frame engine" : "frame engine",
      r.spec.engine_fast_shift ? "barrel" : "bit-serial",
      streaming ? std::string("the chain's layers")
      : r.spec.neuron_lanes ? fmt::format("{} neuron lanes", r.spec.neuron_lanes)
      : r.spec.neuron_unit ? std::string("the neuron unit") : std::string("the engine"),
      r.budget.frame_clocks,
      r.spec.adc_clk_hz > 0
          ? fmt::format("STEP samples of {} ADC clocks, at the least", r.budget.adc_period)
          : fmt::format("STEP x {} per sample", r.budget.period),
      r.load.scene_clocks,
      100.0 * double(r.load.scene_clocks) / frame, r.load.scene_frames, r.load.stress_clocks,
      100.0 * double(r.load.stress_clocks) / frame, r.load.stress_case,
      r.load.stress_bound() > r.load.stress_clocks
          ? fmt::format("\n  packets on any frame  {:>9} ({:.0f} %: {} without its packets + {}, a "
                        "frame's most packets)",
                        r.load.stress_bound(), 100.0 * double(r.load.stress_bound()) / frame,
                        r.load.stress_other_clocks, r.load.stress_packet_clocks)
          : std::string(),
      r.load.stress_total() - r.load.chain_clocks,
      100.0 * double(r.load.stress_total() - r.load.chain_clocks) / frame, r.load.command_case,
      streaming ? fmt::format("  + the chain           {:>9} ({:.0f} %)\n", r.load.stress_total(),
                              100.0 * double(r.load.stress_total()) / frame)
                : std::string(),
      r.bound.total(), 100.0 * double(r.bound.total()) / frame, r.bound.frame, r.bound.command,
      hls::dtmf_frame_bound_limit_percent(r.spec.datapath),
      r.policy == LoadPolicy::Scene && r.load.scene_frames > 0
          ? "scene's frames (--engine-load scene)"
          : "stress frames and a command (--engine-load stress)");
  if (!r.load.stress_routines.empty()) {
    t += "  the longest stress frame by routine:";
    for (const auto& [name, clocks] : r.load.stress_routines)
      if (clocks * 100 >= r.load.stress_clocks)  // 1 % and more
        t += fmt::format(" {} {:.0f} %,", name, 100.0 * double(clocks) / double(r.load.stress_clocks));
    t.back() = '\n';
  }
  for (const auto& w : flow_warnings(r)) t += "warning: " + w + "\n";
  return t;
}

std::string hall_table(const FlowReport& r) {
  std::string decode;
  for (const auto& d : r.hall.decode) decode += (decode.empty() ? "" : ", ") + d;
  const int nb = r.hall.spec.nb, ns = nb * r.hall.spec.nsb;
  std::string t = fmt::format("Hall: {} I2C bus{} x {} sensor{} = {}, decoding: {}\n", nb,
                              nb == 1 ? "" : "es", r.hall.spec.nsb,
                              r.hall.spec.nsb == 1 ? "" : "s", ns, decode.empty() ? "none" : decode);
  if (r.core == Core::Hall && r.clk_hz > 0)  // (not chosen when the pins stopped it)
    t += fmt::format("clock {} MHz ({}), UART {:g} Mbaud\n", mhz(double(r.clk_hz)),
                     r.pll ? "PLL" : "the oscillator itself", double(r.baud) / 1e6);
  t += fmt::format("pins: {} needed, {} free on the board\n", r.hall.pins.needed,
                   r.hall.pins_available);
  for (const auto& p : r.hall.pins.pins)
    t += fmt::format("  {:<12} {:>4}  {}{}\n", p.signal, p.pin.site, p.pin.connector,
                     p.i2c ? " (open drain)" : "");
  return t;
}

}  // namespace

std::vector<std::string> flow_warnings(const FlowReport& r) {
  std::vector<std::string> w;
  if (r.budget.frame_clocks > 0 && long(r.load.stress_total()) > r.budget.frame_clocks)
    w.push_back(fmt::format(
        "under the stress signals the engine needs {} + {}{} = {} clocks of the {} a frame has: "
        "frames are lost (STATUS frame_overruns) while input like '{}' lasts",
        r.load.stress_bound(), r.load.command_clocks,
        r.load.chain_clocks ? fmt::format(" + the chain's {}", r.load.chain_clocks) : std::string(),
        r.load.stress_total(),
        r.budget.frame_clocks, r.load.stress_case));
  return w;
}

std::string report_json(const FlowReport& r) {
  nlohmann::json j;
  j["board"] = r.board;
  j["device"] = r.device;
  j["scene"] = r.scene;
  j["core"] = core_top(r.core);
  j["clock"] = {{"clk_hz", r.clk_hz}, {"baud", r.baud}, {"source", r.pll ? "pll" : "oscillator"},
                {"adc_clk_hz", r.spec.adc_clk_hz}};
  if (r.core != Core::Hall) dtmf_json(r, j);
  if (r.core != Core::Dtmf) hall_json(r, j);
  j["warnings"] = flow_warnings(r);
  nlohmann::json params = nlohmann::json::object();
  for (const auto& p : r.params) params[p.name] = p.value;
  j["parameters"] = params;
  nlohmann::json res = nlohmann::json::object();
  for (const auto& x : r.resources) res[x.name] = {{"used", x.used}, {"available", x.available}};
  j["resources"] = res;
  nlohmann::json clocks = nlohmann::json::array();
  for (const auto& c : r.clocks)
    clocks.push_back({{"net", c.net}, {"fmax_mhz", c.achieved_mhz}, {"required_mhz", c.required_mhz}});
  j["clocks"] = clocks;
  j["fits"] = r.fits;
  j["meets_timing"] = r.meets_timing;
  j["bitstream"] = r.bitstream;
  j["failure"] = r.failure;
  j["tool_seconds"] = r.seconds;
  j["placer_seed"] = r.seed;
  j["placer_seeds_tried"] = r.seeds_tried;
  return j.dump(2) + "\n";
}

std::string report_table(const FlowReport& r) {
  std::string t = fmt::format("board {} ({}), scene {}: {}\n", r.board, r.device, r.scene,
                              core_top(r.core));
  // A Hall scene that has too few pins stops before its clock is chosen.
  if (r.core != Core::Hall && r.budget.period > 0) t += dtmf_table(r);
  if (r.core != Core::Dtmf) t += hall_table(r);
  if (!r.resources.empty()) {
    t += fmt::format("\n{:<16} {:>8} {:>10} {:>6}\n", "resource", "used", "available", "use");
    for (const auto& x : r.resources) {
      if (x.used == 0 && x.name != r.logic_resource) continue;
      t += fmt::format("{:<16} {:>8} {:>10} {:>5.0f}%{}\n", x.name, x.used, x.available,
                       100.0 * double(x.used) / double(std::max(1L, x.available)),
                       x.used > x.available ? "  over" : "");
    }
  }
  if (!r.clocks.empty()) {
    t += fmt::format("\n{:<28} {:>9} {:>13} {:>7}   (placer seed {}{})\n", "clock net",
                     "Fmax MHz", "required MHz", "slack", r.seed,
                     r.seeds_tried > 1 ? fmt::format(", the last of {} tried", r.seeds_tried)
                                       : std::string());
    for (const auto& c : r.clocks)
      t += fmt::format("{:<28} {:>9.1f} {:>13.1f} {:>6.0f}%\n", c.net, c.achieved_mhz,
                       c.required_mhz, 100.0 * (c.achieved_mhz / c.required_mhz - 1.0));
  }
  t += "\n";
  if (r.ok())
    t += fmt::format("fits and meets timing: {} ({:.0f} s of tools)\n", r.bitstream, r.seconds);
  else
    t += "FAILED: " + r.failure + "\n";
  return t;
}

}  // namespace eskin::fpga
