// The figures the docs cite, from generated files only, and a check that
// a doc's figure cannot differ from its file's.
//
// Seven generated files hold every measured figure of docs/ and README.md:
//  - docs/figures.csv (name,value,unit,source): written by this test from
//    the real models: the default scene's plan (common/eskin/dtmf_top_plan.h
//    and its Verilog parameters, ucode/dtmf_engine_image.h), the frame
//    engine's longest frames on its instruction-set model
//    (host/fpga/engine_load.h: ucode/frame_engine.h running the scene's
//    microcode, clock exact against rtl/frame_engine.v), the clocks of
//    single instructions on that model, the DFT lanes' intervals
//    (hls/sdft_bank.h), the demixing's conditioning
//    (hls/carrier_demix_config.h) and the trade study's point counts
//    (host/bench/tradeoff.h). Regenerate it with
//      ESKIN_UPDATE_FIGURES=1 build/bin/system_doc_figures_test
//    (the test then writes the file and passes; without the variable it
//    fails on any difference, naming the figure, the file's value and the
//    measured one);
//  - bench/baselines/latency.csv: `eskin bench latency --update-baseline`
//    (Verilator, checked against the instruction-set model; CI:
//    tests/system/bench_latency_test.cpp);
//  - docs/scale_table.csv: `eskin bitstream --scale-table` (Yosys +
//    nextpnr);
//  - bench/baselines/tradeoff_synth.csv: `eskin bench tradeoff --quick
//    --synth --write-synth-table` (Yosys);
//  - docs/vboard_figures.csv: the default scene's `eskin simulate` figures
//    (tests/vboard/simulate_test.cpp, DefaultSceneFiguresAreTheDocs);
//  - docs/formal.csv: the formal proofs' kinds, depths and times
//    (scripts/formal_table.sh, tests/formal/formal_table_test.cpp);
//  - docs/soak.csv: the line soak (`eskin bench soak --csv docs/soak.csv`,
//    tests/vboard/line_faults_test.cpp);
//  - docs/stream_memory.csv, docs/stream_memory_hdf5.csv: eskin stream's
//    memory over 10^7 packets (`eskin bench memory --csv`,
//    tests/stream/stream_memory_test.cpp at 10^6).
// A doc marks each figure it cites with its name:
//    <!--fig:NAME-->10 077<!--/fig-->
// NAME is a row of docs/figures.csv, latency/CONFIG/STAGE (a row of
// latency.csv; latency/CONFIG/STAGE/us: its cycles in µs at the build's
// clock, bench::latency_configs()) or scale/TARGET/RxC/SAMPLE_HZ/COLUMN (a row of the scale
// table, SAMPLE_HZ as the CSV writes it) or tradeoff_synth/builds,
// tradeoff_synth/COLUMN_min and _max (the stored synthesis table's rows and
// a column's extremes) or vboard/NAME (a row of docs/vboard_figures.csv)
// or formal/MODULE/TASK/depth|seconds, formal/tasks, formal/seconds (rows
// of docs/formal.csv and their count and sum) or soak/NAME (a row of
// docs/soak.csv) or stream_memory/NAME, stream_memory_hdf5/NAME (rows of
// docs/stream_memory.csv, docs/stream_memory_hdf5.csv).
// The text between the markers is
// the number (spaces and commas as thousands separators allowed); a file
// value with more decimals is compared rounded to the doc's decimals. The
// docs check fails naming file:line for every marked figure that differs or
// names nothing, and for a marker left open. A last check scans the docs
// for a number with a measurement unit outside any marker
// (DocsHaveNoUnmarkedMeasuredFigures, kAllowed below): wall-clock speeds,
// synthesis results and run errors are named by the command that reports
// them, not written into the docs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "eskin/dtmf_top_plan.h"
#include "hls/carrier_demix_config.h"
#include "hls/sdft_bank.h"
#include "host/bench/latency.h"
#include "host/bench/tradeoff.h"
#include "host/fpga/engine_load.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"
#include "ucode/dtmf_engine_image.h"
#include "ucode/frame_engine.h"

