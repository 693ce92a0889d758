#include "host/fpga/scale_table.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sim/dtmf_top_spec.h"

namespace eskin::fpga {

std::vector<ScaleTarget> scale_targets() {
  return {{"up5k", "icebreaker", "up5k"}, {"ecp5-25k", "ulx3s", "25k"}, {"ecp5-85k", "ulx3s", "85k"}};
}

std::vector<double> scale_rates() { return {35000.0, 1000000.0}; }

std::vector<int> scale_sizes() { return {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64}; }

sim::Scene scale_scene(const sim::Scene& base, int n, double fs) {
  sim::Scene s = base;
  s.name = fmt::format("scale_{}x{}_{:g}sps", n, n, fs);
  s.skin.rows = n;
  s.skin.cols = n;
  s.skin.adc.rate_hz = fs;
  int window = 32;
  while (window / 2 - 1 < 2 * n) window *= 2;
  s.decoder.window = window;
  const auto f = plan_carriers(2 * n, fs, window);
  s.skin.row_freq_hz.assign(f.begin(), f.begin() + n);
  s.skin.col_freq_hz.assign(f.begin() + n, f.end());
  s.skin.freq_error.clear();
  s.presses.clear();
  s.slides.clear();
  return s;
}

std::string variant_name(EngineVariant v) {
  return std::string(v.barrel ? "barrel" : "serial") + " shifter, " +
         (v.lanes ? "neuron lanes" : v.unit ? "neuron unit" : "engine neurons");
}

std::optional<SlowerClock> slower_clock_variant(const Board& b, const sim::Scene& scene,
                                                EngineVariant failed, long failed_clk_hz,
                                                LoadPolicy policy) {
  // Fewest logic cells first: the barrel shifter costs about 1000 iCE40
  // cells, the neuron unit about 1900 (docs/fpga.md).
  for (const EngineVariant v : {EngineVariant{false, false}, EngineVariant{true, false},
                                EngineVariant{false, true}, EngineVariant{true, true}}) {
    if (v == failed) continue;
    CoreClock c;
    try {
      c = choose_core_clock(b, scene, policy, 0, v.barrel, v.unit ? 1 : 0, true, 0);
    } catch (const std::invalid_argument&) {
      continue;  // the engine cannot hold the skin with this variant
    }
    if (c.budget.ok() && (failed_clk_hz == 0 || c.clocking.clk_hz < failed_clk_hz))
      return SlowerClock{v, c.clocking.clk_hz, c.engine_clocks};
  }
  return std::nullopt;
}

const char* shifter_name(EngineVariant v) { return v.barrel ? "barrel" : "serial"; }
const char* neurons_name(EngineVariant v) {
  return v.lanes ? "lanes" : v.unit ? "unit" : "engine";
}

namespace {
// For a failed build `r`: slower_clock_variant when its core was too slow
// (not for area or pins), under r's load policy; else none.
std::optional<SlowerClock> slower_clock_after(const Board& b, const sim::Scene& scene,
                                              const FlowReport& r) {
  const bool too_slow =
      r.ran_tools ? r.fits && !r.meets_timing : r.core_min_hz > 0 && !r.budget.ok();
  // (the streaming datapath's engine is its control plane: no variant)
  if (r.ok() || !too_slow || r.spec.datapath == hls::DtmfDatapath::Streaming) return std::nullopt;
  return slower_clock_variant(b, scene,
                              {r.spec.engine_fast_shift, r.spec.neuron_unit, r.spec.neuron_lanes > 0},
                              r.budget.ok() ? r.clk_hz : 0, r.policy);
}
}  // namespace

std::string slower_engine_hint(const Board& b, const sim::Scene& scene, const FlowReport& r) {
  const auto s = slower_clock_after(b, scene, r);
  if (!s) return "";
  return fmt::format(
      "with a {} the core keeps up at {:g} MHz (its engine takes {} clocks a frame, {} load): "
      "--engine-shifter {} --neurons {}",
      variant_name(s->engine), s->clk_hz / 1e6, s->engine_clocks,
      r.policy == LoadPolicy::Stress ? "stress" : "scene", shifter_name(s->engine),
      neurons_name(s->engine));
}

ScaleRow scale_row(const ScaleTarget& t, const FlowReport& r) {
  ScaleRow row;
  row.target = t.label;
  row.board = t.board;
  row.device = t.device;
  row.sample_hz = r.spec.sample_hz;
  row.rows = r.spec.rows;
  row.cols = r.spec.cols;
  row.window = r.spec.window;
  row.step = r.step;
  row.clk_hz = r.spec.clk_hz;
  row.adc_clk_hz = r.spec.adc_clk_hz;
  row.engine = {r.spec.engine_fast_shift, r.spec.neuron_unit, r.spec.neuron_lanes > 0};
  row.fits = r.fits;
  row.meets_timing = r.meets_timing;
  auto take = [&](std::initializer_list<const char*> names, long& used, long* avail) {
    for (const char* n : names)
      if (const Resource* x = r.resource(n)) {
        used = x->used;
        if (avail) *avail = x->available;
      }
  };
  take({r.logic_resource.c_str()}, row.logic_used, &row.logic_available);
  take({"ICESTORM_DSP", "MULT18X18D"}, row.dsp_used, &row.dsp_available);
  take({"ICESTORM_RAM", "DP16KD"}, row.ram_used, &row.ram_available);
  take({"ICESTORM_SPRAM"}, row.spram_used, nullptr);
  // The clock with the least margin (the core's; the ULX3S oscillator net
  // has next to no logic).
  if (const ClockResult* c = r.slowest_clock()) row.fmax_mhz = c->achieved_mhz;
  row.seed = r.seed > 0 ? r.seed : 1;  // 0: stopped before the tools
  row.frame_clocks = r.budget.frame_clocks;
  row.engine_clocks = r.engine_clocks;
  row.bound_clocks = long(r.bound.total());
  row.streaming = r.spec.datapath == hls::DtmfDatapath::Streaming;
  row.seconds = r.seconds;
  row.failure = r.failure;
  return row;
}

std::vector<ScaleRow> run_scale_table(const sim::Scene& base, const FlowOptions& opt,
                                      ScaleSelection sel,
                                      const std::function<void(const ScaleRow&)>& progress) {
  std::vector<ScaleRow> rows;
  const auto& sizes = sel.sizes.empty() ? (sel.sizes = scale_sizes()) : sel.sizes;
  for (size_t i = 0; i < sizes.size(); ++i)
    if (sizes[i] < 1 || (i > 0 && sizes[i] <= sizes[i - 1]))
      throw std::invalid_argument("--sizes: expected ascending sizes >= 1");
  if (sel.rates.empty()) sel.rates = scale_rates();
  std::vector<ScaleTarget> targets;
  for (const auto& t : scale_targets())
    if (sel.targets.empty() ||
        std::find(sel.targets.begin(), sel.targets.end(), t.label) != sel.targets.end())
      targets.push_back(t);
  if (targets.size() < std::max<size_t>(1, sel.targets.size()))
    throw std::invalid_argument("--targets: expected labels among up5k, ecp5-25k, ecp5-85k");
  for (const auto& t : targets) {
    const Board b = find_board(t.board, t.device);
    for (double fs : sel.rates) {
      // Invariant: sizes[lo] passed (or lo = -1), sizes[hi] failed (or hi = size()).
      int lo = -1, hi = int(sizes.size());
      while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        const int n = sizes[size_t(mid)];
        const sim::Scene sc = scale_scene(base, n, fs);
        const auto probe = [&](int fast_shift, int neuron_unit, const std::string& dir) {
          FlowOptions o = opt;
          o.load = LoadPolicy::Stress;  // the table's skins have no workload of their own
          o.fast_shift = fast_shift;
          o.neuron_unit = neuron_unit;
          o.out_dir = fmt::format("{}/{}/{:.0f}/{}", opt.out_dir, t.label, fs, dir);
          FlowReport r;
          try {
            r = run_flow(b, sc, o);
          } catch (const std::invalid_argument& e) {  // the plan rejects the skin
            r.spec = sim::dtmf_top_spec(sc);
            apply_engine_options(b, fast_shift, neuron_unit, r.spec);
            r.failure = e.what();
          }
          rows.push_back(scale_row(t, r));
          progress(rows.back());
          return r;
        };
        const FlowReport r = probe(opt.fast_shift, opt.neuron_unit, fmt::format("{}x{}", n, n));
        bool ok = rows.back().ok();
        // Too slow: an engine that keeps up at a slower clock may make it.
        if (opt.fast_shift < 0 && opt.neuron_unit < 0)
          if (const auto s = slower_clock_after(b, sc, r)) {
            const EngineVariant v = s->engine;
            probe(v.barrel, v.unit,
                  fmt::format("{}x{}-{}-{}", n, n, shifter_name(v), neurons_name(v)));
            ok = rows.back().ok();
          }
        (ok ? lo : hi) = mid;
      }
    }
  }
  return rows;
}

