#include "host/bench/latency.h"
#include "eskin/fnv1a.h"
#include "eskin/process.h"
#include "eskin/source_tree.h"

#include <fmt/format.h>

#include "host/bench/text_file.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <map>
#include <numeric>
#include <set>
#include <ostream>
#include <regex>
#include <sstream>

#include <stdlib.h>
#include <unistd.h>
#include <stdexcept>

#include "host/bench/engine_model.h"
#include "host/bench/timing.h"
#include "ucode/dtmf_ucode.h"
#include "host/engine/engine_setup.h"
#include "host/fpga/engine_load.h"
#include "host/fpga/scale_table.h"
#include "sim/dtmf_top_spec.h"
#include "sim/hall_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace fs = std::filesystem;

namespace eskin::bench {

const std::vector<LatencyConfig>& latency_configs() {
  using Top = LatencyConfig::Top;
  static const std::vector<LatencyConfig> c = {
      // The UP5K build (iCEBreaker: 12 MHz x 3/2 by the PLL).
      {"3x3", "scenes/neuroskin2.yaml", hls::kDtmfTopClkHz},
      // 100 taxels, two neuron layers each: as tests/rtl/dtmf_top_test.cmake
      // builds it (the engine needs ~80 000 clocks per 1 ms frame).
      {"10x10", "scenes/staggered10x10.yaml", 96000000},
      // The bitstream flow's 16x16 skin at 35 kS/s (docs/bitstream.md), with
      // sparse taxels (LatencyConfig::sparse_taxels: the dense packet never
      // fits the output FIFO). Its engine load (host/fpga/engine_load.h:
      // stress frame plus the longest command, 227 564 clocks; 214 347 with
      // dense taxels) needs 227.56 MHz (hls::dtmf_top_min_clock_hz); 228 MHz
      // is the first whole MHz at which hls::dtmf_top_clock_budget keeps up
      // (checked by measure_latency). No board here reaches it; Verilator
      // runs any clock.
      {"16x16", "scenes/neuroskin2.yaml", 228000000, Top::Dtmf, 16, false, true},
      // The 64x64 skin at 1 MS/s on the streaming datapath (rtl/dtmf_chain.v,
      // the frame engine its control plane) as the ULX3S flow builds it at
      // 40 MHz (22 DFT lanes, a 4-sample FIFO), with sparse taxels (a dense
      // packet, 8 KB, takes 41 ms at 2 Mbaud).
      {"64x64", "scenes/skin64x64.yaml", 40000000, Top::Dtmf, 0, false, true, true},
      // The seed-000 Hall skin (16 MLX90393 on 4 buses) in hall_top as
      // sim/hall_top_spec.h generates it, from the 12 MHz oscillator.
      {"hall000", "scenes/hall_000_skin.yaml", 12000000, Top::Hall},
  };
  return c;
}

namespace {

// Frames the Hall harness runs: 0 and 1 are the configuration round and
// the first conversion, 2 .. 7 are measured.
constexpr int kHallFrames = 8;

std::string slurp(const fs::path& p) { return eskin::bench::read_text(p.string()); }

// Runs `argv` (no shell), output into `log_file`; throws with its tail on failure.
void run_logged(const std::vector<std::string>& argv, const fs::path& log_file,
                const eskin::RunContext& ctx = {}) {
  const int st = eskin::run_logged(argv, log_file.string(), eskin::LogMode::Truncate, ctx);
  if (st != 0) {
    std::string log = slurp(log_file);
    if (log.size() > 3000) log = "..." + log.substr(log.size() - 3000);
    throw std::runtime_error("command failed (" + log_file.string() + "):\n" +
                             eskin::printable_command(argv) + "\n" + log);
  }
}

// One Verilator build of a harness around a top.
struct HarnessBuild {
  std::string top;                  // module, rtl/<top>.v
  std::string harness;              // bench/latency/<harness>.cpp
  std::vector<std::string> g_args;  // "-GNAME=VALUE"
  std::vector<std::string> flags;   // further Verilator options (--assert)
  std::vector<std::string> deps;    // further files it depends on, relative to the source tree
  std::vector<fs::path> data;       // files the model reads ($readmemh)
  std::string ldflags;
};

// The harness for one parameter set: cached under cache_dir/<hash>.
fs::path harness_for(const HarnessBuild& hb, const fs::path& cache_dir, double& build_seconds) {
  const fs::path src = eskin::source_dir();
  const fs::path harness = src / "bench/latency" / (hb.harness + ".cpp");
  uint64_t h = fnv1a(slurp(harness));
  std::vector<fs::path> deps;
  for (const auto& e : fs::directory_iterator(src / "rtl"))
    if (e.path().extension() == ".v" || e.path().extension() == ".vh") deps.push_back(e.path());
  std::sort(deps.begin(), deps.end());
  for (const auto& f : hb.deps) deps.push_back(src / f);
  for (const char* lib : {ESKIN_LINK_LIB, ESKIN_COMMON_LIB, ESKIN_SIM_LIB})
    deps.push_back(eskin::in_build_dir(lib));
  for (const auto& d : deps) h = fnv1a(d.filename().string() + slurp(d), h);
  for (const auto& d : hb.data) h = fnv1a(slurp(d), h);
  for (const auto& a : hb.g_args) h = fnv1a(a, h);
  for (const auto& a : hb.flags) h = fnv1a(a, h);  // a build without them is another model
  const fs::path dir = cache_dir / fmt::format("{:016x}", h);
  const fs::path exe = dir / "obj" / hb.harness;
  build_seconds = 0;
  if (fs::exists(exe)) return exe;
  // Built aside and renamed into place: concurrent runs never see half a build.
  // GNU Make (Verilator's --build) cannot build in a folder whose path
  // has a space, and expands '$' in it: a cache whose path is not a plain
  // word is built in a fresh folder of /tmp, then moved into the cache.
  const std::string cache_abs = fs::absolute(cache_dir).string();
  const bool plain = cache_abs.find_first_not_of(
                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./+,@%=-") ==
                     std::string::npos;
  fs::path tmp = cache_dir / fmt::format("{:016x}.tmp{}", h, ::getpid());
  fs::create_directories(cache_dir);
  if (plain) {
    fs::remove_all(tmp);
    fs::create_directories(tmp);
  } else {
    std::string t = (fs::temp_directory_path() / "eskin-verilator.XXXXXX").string();
    if (!::mkdtemp(t.data())) throw std::runtime_error(t + ": cannot create a build folder");
    tmp = t;
  }
  const double t0 = wall_seconds();
  // Built in `tmp` with a relative --Mdir: Verilator runs make on its
  // object directory through a shell of its own, which must never see the
  // cache's path (a user's --cache).
  std::vector<std::string> cmd{"verilator", "--cc", "--exe", "--build", "-j", "2", "-O3",
                               "-Wno-fatal", "--x-assign", "unique", "--x-initial", "unique",
                               "-y", (src / "rtl").string(), "--top-module", hb.top};
  cmd.insert(cmd.end(), hb.g_args.begin(), hb.g_args.end());
  cmd.insert(cmd.end(), hb.flags.begin(), hb.flags.end());
  for (const auto& a : {(src / "rtl" / (hb.top + ".v")).string(), harness.string(),
                        std::string("-CFLAGS"),
                        "-std=c++17 -O2 -I" + src.string() + " -I" + (src / "tests/rtl").string() +
                            " -I" + (src / "common").string(),
                        std::string("-LDFLAGS"), hb.ldflags, std::string("--Mdir"),
                        std::string("obj"), std::string("-o"), hb.harness})
    cmd.push_back(a);
  eskin::RunContext ctx;
  ctx.cwd = fs::absolute(tmp).string();
  const std::string ccache = eskin::find_on_path("ccache");  // Verilator's make uses it when set
  if (!ccache.empty()) ctx.env.push_back({"OBJCACHE", ccache});
  run_logged(cmd, tmp / "build.log", ctx);
  build_seconds = wall_seconds() - t0;
  std::error_code ec;
  if (!plain) {  // into the cache's file system first, then the same rename
    const fs::path staged = cache_dir / fmt::format("{:016x}.tmp{}", h, ::getpid());
    fs::remove_all(staged);
    fs::copy(tmp, staged, fs::copy_options::recursive);
    fs::remove_all(tmp);
    tmp = staged;
  }
  fs::rename(tmp, dir, ec);
  if (ec) fs::remove_all(tmp);  // another run built it first
  return exe;
}

// Runs a harness, output into `out`; its "name value" lines: counters (by
// name) into `counters`, the rest into stages, then end_to_end. Lines
// starting with '#' are notes, passed on to `log`.
void run_harness(const std::vector<std::string>& cmd, const fs::path& out, const std::set<std::string>& counter_names,
                 LatencyRun& run, std::map<std::string, int64_t>& counters, std::ostream& log) {
  run_logged(cmd, out);
  std::istringstream lines(slurp(out));
  fs::remove(out);
  std::string line, name;
  int64_t v;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    if (line[0] == '#') {
      log << "  " << line.substr(1) << "\n";
      continue;
    }
    std::istringstream l(line);
    if (!(l >> name >> v))
      throw std::runtime_error(fmt::format("latency {}: harness line '{}' is not 'name cycles'",
                                           run.config.name, line));
    if (counter_names.count(name)) counters[name] = v;
    else run.stages.push_back({name, v});
  }
  int64_t end = 0;
  for (const auto& s : run.stages) end = std::max(end, s.cycles);
  run.stages.push_back({"end_to_end", end});
}

void require_zero(const LatencyConfig& c, std::map<std::string, int64_t>& counters,
                  std::initializer_list<const char*> names, const char* what) {
  for (const char* k : names)
    if (counters[k] != 0)
      throw std::runtime_error(fmt::format("latency {}: the build loses data ({} = {}): {}",
                                           c.name, k, counters[k], what));
}

// The Hall top: the harness runs the scene's sensors and reports the
// slowest of its steady-state frames.
LatencyRun measure_hall_latency(const LatencyConfig& c, const fs::path& cache_dir,
                                std::ostream& log) {
  LatencyRun run;
  run.config = c;
  const std::string scene_path = eskin::source_dir() + "/" + c.scene;
  const sim::Scene scene = sim::load_scene(scene_path);
  if (!scene.has_hall) throw std::runtime_error(c.scene + ": no hall section for the Hall top");
  const sim::HallTopSpec spec = sim::hall_top_spec(scene.hall.config, double(c.clk_hz));
  HarnessBuild hb;
  hb.top = "hall_top";
  hb.harness = "hall_latency_harness";
  hb.g_args = spec.verilog_params();
  for (const auto& p : spec.decode_params()) hb.g_args.push_back(p);
  hb.g_args.push_back("-GCLK_HZ=" + std::to_string(c.clk_hz));
  hb.deps = {"tests/rtl/hall_top_board.h", "tests/rtl/clocked_dut.h", "sim/i2c_pin_bus.h", "sim/hall_sensor_array.h", "sim/hall_sensor_array.cpp",
             "tests/rtl/uart_line.h"};
  hb.ldflags = eskin::in_build_dir(ESKIN_SIM_LIB) + " " + eskin::in_build_dir(ESKIN_LINK_LIB) + " " +
               eskin::in_build_dir(ESKIN_COMMON_LIB) +
               " -lyaml-cpp -lsndfile";
  log << fmt::format("latency {}: {} (hall_top: {} buses of {} sensors{}) at {} MHz\n", c.name,
                     c.scene, spec.nb, spec.nsb, spec.deltas ? ", hall_baseline" : "",
                     c.clk_hz / 1e6);
  const fs::path exe = harness_for(hb, cache_dir, run.build_seconds);
  if (run.build_seconds > 0) log << fmt::format("  built {} in {:.0f} s\n", exe.string(), run.build_seconds);
  const fs::path out = exe.parent_path().parent_path() / fmt::format("{}.{}.out", c.name, ::getpid());
  std::map<std::string, int64_t> counters;
  run_harness({exe.string(), scene_path, std::to_string(kHallFrames)}, out,
              {"missing_readings", "i2c_violations", "link_errors"}, run, counters, log);
  require_zero(c, counters, {"missing_readings", "i2c_violations", "link_errors"},
               "a measured frame lacks a reading, or the bus or the link breaks its rules");
  return run;
}

}  // namespace

LatencyRun measure_latency(const LatencyConfig& c, const std::string& cache_dir,
                           std::ostream& log) {
  if (c.top == LatencyConfig::Top::Hall) return measure_hall_latency(c, cache_dir, log);
  LatencyRun run;
  run.config = c;
  sim::Scene scene = sim::load_scene(eskin::source_dir() + "/" + c.scene);
  if (c.scale_n > 0) scene = fpga::scale_scene(scene, c.scale_n, 35000.0);
  if (c.streaming)
    run.plan = fpga::choose_core_clock(fpga::find_board("ulx3s", "85k"), scene,
                                       fpga::LoadPolicy::Stress, c.clk_hz, 0, -1, true, 1)
                   .plan;
  else
    run.plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(scene, c.clk_hz));
  if (c.sparse_taxels) run.plan.mask = uint8_t((run.plan.mask & ~hls::kMaskTaxels) | hls::kMaskSparse);
  const auto& p = run.plan;
  // The first frame that sends every stream (frame count a multiple of
  // both decimations) after two windows: DFT settled, the link idle
  // (earlier packets long sent).
  const uint32_t every = uint32_t(std::lcm(int(p.decim_amp), int(p.decim_tax)));
  const uint32_t f_min = (2 * uint32_t(p.N) + 64 + uint32_t(p.step) - 1) / uint32_t(p.step);
  const uint32_t frame = (f_min + every - 1) / every * every;
  run.sample = uint32_t(p.N - 1) + frame * uint32_t(p.step);
  const size_t run_to = run.sample + 2 * size_t(every) * size_t(p.step) + 64;
  sim::WorldModel world(scene);
  auto codes = engine::codes12(world.all_codes(), scene.skin.adc.bits);
  if (codes.size() <= run_to) codes.resize(run_to + 1, 2048);