namespace {

namespace fs = std::filesystem;
using namespace eskin;

const fs::path kSrc = ESKIN_SOURCE_DIR;

struct Figure {
  std::string name, value, unit, source;
};

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// One CSV line, double quotes around a field allowed ("" inside).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
      else if (c == '"') quoted = false;
      else out.back() += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else if (c != '\r') {
      out.back() += c;
    }
  }
  return out;
}

// Rows of a CSV file after its comment lines (#) and its header.
std::vector<std::vector<std::string>> read_csv(const fs::path& p,
                                               std::vector<std::string>* header = nullptr) {
  std::istringstream in(read_text(p));
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool have_header = false;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    auto f = split_csv(line);
    if (!have_header) {
      if (header) *header = f;
      have_header = true;
      continue;
    }
    rows.push_back(f);
  }
  return rows;
}

// Clocks of instruction `w` on the instruction-set model, after a `ldx`
// (a control instruction: no bubble before any instruction).
template <bool FAST>
struct ShiftConfig : hls::FrameEngineConfig {
  static constexpr bool FAST_SHIFT = FAST;
};

template <bool FAST>
uint32_t instruction_clocks(uint32_t w) {
  hls::FrameEngine<ShiftConfig<FAST>> e;
  const uint32_t prog[] = {hls::fe::ctl(hls::fe::kLdx, 1, 0, 1), w};
  e.load_program(prog, 2);
  e.reset();
  e.set_a(1000000);
  hls::FrameEngineNullIo io;
  e.step(io);
  return e.step(io);
}

