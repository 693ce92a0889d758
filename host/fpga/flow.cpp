#include "host/fpga/flow.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "ucode/dtmf_ucode.h"
#include "eskin/skin_config.h"
#include "host/fpga/core_flows.h"
#include "host/fpga/core_wrapper.h"
#include "host/fpga/tool_run.h"
#include "sim/dtmf_top_spec.h"
#include "sim/world_model.h"

namespace eskin::fpga {

namespace fs = std::filesystem;

namespace {

std::string mhz(double hz) { return fmt::format("{:.6g}", hz / 1e6); }

}  // namespace

Core scene_core(const sim::Scene& scene) {
  return !scene.has_hall ? Core::Dtmf : scene.has_skin ? Core::Mixed : Core::Hall;
}

const char* core_top(Core c) {
  return c == Core::Dtmf ? "dtmf_top" : c == Core::Hall ? "hall_top" : "mixed_top";
}

const Resource* FlowReport::resource(const std::string& name) const {
  for (const auto& x : resources)
    if (x.name == name) return &x;
  return nullptr;
}

const ClockResult* FlowReport::slowest_clock() const {
  const ClockResult* worst = nullptr;
  for (const auto& c : clocks)
    if (!worst || c.achieved_mhz / c.required_mhz < worst->achieved_mhz / worst->required_mhz)
      worst = &c;
  return worst;
}

void parse_nextpnr_report(const std::string& json_text, FlowReport& r) {
  const auto j = nlohmann::json::parse(json_text);
  r.resources.clear();
  r.clocks.clear();
  for (const auto& [name, u] : j.at("utilization").items())
    r.resources.push_back({name, u.at("used").get<long>(), u.at("available").get<long>()});
  if (j.contains("fmax"))
    for (const auto& [net, f] : j.at("fmax").items())
      r.clocks.push_back({net, f.at("achieved").get<double>(), f.at("constraint").get<double>()});
}

std::vector<Resource> parse_nextpnr_utilisation(const std::string& log_text) {
  // "Info: Device utilisation:" then "Info: \t ICESTORM_LC:  5339/ 5280   101%".
  std::vector<Resource> out;
  const std::regex row(R"(^Info:\s+(\w+):\s+(\d+)/\s*(\d+)\s+\d+%)");
  std::stringstream ss(log_text);
  std::string line;
  bool in_block = false;
  while (std::getline(ss, line)) {
    if (line.find("Device utilisation:") != std::string::npos) {
      in_block = true;
      out.clear();  // keep the last block
      continue;
    }
    std::smatch m;
    if (in_block && std::regex_search(line, m, row))
      out.push_back({m[1], std::stol(m[2]), std::stol(m[3])});
    else if (in_block)
      in_block = false;
  }
  return out;
}

namespace {

// The sample period, in core clocks, that the DFT must keep (0: the rest
// of the top needs no clock, any DFT will do): the one at the board clock
// the rest would get (its clocks come in steps: a lane that saves less
// than a step saves nothing).
long dft_period_needed(const Board& b, const hls::DtmfTopPlan& plan, long engine_clocks) {
  const long other = hls::dtmf_top_min_clock_hz_without_dft(plan, engine_clocks);
  if (other == 0) return 0;
  const auto board_clk = slowest_clock_from(b, other);
  const long clk = board_clk ? board_clk->clk_hz : std::max(other, b.default_clk_hz);
  // An ADC that cannot convert on that clock gets its own (with_adc_clock),
  // whose samples may come a clock sooner (hls::dtmf_top_clock_budget).
  const bool own_adc = !hls::dtmf_top_adc_problem(plan.spec.sample_hz, clk).empty() &&
                       with_adc_clock(b, {clk, 0, {}, 0}, plan.spec.sample_hz).has_value();
  return std::lround(double(clk) / plan.spec.sample_hz) - (own_adc ? 1 : 0);
}

// The sample FIFO a board's flow may put in front of the lanes
// (rtl/sdft_front.v): 4 samples, a few LUT RAM cells, where block RAM
// is plentiful; none on the UP5K (one lane, its pace never needs one).
int fifo_allowed(const Board& b) { return b.max_sdft_lanes > 1 ? 4 : 0; }

}  // namespace

int choose_sdft_lanes(const Board& b, const hls::DtmfTopPlan& plan, long engine_clocks) {
  const long period = dft_period_needed(b, plan, engine_clocks);
  if (period == 0) return 1;
  const int most = std::min({b.max_sdft_lanes, 64, plan.ks});
  const int fifo = std::max(plan.spec.sdft_fifo, fifo_allowed(b));
  int lanes = 1;
  while (lanes < most && hls::dtmf_top_sdft_min_period(plan.ks, lanes, plan.step, fifo) > period)
    ++lanes;
  return lanes;
}

int choose_sdft_fifo(const Board& b, const hls::DtmfTopPlan& plan, long engine_clocks) {
  const long period = dft_period_needed(b, plan, engine_clocks);
  const int lanes = plan.spec.sdft_lanes;
  if (period == 0 ||
      hls::dtmf_top_sdft_min_period(plan.ks, lanes, plan.step, plan.spec.sdft_fifo) <= period)
    return plan.spec.sdft_fifo;
  const int fifo = fifo_allowed(b);
  return fifo > plan.spec.sdft_fifo &&
                 hls::dtmf_top_sdft_min_period(plan.ks, lanes, plan.step, fifo) <= period
             ? fifo
             : plan.spec.sdft_fifo;
}

int neuron_lanes_for(const Board& b, int neuron_unit, int taxels) {
  const int lanes = neuron_unit == 2 ? std::max(5, b.neuron_lanes)
                    : neuron_unit < 0 && b.neuron_unit ? b.neuron_lanes : 0;
  // rtl/izhikevich_lanes.v numbers 2^11 neurons: the board's choice falls
  // back to the unit alone beyond, the user's is refused by the plan.
  return neuron_unit == 2 || 2 * taxels <= 2048 ? lanes : 0;
}

void apply_engine_options(const Board& b, int fast_shift, int neuron_unit,
                          hls::DtmfTopSpec& spec) {
  spec.engine_fast_shift = fast_shift < 0 ? b.engine_fast_shift : fast_shift != 0;
  spec.neuron_unit = neuron_unit < 0 ? b.neuron_unit : neuron_unit != 0;
  spec.neuron_lanes = neuron_lanes_for(b, neuron_unit, spec.rows * spec.cols);
}

namespace {

// choose_core_clock for a plan made at spec's baud rate, among the clocks
// whose UART runs at min_baud or faster (0: any). fast_shift and
// neuron_unit are the user's (-1: the board's, in spec).
CoreClock choose_core_clock_at(const Board& b, const hls::DtmfTopSpec& spec,
                               const std::vector<int32_t>& x, LoadPolicy policy, long clk_hz,
                               int fast_shift, int neuron_unit, long min_baud,
                               bool own_adc_clock) {
  CoreClock c;
  auto load_with = [&](const hls::DtmfTopSpec& s) {
    c.plan = hls::make_dtmf_top_plan(s);
    c.load = measure_engine_load(c.plan, x);
    c.engine_clocks = long(policy == LoadPolicy::Stress || c.load.scene_frames == 0
                               ? c.load.stress_total() : c.load.scene_total());
    if (!b.engine_when_needed) return hls::dtmf_top_min_clock_hz(c.plan, c.engine_clocks);
    // Choosing among engines: the clock the measured load and the static
    // bound (at most its datapath's share of the frame, which run_flow
    // checks) need, so that the engine chosen is one the plan accepts.
    const long bound = long(hls::dtmf_frame_bound(c.plan).total());
    const long pct = hls::dtmf_frame_bound_limit_percent(c.plan.spec.datapath);
    return hls::dtmf_top_min_clock_hz(c.plan,
                                      std::max(c.engine_clocks, (bound * 100 + pct - 1) / pct));
  };
  long need = load_with(spec);
  // The board's engine when needed (Board::engine_when_needed): the first
  // engine, fewest cells first, whose core keeps up at the asked-for clock
  // or the board's default (its measured load, and its static bound within
  // the limit), else the one that needs the slowest clock (when
  // the ADC or the DFT sets the need, no engine lowers it).
  const long keep_up_at = clk_hz > 0 ? clk_hz : b.default_clk_hz;
  if (b.engine_when_needed && need > keep_up_at) {
    CoreClock best = c;
    long best_need = need;
    for (const auto& [barrel, unit] : {std::pair{true, false}, {false, true}, {true, true}}) {
      if ((fast_shift >= 0 && barrel != (fast_shift != 0)) ||
          (neuron_unit >= 0 && unit != (neuron_unit != 0)) ||
          (barrel == spec.engine_fast_shift && unit == spec.neuron_unit))
        continue;
      auto s = spec;
      s.engine_fast_shift = barrel;
      s.neuron_unit = unit;
      s.neuron_lanes = unit ? neuron_lanes_for(b, neuron_unit, s.rows * s.cols) : 0;
      need = load_with(s);
      if (need < best_need) {
        best = c;
        best_need = need;
      }
      if (best_need <= keep_up_at) break;
    }
    c = best;
  }
  c.plan.spec.sdft_lanes = choose_sdft_lanes(b, c.plan, c.engine_clocks);
  c.plan.spec.sdft_fifo = choose_sdft_fifo(b, c.plan, c.engine_clocks);
  c.core_min_hz = hls::dtmf_top_min_clock_hz(c.plan, c.engine_clocks);
  auto budget_at = [&](const Clocking& k) {
    c.plan.spec.clk_hz = k.clk_hz;
    c.plan.spec.adc_clk_hz = k.adc_clk_hz;
    c.plan.spec.baud = k.baud;
    return hls::dtmf_top_clock_budget(c.plan, k.clk_hz, c.engine_clocks);
  };
  // The measured load, and on the streaming datapath, where it keeps up,
  // the static bound too (at the clock: the carrier load's polls depend on
  // the sample period), so that the clock chosen is one run_flow accepts.
  // The frame engine's clock is the measured load's (its bound is then
  // checked by run_flow, which names it: the UP5K's larger skins would
  // otherwise get clocks its fabric does not reach).
  auto bounded_at = [&](const Clocking& k) {
    const hls::DtmfTopClockBudget measured = budget_at(k);
    if (!measured.ok() || c.plan.spec.datapath != hls::DtmfDatapath::Streaming) return measured;
    return hls::dtmf_top_clock_budget(c.plan, k.clk_hz, c.engine_clocks,
                                      long(hls::dtmf_frame_bound(c.plan).total()));
  };
  // k, or k with an ADC clock of its own when only that keeps up (with
  // the bound, or the measured load alone).
  auto keeps_up = [&](const Clocking& k, bool bound = true) -> std::optional<Clocking> {
    auto ok = [&](const Clocking& q) { return bound ? bounded_at(q).ok() : budget_at(q).ok(); };
    if (ok(k)) return k;
    if (own_adc_clock)
      if (const auto a = with_adc_clock(b, k, c.plan.spec.sample_hz); a && ok(*a)) return a;
    return std::nullopt;
  };
  c.clocking = choose_clock(b, 0, clk_hz);  // the asked-for or the board's default
  if (clk_hz > 0) {  // (run_flow then names the bound when only the measurement keeps up)
    if (const auto k = keeps_up(c.clocking)) c.clocking = *k;
    else if (const auto m = keeps_up(c.clocking, false)) c.clocking = *m;
  } else {
    for (const auto& k : board_clocks(b))
      if (k.clk_hz >= std::max(c.core_min_hz, b.default_clk_hz) && k.baud >= min_baud)
        if (const auto ok = keeps_up(k)) {
          c.clocking = *ok;
          break;
        }
  }
  c.budget = budget_at(c.clocking);
  // At its lanes and clock: the DFT's busy time and sample period bound
  // the carrier load's polls.
  c.bound = hls::dtmf_frame_bound(c.plan);
  return c;
}

}  // namespace

namespace {

// choose_core_clock for one datapath (spec's).
CoreClock choose_core_clock_for(const Board& b, hls::DtmfTopSpec spec,
                                const std::vector<int32_t>& x, LoadPolicy policy, long clk_hz,
                                int fast_shift, int neuron_unit, bool own_adc_clock) {
  // The plan paces the packets for its baud rate (make_dtmf_top_plan: the
  // decimation that lets the link carry them), and the clock sets the baud
  // rate (the fastest exact one): when the chosen clock's differs, plan
  // again at it, and measure the engine again (the decimation moves the
  // frames that carry packets against the stress signals, so the longest
  // frame moves a little: 16x16 at 1 MS/s, 38 363 -> 38 504 clocks at 2
  // instead of 3 Mbaud), which may choose another clock: only one whose
  // UART is at least as fast as the plan's link (a plan for a slower link
  // than the clock's is safe; one for a faster link would overrun it), so
  // the passes cannot step down from clock to clock (a 12x12 skin on the
  // ULX3S with the bit-serial shifter and the unit went 3 -> 2 -> 1 Mbaud).
  CoreClock c = choose_core_clock_at(b, spec, x, policy, clk_hz, fast_shift, neuron_unit, 0,
                                     own_adc_clock);
  for (int pass = 1; pass < 3 && c.clocking.baud != spec.baud; ++pass) {
    spec.baud = c.clocking.baud;
    c = choose_core_clock_at(b, spec, x, policy, clk_hz, fast_shift, neuron_unit, spec.baud,
                             own_adc_clock);
  }
  if (c.budget.ok() && c.clocking.baud < spec.baud)
    throw std::logic_error(fmt::format("choose_core_clock: the packets are planned for {} baud, "
                                       "the clock's UART runs at {}",
                                       spec.baud, c.clocking.baud));
  return c;
}

// The measured load keeps up at the chosen clock and the static bound
// holds there (run_flow's two checks).
bool keeps_up_with_bound(const CoreClock& c) {
  return c.budget.ok() && hls::dtmf_top_clock_budget(c.plan, c.clocking.clk_hz, c.engine_clocks,
                                                     long(c.bound.total()))
                              .ok();
}

}  // namespace

const char* datapath_name(hls::DtmfDatapath d) {
  return d == hls::DtmfDatapath::Streaming ? "streaming" : "engine";
}

bool streaming_possible(const hls::DtmfTopSpec& spec) {
  return !spec.demix && spec.rows <= 255 && spec.cols <= 255;
}

CoreClock choose_core_clock(const Board& b, const sim::Scene& scene, LoadPolicy policy,
                            long clk_hz, int fast_shift, int neuron_unit, bool own_adc_clock,
                            int datapath) {
  hls::DtmfTopSpec spec = sim::dtmf_top_spec(scene);
  // Before the load: the shifter and the neuron unit set the engine's clocks.
  apply_engine_options(b, fast_shift, neuron_unit, spec);
  // The scene's samples as the top takes them: 12-bit codes minus 2048.
  std::vector<int32_t> x;
  sim::WorldModel world(scene);
  for (int code : world.all_codes()) x.push_back((code << (12 - scene.skin.adc.bits)) - 2048);
  // The streaming datapath: the chain has its own layers (no neuron unit
  // or lanes); the engine keeps the board's (or the asked-for) shifter.
  hls::DtmfTopSpec stream = spec;
  stream.datapath = hls::DtmfDatapath::Streaming;
  stream.neuron_unit = false;
  stream.neuron_lanes = 0;
  if (datapath == 1) {
    if (neuron_unit > 0)
      throw std::invalid_argument(
          "--neurons: the streaming datapath runs the neurons in its own layers (rtl/dtmf_chain.v); "
          "leave --neurons to the board or say engine");
    return choose_core_clock_for(b, stream, x, policy, clk_hz, fast_shift, 0, own_adc_clock);
  }
  // The neuron unit or its lanes, asked for, are the frame engine's.
  if (datapath == 0 || neuron_unit > 0 || !b.streaming || !streaming_possible(spec))
    return choose_core_clock_for(b, spec, x, policy, clk_hz, fast_shift, neuron_unit,
                                 own_adc_clock);
  // The board's choice: of the two that keep up (the measured load at a
  // board clock and the static bound there), the one at the slower clock
  // (more timing slack), the frame engine alone on a tie (fewer cells);
  // the one that keeps up when only one does; when neither does, the
  // streaming one's report (the larger skins' architecture, whose limits
  // are the ones to read). A skin the engine cannot hold at all (its DMEM)
  // goes to the chain.
  std::optional<CoreClock> engine, chain;
  try {
    engine = choose_core_clock_for(b, spec, x, policy, clk_hz, fast_shift, neuron_unit,
                                   own_adc_clock);
  } catch (const std::invalid_argument&) {
    // The engine cannot hold the skin (its DMEM, its lanes' neurons).
  }
  try {
    chain = choose_core_clock_for(b, stream, x, policy, clk_hz, fast_shift, 0, own_adc_clock);
  } catch (const std::invalid_argument&) {
    if (!engine) throw;
  }
  if (!engine) return *chain;
  if (!chain) return *engine;
  const bool e = keeps_up_with_bound(*engine), c = keeps_up_with_bound(*chain);
  if (e && c) return chain->clocking.clk_hz < engine->clocking.clk_hz ? *chain : *engine;
  return e ? *engine : *chain;
}

bool plan_dtmf_core(const Board& b, const sim::Scene& scene, const FlowOptions& opt,
                    FlowReport& r, Clocking& clk, std::vector<hls::VerilogParam>& params,
                    bool own_adc_clock) {
  // rtl/mixed_top.v (one clock: own_adc_clock false) builds dtmf_top's
  // frame engine alone.
  CoreClock cc = choose_core_clock(b, scene, opt.load, opt.clk_hz, opt.fast_shift,
                                   opt.neuron_unit, own_adc_clock,
                                   own_adc_clock ? opt.datapath : 0);
  const hls::DtmfTopPlan& plan = cc.plan;
  clk = cc.clocking;
  r.step = plan.step;
  r.load = cc.load;
  r.bound = cc.bound;
  r.policy = opt.load;
  r.engine_clocks = cc.engine_clocks;
  r.core_min_hz = cc.core_min_hz;
  r.core_min_reason = hls::dtmf_top_min_clock_reason(plan, cc.engine_clocks);
  r.budget = cc.budget;
  r.spec = plan.spec;
  r.clk_hz = clk.clk_hz;
  r.baud = clk.baud;
  const hls::DtmfTopSpec& spec = r.spec;
  if (!r.budget.ok()) {
    std::string why;
    for (const auto& p : r.budget.problems) why += (why.empty() ? "" : "; ") + p;
    r.failure = fmt::format("timing: the core does not keep up with {:.0f} S/s at {} MHz: {}. {}",
                            spec.sample_hz, mhz(double(clk.clk_hz)), why,
                            r.core_min_hz == 0
                                ? std::string("No clock can: the AD7476A cannot convert that fast.")
                            : opt.clk_hz > 0
                                ? fmt::format("It needs at least {} MHz.", mhz(double(r.core_min_hz)))
                                : fmt::format("It needs at least {} MHz; board {} has no clock "
                                              "that meets every budget.",
                                              mhz(double(r.core_min_hz)), b.name));
    return false;
  }
  // The plan refuses a build whose proven worst case (ucode/dtmf_frame_bound.h)
  // takes more of the frame than its datapath may (90 % on the frame
  // engine), though its measured one keeps up at this clock.
  const hls::DtmfTopClockBudget bounded =
      hls::dtmf_top_clock_budget(plan, clk.clk_hz, cc.engine_clocks, long(cc.bound.total()));
  r.budget.bound_clocks = bounded.bound_clocks;
  r.budget.bound_limit_clocks = bounded.bound_limit_clocks;
  if (!bounded.ok()) {
    r.failure = fmt::format("frame bound: {} (measured: {} clocks; the bound is frame {} + "
                            "command {})",
                            bounded.problems.front(), cc.engine_clocks, cc.bound.frame,
                            cc.bound.command);
    return false;
  }
  const fs::path out = fs::absolute(opt.out_dir);
  fs::create_directories(out);
  // The microcode and constants as $readmemh files beside the core wrapper,
  // which names them by absolute path.
  params = hls::write_dtmf_top_build(plan, out.string(), "dtmf_scene");
  return true;
}

void check_out_dir_for_tools(const std::string& out_dir) {
  const std::string abs = fs::absolute(out_dir).string();
  for (const char c : abs)
    if (c == '"' || c == '\\' || c == '\n')
      throw ConfigError("--out", fmt::format("'{}': a folder whose path holds a double quote, a "
                                             "backslash or a newline cannot be given to Yosys "
                                             "(the core's $readmemh names are Verilog strings); "
                                             "choose another",
                                             abs));
}

// An ECP5 build asked for under /tmp (a plain user's first try) runs there
// like any other: scripts/synth_ecp5.sh lets the WebAssembly tools, which
// have a private /tmp of their own, see the folder (tool_run.h).
FlowReport run_flow(const Board& b, const sim::Scene& scene, const FlowOptions& opt) {
  FlowReport r;
  r.board = b.name;
  r.device = b.device;
  r.scene = scene.name;
  r.logic_resource = b.logic_resource;
  r.core = scene_core(scene);
  if (r.core != Core::Dtmf) {
    run_hall_flow(b, scene, opt, r);
    return r;
  }
  Clocking clk;
  if (!plan_dtmf_core(b, scene, opt, r, clk, r.params, true)) return r;
  const fs::path wrapper = fs::absolute(opt.out_dir) / "dtmf_scene.v";
  std::ofstream(wrapper) << dtmf_core_wrapper("dtmf_scene", r.params);
  r.params.insert(r.params.end(), clk.wrapper_params.begin(), clk.wrapper_params.end());

  ToolRun t;
  t.top = b.wrapper;
  t.reads = {wrapper.string()};
  t.defines = {"ESKIN_DTMF_CORE=dtmf_scene"};
  t.constraints = (fs::path(opt.source_dir) / b.constraints).string();
  t.clk_hz = clk.clk_hz;
  t.params = clk.wrapper_params;
  run_tools(b, opt, t, r);
  // A clock the design misses: say what asked for it.
  if (r.ran_tools && r.fits && !r.meets_timing)
    r.failure += fmt::format(" (the core needs {} MHz or more: {})", mhz(double(r.core_min_hz)),
                             r.core_min_reason);
  return r;
}

}  // namespace eskin::fpga