std::vector<ScaleRow> merge_scale_rows(const std::vector<ScaleRow>& old,
                                       const std::vector<ScaleRow>& fresh) {
  std::vector<ScaleRow> out;
  for (const auto& r : old) {
    bool replaced = false;
    for (const auto& f : fresh) replaced |= f.target == r.target && f.sample_hz == r.sample_hz;
    if (!replaced) out.push_back(r);
  }
  out.insert(out.end(), fresh.begin(), fresh.end());
  return out;
}

namespace {
const char* kHeader =
    "target,board,device,sample_hz,rows,cols,window,step,clk_hz,adc_clk_hz,shifter,neurons,fits,"
    "meets_timing,"
    "logic_used,logic_available,dsp_used,dsp_available,ram_used,ram_available,spram_used,seed,"
    "fmax_mhz,seconds,frame_clocks,engine_clocks,bound_clocks,datapath,failure";
// The headers before the datapath column (its rows read as the frame
// engine's) and before the engine's clock columns (those read as 0).
const char* kHeaderWithoutDatapath =
    "target,board,device,sample_hz,rows,cols,window,step,clk_hz,adc_clk_hz,shifter,neurons,fits,"
    "meets_timing,"
    "logic_used,logic_available,dsp_used,dsp_available,ram_used,ram_available,spram_used,seed,"
    "fmax_mhz,seconds,frame_clocks,engine_clocks,bound_clocks,failure";
const char* kHeaderWithoutClocks =
    "target,board,device,sample_hz,rows,cols,window,step,clk_hz,adc_clk_hz,shifter,neurons,fits,"
    "meets_timing,"
    "logic_used,logic_available,dsp_used,dsp_available,ram_used,ram_available,spram_used,seed,"
    "fmax_mhz,seconds,failure";

std::string csv_field(const std::string& s) {
  std::string q = "\"";
  // One line per row: a tool's multi-line message is joined with spaces.
  for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c == '\n' || c == '\r' ? ' ' : c);
  return q + "\"";
}

