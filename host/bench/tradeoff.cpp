#include "host/bench/tradeoff.h"
#include <sys/wait.h>

#include "eskin/process.h"
#include "eskin/source_tree.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

#include "host/bench/engine_model.h"
#include "eskin/fnv1a.h"
#include "eskin/dtmf_top_plan.h"
#include "ucode/dtmf_ucode.h"
#include "hls/sdft_bank_config.h"
#include "hls/sdft_damped.h"
#include "host/engine/dtmf_engine.h"
#include "host/fpga/core_wrapper.h"
#include "host/engine/engine_setup.h"
#include "host/golden/ghost_filter.h"
#include "host/golden/golden_decoder.h"
#include "host/golden/izhikevich_layer.h"
#include "host/golden/taxel_reconstruct.h"
#include "host/report/html_page.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace fs = std::filesystem;

namespace eskin::bench {

std::string TradePoint::key() const {
  return fmt::format("{},{},{},{},{},{},{},{},{}", variant, n, cw, tw, fb, carriers, ghost, step,
                     decim);
}

const std::vector<TradeAxis>& tradeoff_axes() {
  // Values as strings; the default point is the first value of each list.
  static const std::vector<TradeAxis> axes = {
      {"variant",
       {"fpga-exact", "fpga-goertzel", "golden-direct", "golden-recursive", "golden-damped",
        "golden-exact", "golden-ls"},
       {"fpga-exact", "golden-exact", "golden-ls"}},
      {"n", {"32", "16", "64", "128"}, {"32", "64"}},
      {"carriers", {"thesis", "bin"}, {"thesis", "bin"}},
      {"widths", {"16/10/0", "12/8/0", "14/9/0", "16/12/0", "18/12/2", "24/14/4"},
       {"16/10/0", "12/8/0"}},
      {"ghost", {"improved", "off", "thesis"}, {"improved", "off"}},
      // Frames of 0.2 .. 1 ms (the neuron model takes dt <= ~1 ms).
      {"step", {"35", "7", "14", "18", "28"}, {"35", "7"}},
      {"decim", {"1", "2", "5", "35"}, {"1", "5"}},
      // Hall path (when it exists): {"osr", ...}, {"dig_filt", ...},
      // {"loc_table", ...}; add the axis here and its effect in apply_axis.
  };
  return axes;
}

namespace {

bool fpga(const TradePoint& p) { return p.variant.rfind("fpga-", 0) == 0; }
bool top_buildable(const TradePoint& p);  // the plan accepts the point's top build

// A point is built when its carriers fit its window (thesis carriers are
// 1.4 kHz apart: N >= 25 at 35 kHz) and its knobs apply to its variant.
bool buildable(const TradePoint& p) {
  if (p.carriers == "thesis" && p.n < 32) return false;
  if (p.variant != "fpga-exact" && (p.cw != 16 || p.tw != 10 || p.fb != 0)) return false;
  // The top's ghost filter is the improved (greedy pairing) one; the
  // Goertzel bank makes amplitudes only.
  if (p.variant == "fpga-exact" && p.ghost == "thesis") return false;
  if (p.variant == "fpga-goertzel" && p.ghost != "off") return false;
  if (p.variant != "fpga-exact" && p.step != 35) return false;
  return p.variant != "fpga-exact" || top_buildable(p);
}

void apply_axis(TradePoint& p, const std::string& axis, const std::string& v) {
  if (axis == "variant") {
    p.variant = v;
    p.ghost = v == "fpga-exact" ? "improved" : "off";
  } else if (axis == "n") {
    p.n = std::stoi(v);
  } else if (axis == "carriers") {
    p.carriers = v;
  } else if (axis == "widths") {
    std::sscanf(v.c_str(), "%d/%d/%d", &p.cw, &p.tw, &p.fb);
  } else if (axis == "ghost") {
    p.ghost = v;
  } else if (axis == "step") {
    p.step = std::stoi(v);
  } else if (axis == "decim") {
    p.decim = std::stoi(v);
  }
}

}  // namespace

std::vector<TradePoint> tradeoff_points(bool quick) {
  const auto& axes = tradeoff_axes();
  const auto values = [&](size_t i) { return quick ? axes[i].quick : axes[i].full; };
  std::vector<TradePoint> pts;
  std::set<std::string> seen;
  const auto add = [&](const TradePoint& p) {
    if (buildable(p) && seen.insert(p.key()).second) pts.push_back(p);
  };
  // Grid: variant x n x carriers.
  for (const auto& v : values(0))
    for (const auto& n : values(1))
      for (const auto& c : values(2)) {
        TradePoint p;
        apply_axis(p, "variant", v);
        apply_axis(p, "n", n);
        apply_axis(p, "carriers", c);
        add(p);
      }
  // Every other axis alone, around the default point, on both carrier
  // plans (ghost correction also on the golden exact decoder).
  for (size_t a = 3; a < axes.size(); ++a)
    for (const auto& v : values(a))
      for (const auto& c : values(2))
        for (const char* variant : {"fpga-exact", "golden-exact"}) {
          if (axes[a].name != "ghost" && std::string(variant) != "fpga-exact") continue;
          TradePoint p;
          apply_axis(p, "variant", variant);
          apply_axis(p, "carriers", c);
          apply_axis(p, axes[a].name, v);
          add(p);
        }
  return pts;
}

// ---------------------------------------------------------------- synthesis

namespace {

sim::Scene scene_for(const TradePoint& p) {
  sim::Scene sc = sim::load_scene(eskin::source_dir() + "/scenes/neuroskin2.yaml");
  sc.decoder.window = p.n;
  sc.decoder.hop = 1;
  if (p.carriers == "bin") {
    const auto f = plan_carriers(sc.skin.carriers(), sc.skin.adc.rate_hz, p.n);
    sc.skin.row_freq_hz.assign(f.begin(), f.begin() + sc.skin.rows);
    sc.skin.col_freq_hz.assign(f.begin() + sc.skin.rows, f.end());
  }
  return sc;
}

hls::DtmfTopPlan plan_for(const TradePoint& p, const sim::Scene& sc) {
  auto plan = engine::with_step(engine::top_plan(sc.skin, sc.decoder, sc.neuron, true), p.step,
                                p.decim);
  plan.spec.ghost = p.ghost == "improved";
  return plan;
}

// The top exists for the widths of rtl/sdft_bank.v's build (CW 16, TW 10, FB 0).
bool top_widths(const TradePoint& p) { return p.cw == 16 && p.tw == 10 && p.fb == 0; }

bool top_buildable(const TradePoint& p) {
  try {
    plan_for(p, scene_for(p));
    return true;
  } catch (const std::invalid_argument&) {  // e.g. N 16: taxel reciprocal beyond 16 bits
    return false;
  }
}

}  // namespace

std::string synth_key(const TradePoint& p) {
  if (p.variant != "fpga-exact" || !top_widths(p)) return "";
  // The build: its integer parameters, its microcode and its constants
  // (the hex files' contents, not their paths).
  const hls::DtmfTopPlan plan = plan_for(p, scene_for(p));
  const hls::EngineImage im = hls::dtmf_engine_image(plan);
  std::string s;
  for (const auto& q : hls::dtmf_top_params(plan, im, "", ""))
    if (q.name != "UCODE_HEX" && q.name != "KROM_HEX") s += q.name + "=" + q.value + ";";
  for (uint32_t w : hls::dtmf_ucode_words(im)) s += fmt::format("{:x},", w);
  s += ";";
  for (uint32_t w : im.krom) s += fmt::format("{:x},", w);
  s += ";synth_ice40 -dsp -spram -abc9";  // the flow: another flow, other keys
  return fmt::format("{:016x}", fnv1a(s));
}

SynthTable read_synth_table(const std::string& path) {
  SynthTable t;
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("key,", 0) == 0) continue;
    std::istringstream s(line);
    std::string key, v;
    SynthEntry e;
    std::getline(s, key, ',');
    std::getline(s, v, ',');
    e.luts = std::stol(v);
    std::getline(s, v, ',');
    e.dsp = std::stol(v);
    std::getline(s, v, ',');
    e.bram = std::stol(v);
    if (std::getline(s, v, ',')) e.spram = std::stol(v);
    t[key] = e;
  }
  return t;
}