// Every figure of docs/figures.csv, measured now.
std::vector<Figure> measure_figures() {
  std::vector<Figure> v;
  auto add = [&](std::string name, double value, std::string unit, std::string source) {
    char buf[64];
    if (value == std::floor(value)) std::snprintf(buf, sizeof buf, "%.0f", value);
    else std::snprintf(buf, sizeof buf, "%.6g", value);
    v.push_back({std::move(name), buf, std::move(unit), std::move(source)});
  };

  // The default scene's build: the plan, its Verilog parameters, its load.
  const sim::Scene sc = sim::load_scene((kSrc / "scenes/neuroskin2.yaml").string());
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz));
  const auto image = hls::dtmf_engine_image(plan);
  const auto params = hls::dtmf_top_params(plan, image, "", "");
  auto param = [&](const std::string& n) {
    for (const auto& p : params)
      if (p.name == n) return std::stol(p.value);
    ADD_FAILURE() << "dtmf_top_params has no " << n;
    return 0L;
  };
  const char* plan_src = "common/eskin/dtmf_top_plan.h (make_dtmf_top_plan, dtmf_top_params)";
  const long period = std::lround(double(plan.spec.clk_hz) / plan.spec.sample_hz);
  const long frame = period * plan.step;
  add("default.clk_mhz", plan.spec.clk_hz / 1e6, "MHz", plan_src);
  add("default.sample_clocks", period, "clocks", plan_src);
  add("default.step", plan.step, "samples", plan_src);
  add("default.frame_clocks", frame, "clocks", plan_src);
  add("default.iw", param("IW"), "bits", plan_src);
  add("default.dw", param("DW"), "bits", plan_src);
  add("default.dmem_words", 1L << param("DW"), "words", plan_src);
  add("default.kw", param("KW"), "bits", plan_src);
  add("default.dft_channels", param("KS"), "channels", plan_src);

  sim::WorldModel world(sc);
  const auto codes = world.all_codes();
  const int up = 12 - sc.skin.adc.bits;
  std::vector<int32_t> x;
  for (int c : codes) x.push_back((c << up) - 2048);
  const fpga::EngineLoad load = fpga::measure_engine_load(plan, x);
  const char* load_src = "host/fpga/engine_load.h (measure_engine_load, instruction-set model)";
  add("default.longest_frame", double(load.scene_clocks), "clocks", load_src);
  add("default.longest_frame_percent", std::round(100.0 * load.scene_clocks / frame), "%",
      load_src);
  add("default.idle_percent", std::round(100.0 - 100.0 * load.scene_clocks / frame), "%",
      load_src);
  add("default.scene_frames", load.scene_frames, "frames", load_src);
  add("default.stress_frame", double(load.stress_bound()), "clocks", load_src);
  add("default.longest_command", double(load.command_clocks), "clocks", load_src);
  add("default.stress_plus_command", double(load.stress_total()), "clocks", load_src);
  add("default.stress_plus_command_percent", std::round(100.0 * load.stress_total() / frame), "%",
      load_src);

  // Single instructions (docs/frame_engine.md, Timing): clocks each costs
  // after an instruction that leaves A alone.
  namespace fe = hls::fe;
  const char* fe_src = "ucode/frame_engine.h (FrameEngine::step)";
  add("fe.min_clocks", instruction_clocks<false>(fe::imm(fe::kMin, 5)), "clocks", fe_src);
  add("fe.max_clocks", instruction_clocks<false>(fe::imm(fe::kMax, 5)), "clocks", fe_src);
  add("fe.sqrt_clocks", instruction_clocks<false>(fe::ctl(fe::kSqrt, 0, 0, 0)), "clocks", fe_src);
  add("fe.sqrtr_clocks", instruction_clocks<false>(fe::ctl(fe::kSqrtr, 0, 0, 0)), "clocks", fe_src);
  add("fe.sqrt_clocks_fast", instruction_clocks<true>(fe::ctl(fe::kSqrt, 0, 0, 0)), "clocks",
      fe_src);
  add("fe.rnd12_clocks", instruction_clocks<false>(fe::imm(fe::kRnd, 12)), "clocks", fe_src);
  add("fe.rnd12_clocks_fast", instruction_clocks<true>(fe::imm(fe::kRnd, 12)), "clocks", fe_src);
  add("fe.shl15_clocks", instruction_clocks<false>(fe::imm(fe::kShl, 15)), "clocks", fe_src);
  add("fe.shl15_clocks_fast", instruction_clocks<true>(fe::imm(fe::kShl, 15)), "clocks", fe_src);
  add("fe.shr1_clocks", instruction_clocks<false>(fe::imm(fe::kShr, 1)), "clocks", fe_src);
  add("fe.sqrt_clocks_saved",
      double(instruction_clocks<false>(fe::ctl(fe::kSqrt, 0, 0, 0))) -
          instruction_clocks<true>(fe::ctl(fe::kSqrt, 0, 0, 0)),
      "clocks", fe_src);

  // The DFT lanes' intervals (docs/fpga.md, DFT lanes; docs/bitstream.md,
  // Clocks): clocks of a frame's sample and of a skipped one for KS
  // channels in L lanes, the consumer taking a token a clock (frame_capture).
  const char* lanes_src = "hls/sdft_bank.h (sdft_lanes_interval, sdft_skip_interval)";
  for (const auto& [ks, lanes] : std::vector<std::pair<int, int>>{
           {24, 3}, {24, 5}, {24, 6}, {64, 11}, {64, 10}, {32, 6}, {8, 1}, {8, 2}, {44, 8}}) {
    const std::string key = "sdft.ks" + std::to_string(ks) + "_l" + std::to_string(lanes);
    add(key + "_frame", double(hls::sdft_lanes_interval(ks, lanes, 1)), "clocks", lanes_src);
    add(key + "_skip", double(hls::sdft_skip_interval(ks, lanes)), "clocks", lanes_src);
  }

  // The demixing's conditioning (docs/carrier_demix.md): the thesis
  // carriers at 35 kHz through the builder of the top's demix (K 6, TW 10,
  // SW 16, CW 16, CF 14, the sums' gain of sdft_bank's Q1.15 amplitude).
  const char* demix_src = "hls/carrier_demix_config.h (carrier_demix_tables)";
  const std::vector<double> thesis = {1900, 3300, 5000, 7140, 8300, 10000};
  auto demix = [&](const std::vector<double>& f, int n) {
    hls::CarrierDemixTables t;
    const double gain = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);
    return hls::carrier_demix_tables(f, 35000, gain, n, 6, 10, 16, 16, 14, 1, 1 - n, t);
  };
  auto rounded = [](double x, int decimals) {
    const double s = std::pow(10.0, decimals);
    return std::round(x * s) / s;
  };
  for (int n : {32, 64, 24, 16}) {
    const auto st = demix(thesis, n);
    const std::string key = "demix.n" + std::to_string(n);
    EXPECT_EQ(st.ok, n != 16) << key << ": " << st.message;
    add(key + "_condition", rounded(st.condition, 3), "", demix_src);
    if (n == 32) add(key + "_kappa", rounded(std::sqrt(st.condition), 3), "", demix_src);
    if (st.ok) {
      add(key + "_max_coef", rounded(st.max_coef, 3), "", demix_src);
      add(key + "_row_norm", rounded(st.row_norm, 3), "", demix_src);
    }
  }
  std::vector<double> bins;
  for (int k = 2; k <= 7; ++k) bins.push_back(k * 35000.0 / 32);
  const auto bin_st = demix(bins, 32);
  add("demix.n32_bins_condition", rounded(bin_st.condition, 3), "", demix_src);
  add("demix.n32_bins_max_coef", rounded(bin_st.max_coef, 3), "", demix_src);
  add("demix.n32_bins_row_norm", rounded(bin_st.row_norm, 3), "", demix_src);

  // The trade study's sweeps (docs/bench.md, Trade study).
  const char* trade_src = "host/bench/tradeoff.cpp (tradeoff_points)";
  add("tradeoff.quick_points", double(bench::tradeoff_points(true).size()), "points", trade_src);
  add("tradeoff.points", double(bench::tradeoff_points(false).size()), "points", trade_src);
  return v;
}