  log << fmt::format("latency {}: {} (K {}, T {}, N {}, step {}, decim {}/{}) at {} MHz\n", c.name,
                     c.scene, p.K, p.T, p.N, p.step, p.decim_amp, p.decim_tax, c.clk_hz / 1e6);
  const fs::path hex_dir = fs::path(cache_dir) / "ucode";
  fs::create_directories(hex_dir);
  HarnessBuild hb;
  hb.top = "dtmf_top";
  hb.harness = "latency_harness";
  const auto params = hls::write_dtmf_top_build(p, fs::absolute(hex_dir).string(), c.name);
  hb.g_args = hls::verilator_g_args(params);
  // The RTL's simulation assertions (the microcode's timing contracts) fire
  // here as in every other build of the top (tests/rtl/dtmf_top_test.cmake,
  // sim/vboard): a run that breaks one fails instead of timing it.
  hb.flags = {"--assert"};
  for (const auto& q : params)  // the microcode and constants the model reads
    if (q.name == "UCODE_HEX" || q.name == "KROM_HEX") hb.data.push_back(q.value.substr(1, q.value.size() - 2));
  hb.deps = {"tests/rtl/dtmf_top_board.h", "sim/ad7476_model.h", "host/link/link_decoder.h",
             "host/link/link_encoder.h"};
  hb.ldflags = eskin::in_build_dir(ESKIN_LINK_LIB) + " " + eskin::in_build_dir(ESKIN_COMMON_LIB);
  const fs::path exe = harness_for(hb, cache_dir, run.build_seconds);
  if (run.build_seconds > 0) log << fmt::format("  built {} in {:.0f} s\n", exe.string(), run.build_seconds);
  const std::string stem = fmt::format("{}.{}", c.name, ::getpid());  // concurrent runs
  const fs::path codes_file = exe.parent_path().parent_path() / (stem + ".u16");
  {
    std::ofstream f(codes_file, std::ios::binary);
    for (uint16_t v : codes) f.put(char(v & 0xFF)).put(char(v >> 8));
  }
  const fs::path out = exe.parent_path().parent_path() / (stem + ".out");
  const long cpb = std::lround(double(c.clk_hz) / double(p.spec.baud));
  std::map<std::string, int64_t> counters;
  run_harness({exe.string(), codes_file.string(), std::to_string(run.sample), std::to_string(run_to),
               std::to_string(c.clk_hz), std::to_string(cpb)},
              out,
              {"engine_clocks", "engine_first_byte_clocks", "packets", "adc_overruns",
               "frame_overruns", "dropped_frames", "out_overflows", "link_errors"},
              run, counters, log);
  fs::remove(codes_file);
  require_zero(c, counters,
               {"adc_overruns", "frame_overruns", "dropped_frames", "out_overflows", "link_errors"},
               "the engine or the link does not keep up");
  if (counters["packets"] < 1)
    throw std::runtime_error(fmt::format("latency {}: no packet of frame {} on the wire", c.name,
                                         run.sample));
  run.engine_clocks = counters["engine_clocks"];
  run.engine_first_byte = counters["engine_first_byte_clocks"];
  // The stated clock keeps up with this frame (the bitstream flow's budget).
  const auto budget = hls::dtmf_top_clock_budget(p, c.clk_hz, long(run.engine_clocks));
  if (!budget.ok())
    throw std::runtime_error(fmt::format("latency {}: {} MHz does not keep up: {}", c.name,
                                         c.clk_hz / 1e6, budget.problems.front()));
  if (c.scale_n > 0) {
    // The flow's n x n skin: the clock must keep up with the engine's
    // stress load too (host/fpga/engine_load.h, as the bitstream flow sizes it).
    const long load = long(fpga::measure_engine_load(p, {}).stress_total());
    const auto b = hls::dtmf_top_clock_budget(p, c.clk_hz, load);
    log << fmt::format("  engine stress load {} clocks a frame of {}; min clock {} Hz\n", load,
                       b.frame_clocks, hls::dtmf_top_min_clock_hz(p, load));
    if (!b.ok())
      throw std::runtime_error(fmt::format("latency {}: {} MHz does not keep up: {}", c.name,
                                           c.clk_hz / 1e6, b.problems.front()));
  }
  // The same frame in the frame engine's instruction-set model.
  EngineCycleModel model(p, std::lround(p.spec.sample_hz > 0 ? c.clk_hz / p.spec.sample_hz : 1));
  for (size_t i = 0; i <= run.sample; ++i) model.sample(codes[i]);
  for (size_t i = run.sample + 1; i < codes.size() && i <= run.sample + size_t(p.step); ++i)
    model.sample(codes[i]);  // time to finish the frame
  for (const auto& f : model.frames())
    if (f.t == run.sample) run.model_clocks = f.done, run.model_first_byte = f.first_out;
  return run;
}