// Splits one CSV line (fields optionally in double quotes, "" inside them).
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      f.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

// The markdown's engine column: the frame engine's variant, or the
// streaming datapath with its control plane's shifter.
std::string row_engine(const ScaleRow& r) {
  return r.streaming ? fmt::format("streaming datapath ({} shifter control plane)",
                                   shifter_name(r.engine))
                     : variant_name(r.engine);
}

std::string khz(double fs) { return fs >= 1e6 ? fmt::format("{:g} MS/s", fs / 1e6) : fmt::format("{:g} kS/s", fs / 1e3); }
}  // namespace

std::string scale_csv(const std::vector<ScaleRow>& rows) {
  std::string s = std::string(kHeader) + "\n";
  for (const auto& r : rows)
    s += fmt::format(
        "{},{},{},{:g},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.2f},{:.0f},{},{},{},"
        "{},{}\n",
        r.target, r.board, r.device, r.sample_hz, r.rows, r.cols, r.window, r.step, r.clk_hz,
        r.adc_clk_hz, shifter_name(r.engine), neurons_name(r.engine), int(r.fits),
        int(r.meets_timing), r.logic_used, r.logic_available, r.dsp_used, r.dsp_available,
        r.ram_used, r.ram_available, r.spram_used, r.seed, r.fmax_mhz, r.seconds, r.frame_clocks,
        r.engine_clocks, r.bound_clocks,
        datapath_name(r.streaming ? hls::DtmfDatapath::Streaming : hls::DtmfDatapath::FrameEngine),
        csv_field(r.failure));
  return s;
}