const fs::path kFiguresCsv = kSrc / "docs/figures.csv";

void write_figures(const std::vector<Figure>& figs) {
  std::ofstream f(kFiguresCsv, std::ios::binary);
  f << "# Measured figures the docs cite (<!--fig:NAME-->), written by\n"
       "# tests/system/doc_figures_test.cpp (ESKIN_UPDATE_FIGURES=1\n"
       "# build/bin/system_doc_figures_test); the test fails when a figure here\n"
       "# differs from the models' or a doc's differs from here.\n"
       "name,value,unit,source\n";
  for (const auto& g : figs) f << g.name << ',' << g.value << ',' << g.unit << ",\"" << g.source << "\"\n";
}

// PREFIX/NAME for each `name,value,...` row of a docs table (relative to
// the source tree).
void add_named_rows(std::map<std::string, std::string>& m, const std::string& prefix,
                    const std::string& file) {
  EXPECT_TRUE(fs::exists(kSrc / file)) << file << ": missing";
  for (const auto& r : read_csv(kSrc / file))
    if (r.size() >= 2) m[prefix + "/" + r[0]] = r[1];
}

// Every figure a doc may cite, by name.
std::map<std::string, std::string> known_figures() {
  std::map<std::string, std::string> m;
  for (const auto& r : read_csv(kFiguresCsv))
    if (r.size() >= 2) m[r[0]] = r[1];
  // latency/CONFIG/STAGE: cycles; latency/CONFIG/STAGE/us: the same at
  // the reference build's clock (bench::latency_configs()).
  std::map<std::string, long> clk;
  for (const auto& c : bench::latency_configs()) clk[c.name] = c.clk_hz;
  for (const auto& r : read_csv(kSrc / "bench/baselines/latency.csv")) {
    if (r.size() != 3) continue;
    m["latency/" + r[0] + "/" + r[1]] = r[2];
    EXPECT_TRUE(clk.count(r[0])) << "bench/baselines/latency.csv: " << r[0]
                                 << " is no reference build of bench::latency_configs()";
    if (clk.count(r[0])) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.6f", std::stod(r[2]) * 1e6 / double(clk[r[0]]));
      m["latency/" + r[0] + "/" + r[1] + "/us"] = buf;
    }
  }
  // vboard/NAME: the default scene on the virtual board, as `eskin
  // simulate` prints it (docs/vboard_figures.csv, written and checked by
  // tests/vboard/simulate_test.cpp, DefaultSceneFiguresAreTheDocs).
  add_named_rows(m, "vboard", "docs/vboard_figures.csv");
  // soak/NAME: the line soak's table (docs/soak.csv, written by `eskin
  // bench soak --csv`; checked by tests/vboard/line_faults_test.cpp,
  // LineSoak.TheDocsTableHoldsTogether).
  add_named_rows(m, "soak", "docs/soak.csv");
  // stream_memory/NAME, stream_memory_hdf5/NAME: eskin stream's memory over
  // a long stream, without and with an HDF5 recording (`eskin bench memory
  // --csv`, host/stream/stream_memory.h; tests/stream/stream_memory_test.cpp
  // runs the same measurement at 10^6 packets).
  add_named_rows(m, "stream_memory", "docs/stream_memory.csv");
  add_named_rows(m, "stream_memory_hdf5", "docs/stream_memory_hdf5.csv");
  // formal/MODULE/TASK/depth and /seconds, formal/tasks, formal/seconds:
  // the proofs' table (docs/formal.csv, scripts/formal_table.sh; checked
  // against tests/formal/*.sby by tests/formal/formal_table_test.cpp).
  {
    double total = 0;
    const auto frows = read_csv(kSrc / "docs/formal.csv");
    for (const auto& r : frows) {
      if (r.size() != 6) continue;
      m["formal/" + r[0] + "/" + r[1] + "/depth"] = r[3];
      m["formal/" + r[0] + "/" + r[1] + "/seconds"] = r[4];
      total += std::stod(r[4]);
    }
    m["formal/tasks"] = std::to_string(frows.size());
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", total);
    m["formal/seconds"] = buf;
  }
  // tradeoff_synth/builds, tradeoff_synth/COLUMN_min, _max: the stored
  // synthesis table of the trade study's quick builds
  // (bench/baselines/tradeoff_synth.csv, `eskin bench tradeoff --quick
  // --synth --write-synth-table`).
  {
    std::vector<std::string> th;
    const auto trows = read_csv(kSrc / "bench/baselines/tradeoff_synth.csv", &th);
    m["tradeoff_synth/builds"] = std::to_string(trows.size());
    for (size_t i = 1; i < th.size(); ++i) {
      long lo = 0, hi = 0;
      for (size_t r = 0; r < trows.size(); ++r) {
        const long x = std::stol(trows[r].at(i));
        lo = r ? std::min(lo, x) : x;
        hi = r ? std::max(hi, x) : x;
      }
      m["tradeoff_synth/" + th[i] + "_min"] = std::to_string(lo);
      m["tradeoff_synth/" + th[i] + "_max"] = std::to_string(hi);
    }
  }
  std::vector<std::string> h;
  const auto rows = read_csv(kSrc / "docs/scale_table.csv", &h);
  auto col = [&](const std::string& n) {
    for (size_t i = 0; i < h.size(); ++i)
      if (h[i] == n) return i;
    ADD_FAILURE() << "docs/scale_table.csv has no column " << n;
    return size_t(0);
  };
  const size_t target = col("target"), rows_c = col("rows"), cols_c = col("cols"),
               rate = col("sample_hz");
  for (const auto& r : rows) {
    if (r.size() != h.size()) continue;
    const std::string key =
        "scale/" + r[target] + "/" + r[rows_c] + "x" + r[cols_c] + "/" + r[rate] + "/";
    for (size_t i = 0; i < h.size(); ++i) m[key + h[i]] = r[i];
  }
  return m;
}