std::vector<std::pair<std::string, StageLatency>> read_latency_baseline(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot read the latency baseline");
  std::vector<std::pair<std::string, StageLatency>> rows;
  std::string line;
  int no = 0;
  while (std::getline(f, line)) {
    ++no;
    if (line.empty() || line[0] == '#' || line == "config,stage,cycles") continue;
    std::smatch m;
    if (!std::regex_match(line, m, std::regex("([^,]+),([^,]+),(-?[0-9]+)")))
      throw std::runtime_error(fmt::format("{}:{}: expected config,stage,cycles, got '{}'", path,
                                           no, line));
    rows.push_back({m[1], {m[2], std::stoll(m[3])}});
  }
  return rows;
}

void write_latency_baseline(const std::string& path, const std::vector<LatencyRun>& runs) {
  // Builds not measured in this run keep their rows (`--ci` or `--config`
  // updates only what it ran); rows of builds no longer in the table go.
  std::vector<std::pair<std::string, StageLatency>> old;
  if (fs::exists(path)) old = read_latency_baseline(path);
  std::ostringstream rows;
  for (const auto& c : latency_configs()) {
    bool measured = false;
    for (const auto& r : runs)
      if (r.config.name == c.name) {
        measured = true;
        for (const auto& s : r.stages) rows << c.name << "," << s.stage << "," << s.cycles << "\n";
      }
    if (!measured)
      for (const auto& [name, s] : old)
        if (name == c.name) rows << name << "," << s.stage << "," << s.cycles << "\n";
  }
  std::ofstream f(path);
  f << "# Cycle latencies of the reference builds (eskin bench latency); changed only by\n"
       "# `eskin bench latency --update-baseline`.\nconfig,stage,cycles\n" << rows.str();
  if (!f) throw std::runtime_error(path + ": write failed");
}