std::vector<ScaleRow> parse_scale_csv(const std::string& text) {
  std::vector<ScaleRow> rows;
  std::stringstream ss(text);
  std::string line;
  int lineno = 0;
  size_t fields = 29;
  while (std::getline(ss, line)) {
    ++lineno;
    if (lineno == 1) {
      if (line == kHeaderWithoutClocks) fields = 25;
      else if (line == kHeaderWithoutDatapath) fields = 28;
      else if (line != kHeader)
        throw std::runtime_error("scale table line 1: expected the header '" + std::string(kHeader) + "'");
      continue;
    }
    if (line.empty()) continue;
    auto f = split_csv(line);
    if (f.size() != fields)
      throw std::runtime_error(
          fmt::format("scale table line {}: expected {} fields, got {}", lineno, fields, f.size()));
    if (fields == 25) f.insert(f.begin() + 24, {"0", "0", "0"});
    if (fields <= 28) f.insert(f.begin() + 27, "engine");
    if (f[27] != "engine" && f[27] != "streaming")
      throw std::runtime_error(fmt::format(
          "scale table line {}: expected datapath engine|streaming, got {}", lineno, f[27]));
    if ((f[10] != "serial" && f[10] != "barrel") ||
        (f[11] != "engine" && f[11] != "unit" && f[11] != "lanes"))
      throw std::runtime_error(fmt::format(
          "scale table line {}: expected shifter serial|barrel and neurons engine|unit|lanes, "
          "got {} {}",
          lineno, f[10], f[11]));
    try {
      ScaleRow r;
      r.target = f[0];
      r.board = f[1];
      r.device = f[2];
      r.sample_hz = std::stod(f[3]);
      r.rows = std::stoi(f[4]);
      r.cols = std::stoi(f[5]);
      r.window = std::stoi(f[6]);
      r.step = std::stoi(f[7]);
      r.clk_hz = std::stol(f[8]);
      r.adc_clk_hz = std::stol(f[9]);
      r.engine = {f[10] == "barrel", f[11] != "engine", f[11] == "lanes"};
      r.fits = f[12] == "1";
      r.meets_timing = f[13] == "1";
      r.logic_used = std::stol(f[14]);
      r.logic_available = std::stol(f[15]);
      r.dsp_used = std::stol(f[16]);
      r.dsp_available = std::stol(f[17]);
      r.ram_used = std::stol(f[18]);
      r.ram_available = std::stol(f[19]);
      r.spram_used = std::stol(f[20]);
      r.seed = std::stoi(f[21]);
      r.fmax_mhz = std::stod(f[22]);
      r.seconds = std::stod(f[23]);
      r.frame_clocks = std::stol(f[24]);
      r.engine_clocks = std::stol(f[25]);
      r.bound_clocks = std::stol(f[26]);
      r.streaming = f[27] == "streaming";
      r.failure = f[28];
      rows.push_back(r);
    } catch (const std::logic_error&) {
      throw std::runtime_error(fmt::format("scale table line {}: a number field is not a number", lineno));
    }
  }
  return rows;
}