// The number a doc writes, without thousands separators (space, no-break
// and thin spaces, commas); "" when it is not a number.
std::string doc_number(std::string s) {
  for (const char* sep : {"\xe2\x80\xaf", "\xc2\xa0", "\xe2\x80\x89", " ", ","}) {
    for (size_t at; (at = s.find(sep)) != std::string::npos;) s.erase(at, std::strlen(sep));
  }
  return std::regex_match(s, std::regex("-?[0-9]+(\\.[0-9]+)?")) ? s : "";
}

// Whether a doc's number `d` cites the file's value `v` (rounded to d's
// decimals when v has more).
bool cites(const std::string& d, const std::string& v) {
  if (d == v) return true;
  const size_t dot = d.find('.');
  const int decimals = dot == std::string::npos ? 0 : int(d.size() - dot - 1);
  char* end = nullptr;
  const double value = std::strtod(v.c_str(), &end);
  if (v.empty() || *end) return false;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return d == buf;
}

std::vector<fs::path> doc_files() {
  std::vector<fs::path> v = {kSrc / "README.md"};
  for (const auto& e : fs::directory_iterator(kSrc / "docs"))
    if (e.path().extension() == ".md") v.push_back(e.path());
  std::sort(v.begin(), v.end());
  return v;
}

// One message per marked figure of `text` (file `name`) that is wrong.
std::vector<std::string> check_doc(const std::string& name, const std::string& text,
                                   const std::map<std::string, std::string>& figs, int* marked) {
  std::vector<std::string> bad;
  std::istringstream in(text);
  std::string line;
  const std::regex mark("<!--fig:([^>]*?)-->(.*?)<!--/fig-->");
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string where = name + ":" + std::to_string(n) + ": ";
    size_t opened = 0;
    for (size_t at = 0; (at = line.find("<!--fig:", at)) != std::string::npos; ++at) ++opened;
    size_t closed = 0;
    for (std::sregex_iterator it(line.begin(), line.end(), mark), end; it != end; ++it, ++closed) {
      ++*marked;
      const std::string fig = (*it)[1], text_value = (*it)[2];
      const auto f = figs.find(fig);
      const std::string d = doc_number(text_value);
      if (f == figs.end())
        bad.push_back(where + "figure " + fig + " is in no generated file");
      else if (d.empty())
        bad.push_back(where + "figure " + fig + ": \"" + text_value + "\" is not a number");
      else if (!cites(d, f->second))
        bad.push_back(where + "figure " + fig + " reads " + text_value + ", the generated value is " +
                      f->second);
    }
    if (opened != closed) bad.push_back(where + "a <!--fig:...--> without its <!--/fig--> on the line");
  }
  return bad;
}