std::vector<std::string> compare_latency(
    const std::vector<LatencyRun>& runs,
    const std::vector<std::pair<std::string, StageLatency>>& base, std::vector<std::string>& notes) {
  std::map<std::pair<std::string, std::string>, int64_t> want, got;
  for (const auto& [c, s] : base) want[{c, s.stage}] = s.cycles;
  for (const auto& r : runs)
    for (const auto& s : r.stages) got[{r.config.name, s.stage}] = s.cycles;
  std::vector<std::string> fail;
  for (const auto& [k, v] : got) {
    const auto it = want.find(k);
    if (it == want.end())
      fail.push_back(fmt::format("{} {}: {} cycles, not in the baseline", k.first, k.second, v));
    else if (v > it->second)
      fail.push_back(fmt::format("{} {}: latency grew from {} to {} cycles (+{})", k.first,
                                 k.second, it->second, v, v - it->second));
    else if (v < it->second)
      notes.push_back(fmt::format("{} {}: {} -> {} cycles ({})", k.first, k.second, it->second, v,
                                  v - it->second));
  }
  for (const auto& [k, v] : want) {
    bool measured = false;
    for (const auto& r : runs) measured |= r.config.name == k.first;
    if (measured && !got.count(k))
      fail.push_back(fmt::format("{} {}: in the baseline ({} cycles), not measured", k.first,
                                 k.second, v));
  }
  return fail;
}