std::string scale_markdown(const std::vector<ScaleRow>& rows) {
  std::string t =
      "| FPGA | rate | largest skin that fits and meets timing | carriers | window | engine | "
      "clock | logic | DSP | block RAM | Fmax | engine clocks a frame: measured / bound of the "
      "frame's (spare under the bound) | smallest that fails |\n"
      "|---|---|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& tg : scale_targets())
    for (double fs : scale_rates()) {
      // A size passes when one of its builds (engines) does.
      std::map<int, std::vector<const ScaleRow*>> sizes;
      for (const auto& r : rows)
        if (r.target == tg.label && r.sample_hz == fs) sizes[r.rows].push_back(&r);
      const ScaleRow* best = nullptr;
      int fail = 0;
      for (const auto& [n, builds] : sizes) {
        const auto good =
            std::find_if(builds.begin(), builds.end(), [](const ScaleRow* r) { return r->ok(); });
        if (good != builds.end()) best = *good;
        else if (fail == 0) fail = n;
      }
      std::string why = "-";
      if (fail > 0) {
        why = fmt::format("{}x{}: ", fail, fail);
        const auto& builds = sizes[fail];
        for (size_t i = 0; i < builds.size(); ++i)
          why += (i ? "; " : "") +
                 (builds.size() > 1 ? row_engine(*builds[i]) + ": " : "") +
                 builds[i]->failure;
      }
      if (!best) {
        t += fmt::format("| {} | {} | none | | | | | | | | | | {} |\n", tg.label, khz(fs), why);
        continue;
      }
      const std::string clocks =
          best->bound_clocks > 0 && best->frame_clocks > 0
              ? fmt::format("{} / {} of {} ({:.0f} %)", best->engine_clocks, best->bound_clocks,
                            best->frame_clocks,
                            100.0 * double(best->frame_clocks - best->bound_clocks) /
                                double(best->frame_clocks))
              : std::string("-");
      t += fmt::format(
          "| {} | {} | {}x{} | {} | {} | {} | {:g} MHz{} | {}/{} | {}/{} | {}/{} | {:.1f} MHz{} | {} | {} |\n",
                       tg.label, khz(fs), best->rows, best->cols, best->rows + best->cols,
                       best->window, row_engine(*best), best->clk_hz / 1e6,
                       best->adc_clk_hz > 0 ? fmt::format(" (ADC {:g})", best->adc_clk_hz / 1e6)
                                            : std::string(),
                       best->logic_used, best->logic_available, best->dsp_used,
                       best->dsp_available, best->ram_used, best->ram_available, best->fmax_mhz,
                       best->seed != 1 ? fmt::format(" (seed {})", best->seed) : std::string(),
                       clocks, why);
    }
  return t;
}

std::string fit_hint(const std::vector<ScaleRow>& rows, const std::string& board,
                     const std::string& device, double fs) {
  const ScaleRow* best = nullptr;
  double rate = 0;
  // The table's rate nearest to fs (on a log scale).
  for (const auto& r : rows)
    if (r.board == board && r.device == device &&
        (rate == 0 || std::fabs(std::log(r.sample_hz / fs)) < std::fabs(std::log(rate / fs))))
      rate = r.sample_hz;
  for (const auto& r : rows)
    if (r.board == board && r.device == device && r.sample_hz == rate && r.ok() &&
        (!best || r.rows * r.cols > best->rows * best->cols))
      best = &r;
  if (rate == 0)
    return fmt::format("the scale table (docs/scale_table.csv) has no entry for {} {}; "
                       "`eskin bitstream --scale-table` measures it",
                       board, device);
  if (!best)
    return fmt::format("per the scale table (docs/scale_table.csv) no skin tried fits {} {} at {}",
                       board, device, khz(rate));
  return fmt::format(
      "per the scale table (docs/scale_table.csv), {} {} at {} fits skins up to {}x{} "
      "({} carriers, window {}: {}/{} logic cells, Fmax {:.1f} MHz at a {:g} MHz clock)",
      board, device, khz(rate), best->rows, best->cols, best->rows + best->cols, best->window,
      best->logic_used, best->logic_available, best->fmax_mhz, best->clk_hz / 1e6);
}

}  // namespace eskin::fpga