TEST(DocFigures, FiguresFileEqualsTheModels) {
  const auto measured = measure_figures();
  if (const char* u = std::getenv("ESKIN_UPDATE_FIGURES"); u && *u && std::string(u) != "0") {
    write_figures(measured);
    std::printf("wrote %s (%zu figures)\n", kFiguresCsv.c_str(), measured.size());
  }
  std::map<std::string, std::string> file;
  for (const auto& r : read_csv(kFiguresCsv))
    if (r.size() >= 2) file[r[0]] = r[1];
  for (const auto& g : measured) {
    std::printf("  %-32s %10s %s\n", g.name.c_str(), g.value.c_str(), g.unit.c_str());
    const auto f = file.find(g.name);
    if (f == file.end())
      ADD_FAILURE() << "docs/figures.csv lacks " << g.name << " (measured " << g.value
                    << "): regenerate it (ESKIN_UPDATE_FIGURES=1)";
    else
      EXPECT_EQ(f->second, g.value) << "docs/figures.csv: " << g.name << " is " << f->second
                                    << ", the models give " << g.value
                                    << " (regenerate: ESKIN_UPDATE_FIGURES=1, then fix the docs)";
  }
  EXPECT_EQ(file.size(), measured.size()) << "docs/figures.csv has figures nothing measures";
}