std::string format_latency(const std::vector<LatencyRun>& runs) {
  std::string s = "Latency in cycles from the 16th SCLK falling edge of the frame's newest sample\n"
                  "(the Hall top: from the DRDY of the reading that completes the frame)\n";
  s += fmt::format("{:<26}", "stage");
  for (const auto& r : runs) s += fmt::format(" {:>10}", r.config.name);
  s += "\n";
  std::vector<std::string> order;
  for (const auto& r : runs)
    for (const auto& st : r.stages)
      if (std::find(order.begin(), order.end(), st.stage) == order.end()) order.push_back(st.stage);
  const auto cycles = [](const LatencyRun& r, const std::string& stage) -> int64_t {
    for (const auto& st : r.stages)
      if (st.stage == stage) return st.cycles;
    return -1;
  };
  for (const auto& stage : order) {
    s += fmt::format("{:<26}", stage);
    for (const auto& r : runs) s += fmt::format(" {:>10}", cycles(r, stage));
    s += "\n";
  }
  s += "\nEnd to end at the build clock (the ADC, I2C and UART dividers are derived from CLK_HZ, so\n"
       "the cycles hold at that clock only):\n";
  for (const auto& r : runs) {
    const double us = double(cycles(r, "end_to_end")) / (r.config.clk_hz / 1e6);
    if (r.config.top == LatencyConfig::Top::Hall) {
      s += fmt::format("  {}: {} cycles = {:.2f} us at {:g} MHz from the DRDY of the reading that "
                       "completes a frame to its last byte ({:.2f} us to its first)\n",
                       r.config.name, cycles(r, "end_to_end"), us, r.config.clk_hz / 1e6,
                       double(cycles(r, "uart.first_start_bit")) / (r.config.clk_hz / 1e6));
      continue;
    }
    s += fmt::format("  {}: {} cycles = {:.2f} us at {:g} MHz; one ADC sample period {:.1f} us at "
                     "{:.0f} S/s; the thesis's 1 ms window; this build's window N/fs = {:.3f} ms, "
                     "a frame every {} samples ({:.3f} ms)\n",
                     r.config.name, cycles(r, "end_to_end"), us, r.config.clk_hz / 1e6,
                     1e6 / r.plan.spec.sample_hz, r.plan.spec.sample_hz,
                     1e3 * r.plan.N / r.plan.spec.sample_hz, r.plan.step,
                     1e3 * r.plan.step / r.plan.spec.sample_hz);
  }
  return s;
}

}  // namespace eskin::bench