void write_synth_table(const std::string& path, const SynthTable& t) {
  std::ofstream f(path);
  f << "# Yosys synth_ice40 -dsp -spram -abc9 (scripts/synth_ice40.sh) of the trade study's\n"
       "# dtmf_top builds, keyed by a hash of their parameters, microcode, constants and the flow.\n"
       "# Regenerate: eskin bench tradeoff --quick --synth --write-synth-table\n"
       "key,luts,dsp,bram,spram\n";
  for (const auto& [k, e] : t)
    f << k << "," << e.luts << "," << e.dsp << "," << e.bram << "," << e.spram << "\n";
  if (!f) throw std::runtime_error(path + ": write failed");
}

SynthEntry synthesize(const TradePoint& p, const std::string& cache_dir) {
  const std::string key = synth_key(p);
  if (key.empty()) throw std::invalid_argument("synthesize: point " + p.key() + " has no RTL build");
  const fs::path dir = fs::path(cache_dir) / key;
  const fs::path stat = dir / "stat.txt";
  if (!fs::exists(stat)) {
    const fs::path tmp = fs::path(cache_dir) / (key + ".tmp" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    // The build's microcode and constants beside the wrapper that sets its
    // parameters (Yosys reads the hex files while it elaborates).
    const auto params =
        hls::write_dtmf_top_build(plan_for(p, scene_for(p)), fs::absolute(tmp).string(), "top");
    std::ofstream(tmp / "tradeoff_top.v") << fpga::dtmf_core_wrapper("tradeoff_top", params);
    // The project's flow (scripts/synth_ice40.sh: -dsp -spram -abc9), as
    // docs/fpga.md's figures; it writes stat.txt into --out.
    const int st = eskin::run_logged(
        {eskin::source_dir() + "/scripts/synth_ice40.sh", (fs::absolute(tmp) / "tradeoff_top.v").string(),
         "--out", fs::absolute(tmp).string()},
        "/dev/null");
    if (st == -1 || !WIFEXITED(st) || WEXITSTATUS(st) != 0)
      throw std::runtime_error("yosys failed for " + p.key() + ": see " + (tmp / "yosys.log").string());
    std::error_code ec;
    fs::rename(tmp, dir, ec);
    if (ec) fs::remove_all(tmp);
  }
  std::ifstream f(stat);
  std::string line;
  SynthEntry e{0, 0, 0, 0};
  const std::regex cell("^\\s+(SB_\\w+)\\s+([0-9]+)\\s*$");
  while (std::getline(f, line)) {
    std::smatch m;
    if (!std::regex_match(line, m, cell)) continue;
    const long n = std::stol(m[2]);
    if (m[1] == "SB_LUT4") e.luts = n;
    if (m[1] == "SB_MAC16") e.dsp = n;
    if (m[1] == "SB_RAM40_4K") e.bram = n;
    if (m[1] == "SB_SPRAM256KA") e.spram = n;
  }
  return e;
}

// ---------------------------------------------------------------- evaluation

namespace {

struct Stats {
  double sum2 = 0;
  long n = 0;
  void add(double e) { sum2 += e * e, ++n; }
  double rms() const { return n ? std::sqrt(sum2 / double(n)) : -1; }
};

// One decoded frame: amplitudes (skin LSB peak) and, when decoded, pressures.
struct Frame {
  size_t t;
  std::vector<double> amp;
  std::vector<double> kpa;  // empty: no taxels
};

std::vector<Frame> decode_fpga_exact(const TradePoint& p, const sim::Scene& sc,
                                     const std::vector<int>& codes, long& spikes) {
  const auto plan = plan_for(p, sc);
  engine::EngineConfig c = engine::engine_config(plan);
  c.sdft.cw = p.cw;
  c.sdft.tw = p.tw;
  c.sdft.fb = p.fb;
  c.sdft.acc_w = hls::sdft_min_acc_width(p.n, c.sdft.xw, p.fb);
  c.mag_shift += p.fb;  // magnitudes stay in sample-LSB units >> the plan's shift
  const engine::DtmfEngine eng(c);
  const auto c12 = engine::codes12(codes, sc.skin.adc.bits);
  const auto ps = eng.run(c12.data(), c12.size());
  // Magnitude units -> skin LSB peak: x 2^MAG_SHIFT (window sum of 12-bit
  // codes), 2 / N, / 2^(12 - bits); the plain bank keeps its gain G.
  const double g = plan.spec.demix ? 1.0 : (std::ldexp(1.0, p.cw - 1) - 1) / std::ldexp(1.0, p.cw - 1);
  const double unit = std::ldexp(1.0, plan.mag_shift) * 2.0 / p.n /
                      std::ldexp(1.0, 12 - sc.skin.adc.bits) / g;
  std::map<size_t, Frame> frames;
  spikes = 0;
  for (const auto& pk : ps.packets) {
    const uint8_t* b = ps.payload(pk);
    Frame& f = frames[pk.t];
    f.t = pk.t;
    if (pk.type == hls::kDtmfAmplitudes)
      for (uint32_t i = 0; i < pk.len; i += 2) f.amp.push_back((b[i] | b[i + 1] << 8) * unit);
    if (pk.type == hls::kDtmfTaxelsDense)
      for (uint32_t i = 2; i < pk.len; i += 2)
        f.kpa.push_back(sc.skin.conductance.inverse((b[i] | b[i + 1] << 8) / 32768.0));
    if (pk.type == hls::kDtmfSpikes)
      for (uint32_t i = 0; i < pk.len; i += 5) spikes += b[i + 2] == 0;  // receptors (layer 0)
  }
  std::vector<Frame> out;
  for (auto& [t, f] : frames)
    if (!f.amp.empty()) out.push_back(std::move(f));
  return out;
}

template <int N>
std::vector<Frame> goertzel_n(const sim::Scene& sc, const std::vector<int>& codes) {
  using Bank = hls::GoertzelBlockBank<6, N, 12, 16, 4>;
  typename Bank::Config cfg;
  const auto st = hls::make_goertzel_config<Bank>(sc.skin.carrier_freqs_hz(), sc.skin.adc.rate_hz, cfg);
  if (!st.ok()) throw std::invalid_argument("fpga-goertzel: " + st.message);
  Bank bank;
  bank.configure(cfg);
  hls::GoertzelToken tok[6];
  const auto c12 = engine::codes12(codes, sc.skin.adc.bits);
  const double unit = std::ldexp(1.0, 12 - sc.skin.adc.bits);
  std::vector<Frame> out;
  for (size_t i = 0; i < c12.size(); ++i) {
    if (bank.push(int32_t(c12[i]) - 2048, tok) == 0) continue;
    Frame f{i, {}, {}};
    for (int k = 0; k < 6; ++k) f.amp.push_back(2.0 * std::hypot(tok[k].re, tok[k].im) / N / unit);
    out.push_back(std::move(f));
  }
  return out;
}

std::vector<Frame> decode_goertzel(const TradePoint& p, const sim::Scene& sc,
                                   const std::vector<int>& codes) {
  if (sc.skin.carriers() != 6) throw std::invalid_argument("fpga-goertzel: 6 carriers only");
  switch (p.n) {
    case 16: return goertzel_n<16>(sc, codes);
    case 32: return goertzel_n<32>(sc, codes);
    case 64: return goertzel_n<64>(sc, codes);
    case 128: return goertzel_n<128>(sc, codes);
    default: throw std::invalid_argument("fpga-goertzel: n must be 16, 32, 64 or 128");
  }
}

std::vector<Frame> decode_golden(const TradePoint& p, const sim::Scene& sc,
                                 const std::vector<int>& codes) {
  DecoderConfig dec = sc.decoder;
  const std::string v = p.variant.substr(7);
  dec.variant = dft_variant_from_string(v);
  golden::GoldenOptions opt;
  opt.taxels = false;
  opt.spikes = false;
  golden::GoldenDecoder d(sc.skin, dec, sc.neuron, opt);
  std::unique_ptr<golden::GhostFilter> ghost;
  if (p.ghost == "thesis" || p.ghost == "improved") {
    golden::GhostFilterConfig g;
    g.onset = dec.ghost_onset;
    g.release = dec.ghost_threshold;
    g.lookback = p.n;
    g.simultaneous = p.ghost == "improved";
    ghost = std::make_unique<golden::GhostFilter>(sc.skin.rows, sc.skin.cols, g);
  }
  const size_t every = size_t(p.step) * size_t(p.decim);
  std::vector<Frame> out;
  for (size_t i = 0; i < codes.size(); ++i) {
    if (!d.push(codes[i])) continue;
    const auto& fr = d.frame();
    const Eigen::VectorXd rg = fr.line_g.head(sc.skin.rows), cg = fr.line_g.tail(sc.skin.cols);
    Eigen::MatrixXd kpa;
    if (ghost) {
      const Eigen::MatrixXd& g = ghost->update(rg, cg);
      kpa = g.unaryExpr([&](double x) { return sc.skin.conductance.inverse(x); });
    }
    if (i % every) continue;
    if (!ghost) kpa = golden::taxel_pressure(rg, cg, sc.skin.conductance);
    Frame f{i, {fr.amp_lsb.data(), fr.amp_lsb.data() + fr.amp_lsb.size()}, {}};
    for (int r = 0; r < kpa.rows(); ++r)
      for (int c = 0; c < kpa.cols(); ++c) f.kpa.push_back(kpa(r, c));
    out.push_back(std::move(f));
  }
  return out;
}

// Spikes of the reference layer: the scene's neurons (double), one step per
// sample, driven by the true taxel conductances.
long reference_spikes(const sim::Scene& sc, sim::WorldModel& w, size_t n) {
  const int t = sc.skin.rows * sc.skin.cols;
  golden::IzhikevichLayer layer(t, golden::izhikevich_preset(sc.neuron.preset),
                                1000.0 / sc.skin.adc.rate_hz);
  std::vector<double> kpa, in(static_cast<size_t>(t));
  std::vector<int> fired;
  long count = 0;
  for (size_t i = 0; i < n; ++i) {
    w.pressure_at(i, kpa);
    for (int j = 0; j < t; ++j) in[size_t(j)] = sc.neuron.input_scale * sc.skin.conductance.g(kpa[size_t(j)]);
    fired.clear();
    layer.step(in.data(), fired);
    count += long(fired.size());
  }
  return count;
}

}  // namespace

TradeRow evaluate_point(const TradePoint& p, const SynthTable& table,
                        const std::string& synth_cache) {
  TradeRow r;
  r.p = p;
  const sim::Scene sc = scene_for(p);
  sim::WorldModel world(sc);
  const std::vector<int> codes = world.all_codes();
  const double fs = sc.skin.adc.rate_hz, full = sc.skin.full_carrier_lsb();
  const int rows = sc.skin.rows, cols = sc.skin.cols, k = rows + cols;

  std::vector<Frame> frames;
  if (p.variant == "fpga-exact") {
    frames = decode_fpga_exact(p, sc, codes, r.spikes);
    r.spikes_ref = reference_spikes(sc, world, codes.size());
    r.spike_err = r.spikes_ref ? 100.0 * std::fabs(double(r.spikes - r.spikes_ref)) /
                                     double(r.spikes_ref) : -1;
  } else if (p.variant == "fpga-goertzel") {
    frames = decode_goertzel(p, sc, codes);
  } else {
    frames = decode_golden(p, sc, codes);
  }

  // References: the golden direct DFT of the same window; the truth at the
  // window's centre (its group delay).
  DecoderConfig direct = sc.decoder;
  direct.variant = DftVariant::Direct;
  auto bank = golden::make_sdft_bank(DftVariant::Direct, sc.skin.carrier_freqs_hz(), fs, direct);
  Stats amp_truth, amp_golden, kpa_err;
  std::vector<double> kpa;
  size_t fi = 0;
  const double mid = sc.skin.adc.mid_code();
  for (size_t i = 0; i < codes.size() && fi < frames.size(); ++i) {
    bank->push(codes[i] - mid);
    if (i != frames[fi].t) continue;
    const Frame& f = frames[fi++];
    world.pressure_at(i - size_t(p.n - 1) / 2, kpa);
    std::vector<double> line(size_t(k), 0.0);
    for (int a = 0; a < rows; ++a)
      for (int b = 0; b < cols; ++b) {
        const double g = sc.skin.conductance.g(kpa[size_t(a * cols + b)]);
        line[size_t(a)] += g;
        line[size_t(rows + b)] += g;
      }
    for (int c = 0; c < k; ++c) {
      amp_truth.add((f.amp[size_t(c)] - line[size_t(c)] * full) / full * 100);
      amp_golden.add((f.amp[size_t(c)] - bank->magnitude(c)) / full * 100);
    }
    for (size_t j = 0; j < f.kpa.size(); ++j) kpa_err.add(f.kpa[j] - kpa[j]);
  }
  r.amp_err_truth = amp_truth.rms();
  r.amp_err_golden = amp_golden.rms();
  r.pressure_err = kpa_err.rms();

  // Latency and rates.
  const double centre = (p.n - 1) / 2.0;
  if (p.variant == "fpga-exact") {
    const auto plan = plan_for(p, sc);
    r.update_hz = fs / p.step;
    r.packet_hz = fs / (p.step * p.decim);
    if (top_widths(p)) {  // the top's frame engine: its slowest frame (ISS, clock-exact)
      r.latency_cycles = double(max_engine_clocks(
          plan, engine::codes12(codes, sc.skin.adc.bits), std::lround(plan.spec.clk_hz / fs)));
      r.latency_us = r.latency_cycles / (plan.spec.clk_hz / 1e6);
      r.delay_ms = (centre + (p.step - 1)) / fs * 1e3 + r.latency_us / 1e3;
      r.keeps_up = r.latency_cycles <= double(p.step) * double(plan.spec.clk_hz) / fs ? 1 : 0;
    } else {
      r.delay_ms = -1;  // no RTL for these widths: no processing time to add
    }
  } else if (p.variant == "fpga-goertzel") {
    r.delay_ms = (centre + (p.n - 1) / 2.0) / fs * 1e3;  // + the mean wait for the block end
    r.update_hz = r.packet_hz = fs / p.n;
  } else {
    r.delay_ms = centre / fs * 1e3;
    r.update_hz = fs / p.step;
    r.packet_hz = fs / (p.step * p.decim);
  }

  // Resources.
  const std::string key = synth_key(p);
  if (key.empty()) {
    r.resources = p.variant == "fpga-exact" ? "n/a: the top's DFT is CW 16 / TW 10 / FB 0" : "n/a: no RTL";
  } else if (table.count(key)) {
    const auto& e = table.at(key);
    r.luts = e.luts, r.dsp = e.dsp, r.bram = e.bram, r.spram = e.spram, r.resources = "table";
  } else if (!synth_cache.empty()) {
    const auto e = synthesize(p, synth_cache);
    r.luts = e.luts, r.dsp = e.dsp, r.bram = e.bram, r.spram = e.spram, r.resources = "synth";
  } else {
    r.resources = "n/a: not in the synthesis table (--synth)";
  }
  return r;
}

void mark_pareto(std::vector<TradeRow>& rows) {
  const auto front = [&](auto cost, auto flag) {
    for (auto& a : rows) {
      if (cost(a) < 0) continue;
      bool dominated = false;
      for (const auto& b : rows)
        if (&a != &b && cost(b) >= 0 && cost(b) <= cost(a) && b.amp_err_truth <= a.amp_err_truth &&
            (cost(b) < cost(a) || b.amp_err_truth < a.amp_err_truth))
          dominated = true;
      flag(a) = dominated ? 0 : 1;
    }
  };
  // Latency front over the FPGA points only: a golden point's delay has no
  // processing time in it, so it would dominate unfairly.
  front([](const TradeRow& r) { return fpga(r.p) ? r.delay_ms : -1.0; },
        [](TradeRow& r) -> int& { return r.pareto_latency; });
  front([](const TradeRow& r) { return double(r.luts); },
        [](TradeRow& r) -> int& { return r.pareto_resources; });
}

std::string tradeoff_csv_header() {
  return "variant,n,cw,tw,fb,carriers,ghost,step,decim,latency_cycles,latency_us,delay_ms,"
         "update_hz,packet_hz,luts,dsp,bram,spram,resources,amp_err_truth_pct,amp_err_golden_pct,"
         "pressure_err_kpa,spikes,spikes_ref,spike_err_pct,pareto_latency,pareto_resources,keeps_up";
}

std::string tradeoff_csv_row(const TradeRow& r) {
  return fmt::format("{},{:g},{:.4f},{:.5f},{:.6g},{:.6g},{},{},{},{},{},{:.6g},{:.6g},{:.6g},{},{},{:.4g},{},{},{}",
                     r.p.key(), r.latency_cycles, r.latency_us, r.delay_ms, r.update_hz,
                     r.packet_hz, r.luts, r.dsp, r.bram, r.spram, r.resources, r.amp_err_truth,
                     r.amp_err_golden, r.pressure_err, r.spikes, r.spikes_ref, r.spike_err, r.pareto_latency,
                     r.pareto_resources, r.keeps_up);
}

TradePoint parse_point(const std::string& line) {
  std::istringstream s(line);
  std::vector<std::string> f;
  std::string x;
  while (f.size() < 9 && std::getline(s, x, ',')) f.push_back(x);
  if (f.size() < 9) throw std::invalid_argument("tradeoff point: expected 9 key columns in '" + line + "'");
  TradePoint p;
  p.variant = f[0];
  p.n = std::stoi(f[1]);
  p.cw = std::stoi(f[2]);
  p.tw = std::stoi(f[3]);
  p.fb = std::stoi(f[4]);
  p.carriers = f[5];
  p.ghost = f[6];
  p.step = std::stoi(f[7]);
  p.decim = std::stoi(f[8]);
  return p;
}

void write_tradeoff_report(const std::string& path, const std::vector<TradeRow>& rows,
                           const std::string& title) {
  report::Page page(title);
  page.text("Each point is one decoder configuration on the default scene's stimuli "
            "(scenes/neuroskin2.yaml). Error: RMS amplitude error against the ground truth at "
            "the window centre, % of a full carrier. Red: the Pareto front (no other point is "
            "both faster/smaller and more accurate); the latency front is over the FPGA points "
            "(a golden point's delay holds no processing time). Regenerate: eskin bench tradeoff "
            "(docs/bench.md).");
  const auto scatter = [&](const char* xlabel, auto x, auto on_front) {
    nlohmann::json all = nlohmann::json::array(), front = nlohmann::json::array();
    std::vector<const TradeRow*> f;
    for (const auto& r : rows) {
      if (x(r) < 0) continue;
      all.push_back({{"x", x(r)}, {"y", r.amp_err_truth}, {"label", r.p.key()}});
      if (on_front(r)) f.push_back(&r);
    }
    std::sort(f.begin(), f.end(), [&](auto* a, auto* b) { return x(*a) < x(*b); });
    for (auto* r : f) front.push_back({{"x", x(*r)}, {"y", r->amp_err_truth}});
    page.chart({{"type", "scatter"},
                {"data",
                 {{"datasets",
                   {{{"label", "points"}, {"data", all}, {"backgroundColor", "#7f7f7f"}, {"order", 1}},
                    {{"label", "Pareto front"}, {"data", front}, {"showLine", true}, {"order", 0},
                     {"pointRadius", 5}, {"borderColor", "#d62728"},
                     {"backgroundColor", "#d62728"}}}}}},
                {"options",
                 {{"scales",
                   {{"x", {{"type", "logarithmic"}, {"title", {{"display", true}, {"text", xlabel}}}}},
                    {"y", {{"type", "logarithmic"},
                           {"title", {{"display", true}, {"text", "amplitude error vs truth (% full carrier)"}}}}}}}}}},
               380);
  };
  page.heading("Error against latency");
  scatter("delay (ms): window centre + step wait + processing (FPGA points)",
          [](const TradeRow& r) { return fpga(r.p) ? r.delay_ms : -1.0; },
          [](const TradeRow& r) { return r.pareto_latency; });
  page.heading("Error against resources");
  scatter("iCE40 LUT4 (Yosys synth_ice40)", [](const TradeRow& r) { return double(r.luts); },
          [](const TradeRow& r) { return r.pareto_resources; });
  page.heading("All points");
  std::vector<std::string> head;
  std::istringstream h(tradeoff_csv_header());
  for (std::string c; std::getline(h, c, ',');) head.push_back(c);
  std::vector<std::vector<std::string>> body;
  for (const auto& r : rows) {
    std::istringstream s(tradeoff_csv_row(r));
    std::vector<std::string> cells;
    for (std::string c; std::getline(s, c, ',');) cells.push_back(c);
    body.push_back(cells);
  }
  page.table(head, body);
  page.write(path);
}

}  // namespace eskin::bench