TEST(DocFigures, DocsCiteTheGeneratedFigures) {
  const auto figs = known_figures();
  int marked = 0;
  std::vector<std::string> bad;
  for (const auto& p : doc_files()) {
    const auto b = check_doc(fs::relative(p, kSrc).string(), read_text(p), figs, &marked);
    bad.insert(bad.end(), b.begin(), b.end());
  }
  for (const auto& b : bad) ADD_FAILURE() << b;
  std::printf("%d marked figures\n", marked);
  EXPECT_GE(marked, 150);
}

// The check itself: a wrong, unknown, non-numeric or unclosed figure fails,
// a right one (with separators, or rounded) passes.
TEST(DocFigures, CheckFailsOnAWrongFigure) {
  const std::map<std::string, std::string> figs = {{"a", "10077"}, {"b", "54.27"}};
  int marked = 0;
  EXPECT_TRUE(check_doc("d.md", "x <!--fig:a-->10 077<!--/fig--> y <!--fig:b-->54.3<!--/fig-->", figs,
                        &marked)
                  .empty());
  EXPECT_EQ(marked, 2);
  const auto bad = check_doc("d.md", "ok\n<!--fig:a-->10 387<!--/fig-->\n<!--fig:c-->1<!--/fig-->\n"
                             "<!--fig:a-->ten<!--/fig-->\n<!--fig:a-->10077\n<!--fig:b-->54.2<!--/fig-->",
                             figs, &marked);
  ASSERT_EQ(bad.size(), 5u);
  EXPECT_EQ(bad[0], "d.md:2: figure a reads 10 387, the generated value is 10077");
  EXPECT_NE(bad[1].find("d.md:3: figure c is in no generated file"), std::string::npos);
  EXPECT_NE(bad[2].find("d.md:4:"), std::string::npos);
  EXPECT_NE(bad[3].find("d.md:5: a <!--fig:"), std::string::npos);
  EXPECT_NE(bad[4].find("d.md:6:"), std::string::npos);
}

// A number with a measurement unit outside a marker, which no generated
// file would check: clocks or cycles from 100 up (smaller counts are the
// design's own: an instruction's, a pipeline's, a bit's clocks), MHz with
// decimals (a clock somebody set is a whole MHz; an Fmax or a needed clock
// has decimals), and every count of logic (LC, LUT, FF, flip-flops, EBR,
// TRELLIS_COMB, DP16KD). A heuristic: it reads one line at a time, so a
// number and its unit on two lines escape it.
struct Allowed {
  const char* figure;  // the number and unit as the scan reads them
  const char* why;
};
// Design constants and arithmetic the scan would take for measurements.
// Keep it short: a measured figure belongs in a generated file and a marker.
const Allowed kAllowed[] = {
    {"3.125 MHz", "the ECP5 PLL's least phase-detector frequency (datasheet)"},
    {"37.3-40 MHz", "the AD7476A's first clock band at 1 MS/s (its datasheet's SCLK and tACQ)"},
    {"74.7-80 MHz", "the AD7476A's second clock band at 1 MS/s"},
    {"12.0 MHz", "the requirement in a quoted `misses timing` message (the Hall top's clock)"},
    {"12000 clocks", "1 ms at 12 MHz"},
    {"40000 clocks", "1 ms at 40 MHz (the AD7476A's first band)"},
    {"44999 clocks", "a 1 ms frame at 45 MHz less the CDC's clock (the formula beside it)"},
    {"29995 clocks", "35 samples of 857 clocks (30 MHz at 35 kS/s)"},
    {"1800 cycles", "the virtual board's 100 us batch at 18 MHz"},
    {"3170 clocks", "an I2C reading computed from the 34-clock bit beside it, not measured"},
    {"64 flip-flops", "two 32-bit registers of the design (the unit's x_prev copy and result)"},
    {"128 EBRs", "the divisor of the memory formula 2^IW / 128 EBRs"},
    {"1000 LCs", "the frame engine's design target (well under 1000 LCs)"},
};

// One message per unmarked measured-looking figure of `text` (file `name`).
std::vector<std::string> unmarked_figures(const std::string& name, const std::string& text) {
  static const std::regex mark("<!--fig:[^>]*?-->.*?<!--/fig-->");
  static const std::regex number(
      "(^|[^\\w.])(\\d{1,3}(?: \\d{3})+|\\d+(?:\\.\\d+)?)((?:\\.\\.|-)\\d+(?:\\.\\d+)?)? ?"
      "(clocks?|cycles?|LCs?|LUT4?s?|FFs?|flip-flops|EBRs?|MHz|TRELLIS_COMB|DP16KDs?)\\b");
  std::vector<std::string> bad;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::string l = std::regex_replace(line, mark, "FIG");
    for (const char* sep : {"\xe2\x80\xaf", "\xc2\xa0", "\xe2\x80\x89"})
      for (size_t at; (at = l.find(sep)) != std::string::npos;) l.replace(at, std::strlen(sep), " ");
    for (std::sregex_iterator it(l.begin(), l.end(), number), end; it != end; ++it) {
      std::string num = (*it)[2], range = (*it)[3];
      const std::string unit = (*it)[4];
      num.erase(std::remove(num.begin(), num.end(), ' '), num.end());
      if (range.rfind("..", 0) == 0) range = "-" + range.substr(2);
      const bool counts = unit.rfind("clock", 0) == 0 || unit.rfind("cycle", 0) == 0;
      if (counts && std::stod(num) < 100) continue;
      if (unit == "MHz" && (num + range).find('.') == std::string::npos) continue;
      const std::string fig = num + range + " " + unit;
      bool allowed = false;
      for (const auto& a : kAllowed) allowed = allowed || fig == a.figure;
      if (!allowed)
        bad.push_back(name + ":" + std::to_string(n) + ": \"" + fig +
                      "\" is in no marker: cite a generated file (<!--fig:NAME-->), or name "
                      "the command that reports it");
    }
  }
  return bad;
}

TEST(DocFigures, DocsHaveNoUnmarkedMeasuredFigures) {
  for (const auto& p : doc_files())
    for (const auto& b : unmarked_figures(fs::relative(p, kSrc).string(), read_text(p)))
      ADD_FAILURE() << b;
}

// The scan itself: measured-looking figures fail, marked ones, small
// clock counts, whole-MHz clocks and allowed constants pass.
TEST(DocFigures, ScanFailsOnAnUnmarkedFigure) {
  EXPECT_TRUE(unmarked_figures("d.md",
                               "takes <!--fig:a-->5259<!--/fig--> LC at 18 MHz; `min` 2 clocks;\n"
                               "the band 37.3..40 MHz, 1 ms = 12 000 clocks at 12 MHz\n")
                  .empty());
  const auto bad = unmarked_figures(
      "d.md", "ok\n5259 LC, Fmax 19.85 MHz\nits frame takes 10 077 clocks\n3 EBRs and 1234 TRELLIS_COMB\n");
  ASSERT_EQ(bad.size(), 5u);
  EXPECT_EQ(bad[0].rfind("d.md:2: \"5259 LC\"", 0), 0u) << bad[0];
  EXPECT_EQ(bad[1].rfind("d.md:2: \"19.85 MHz\"", 0), 0u) << bad[1];
  EXPECT_EQ(bad[2].rfind("d.md:3: \"10077 clocks\"", 0), 0u) << bad[2];
  EXPECT_EQ(bad[3].rfind("d.md:4: \"3 EBRs\"", 0), 0u) << bad[3];
  EXPECT_EQ(bad[4].rfind("d.md:4: \"1234 TRELLIS_COMB\"", 0), 0u) << bad[4];
}

// Docs say what is: dated notes and old measurements belong to git history.
TEST(DocFigures, DocsCarryNoDatedNotes) {
  const std::regex date("20[0-9][0-9]-[01][0-9]-[0-3][0-9]");
  for (const auto& p : doc_files()) {
    std::istringstream in(read_text(p));
    std::string line;
    for (int n = 1; std::getline(in, line); ++n)
      EXPECT_FALSE(std::regex_search(line, date))
          << fs::relative(p, kSrc).string() << ":" << n << ": a dated note: " << line;
  }
}

}  // namespace
