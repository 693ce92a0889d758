#include "host/bench/stability.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "host/bench/timing.h"
#include "hls/izhikevich_layer.h"
#include "hls/izhikevich_layer_config.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/engine/exact_sdft.h"
#include "host/golden/sdft_bank.h"
#include "host/report/html_page.h"

namespace eskin::bench {
namespace {

// The top's DFT: 6 thesis carriers, N 32, 12-bit samples.
constexpr int kN = 32, kXW = 12, kCW = 16, kTW = 10, kAccW = 18, kK = 6;
using Kernel = hls::SdftBank<kK, kN, kXW, kCW, kTW, kAccW>;

// Worst-case input, generated on the fly (no 10^9-sample buffer): blocks of
// 4096 samples cycling through full-scale DC, full-scale alternation, the
// sign of each carrier's cosine at full scale (the largest window sum that
// carrier can reach) and full-scale random values.
struct WorstCase {
  std::vector<uint32_t> inc;
  uint64_t rng = 0x9e3779b97f4a7c15ull;
  int32_t at(uint64_t n) {
    const int32_t hi = (1 << (kXW - 1)) - 1, lo = -(1 << (kXW - 1));
    const uint64_t mode = (n >> 12) % 9;
    if (mode == 0) return hi;
    if (mode == 1) return (n & 1) ? hi : lo;
    if (mode == 2) return lo;
    if (mode < 9 && mode >= 3) {
      const uint32_t th = uint32_t(n * inc[mode - 3]);
      return (th + 0x40000000u) < 0x80000000u ? hi : lo;  // sign of cos
    }
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return int32_t(rng % 4096) - 2048;
  }
};

}  // namespace

StabilityResult run_stability(uint64_t samples, uint64_t neuron_steps, int checkpoints,
                              const hls::IzhikevichConfig (&neurons)[2]) {
  StabilityResult res;
  res.samples = samples;
  res.carriers = kK;
  res.window = kN;
  const double t0 = wall_seconds();
  const std::vector<double> f = {1900, 3300, 5000, 7140, 8300, 10000};
  const double fs = 35000;
  Kernel::Config kc;
  if (!hls::make_sdft_bank_config<Kernel>(f, fs, kc).ok()) throw std::logic_error("carriers");
  WorstCase in{std::vector<uint32_t>(kc.inc, kc.inc + kK)};
  engine::ExactSdft bank(engine::SdftWidthsRt{kN, kXW, kCW, kTW, kAccW, 0}, in.inc);
  DecoderConfig dec;
  dec.window = kN;
  auto naive = golden::make_sdft_bank(DftVariant::Recursive, f, fs, dec);
  auto damped = golden::make_sdft_bank(DftVariant::Damped, f, fs, dec);
  auto direct = golden::make_sdft_bank(DftVariant::Direct, f, fs, dec);
  // Checkpoints spaced geometrically (the drift plot is log-log), last = end.
  std::vector<uint64_t> at;
  for (int i = 1; i <= checkpoints; ++i) {
    const uint64_t c = uint64_t(std::llround(std::pow(double(samples), double(i) / checkpoints)));
    if (c >= uint64_t(kN) && (at.empty() || c > at.back())) at.push_back(c);
  }
  std::vector<int32_t> win(kN);  // the last N samples, for the direct sums
  std::vector<int32_t> buf(8192);
  uint64_t n = 0;
  for (uint64_t next : at) {
    while (n < next) {
      const size_t len = size_t(std::min<uint64_t>(buf.size(), next - n));
      for (size_t i = 0; i < len; ++i) {
        buf[i] = in.at(n + i);
        const double x = buf[i];
        naive->push(x);
        damped->push(x);
        direct->push(x);
      }
      bank.push_block(buf.data(), len);
      for (size_t i = (len >= size_t(kN) ? len - kN : 0); i < len; ++i)
        win[size_t((n + i) % kN)] = buf[i];
      n += len;
    }
    DriftPoint d{n, 0, 0, 0};
    for (int k = 0; k < kK; ++k) {
      // Direct sum of the window's terms, T(x[m], theta(m)), from the kernel.
      int64_t re = 0, im = 0;
      for (uint64_t m = n - kN; m < n; ++m) {
        const uint32_t idx = Kernel::index(uint32_t(m * kc.inc[k]));
        const int32_t x = win[size_t(m % kN)];
        re += Kernel::term(x, Kernel::cosine(idx));
        im += Kernel::term(x, -Kernel::sine(idx));
      }
      d.exact_lsb = std::max<int64_t>({d.exact_lsb, std::llabs(re - bank.re(k)), std::llabs(im - bank.im(k))});
      d.naive_err = std::max(d.naive_err, std::fabs(naive->magnitude(k) - direct->magnitude(k)));
      d.damped_err = std::max(d.damped_err, std::fabs(damped->magnitude(k) - direct->magnitude(k)));
    }
    res.drift.push_back(d);
  }

  // Neurons at the edges of their range, both layers as the top runs them
  // (the plan's configurations: one step per frame). Each at its largest
  // and smallest inputs (x = +-2^31: the 16-bit operand saturates), then
  // with the gain at its maximum (mantissa 32767 << 15), where J saturates
  // at +-512 mV per step: hls/izhikevich_layer.h proves a spike every step
  // at +max and v pinned at V_MIN at -max.
  bool recovered = true;
  for (int layer = 0; layer < 2; ++layer) {
    const hls::IzhikevichConfig& nc = neurons[layer];
    const std::string who = fmt::format("layer {}: ", layer + 1);
    hls::IzhikevichConfig big = nc;
    big.gain = 32767;
    big.gain_shift = -15;
    big.input_change = false;  // a held input: the drive itself, not its change
    const auto run = [&](const hls::IzhikevichConfig& c, const std::string& phase, int32_t& v,
                         int32_t& u, int32_t x, uint64_t steps) {
      NeuronEdge e{who + phase, steps, 0, true, ""};
      for (uint64_t s = 0; s < steps; ++s) {
        e.spikes += hls::izhikevich_update(c, v, u, x);
        e.in_range = e.in_range && v >= hls::izh::kVMin && v < hls::izh::kVPeak &&
                     u >= hls::izh::kUMin && u <= hls::izh::kUMax;
      }
      return e;
    };
    int32_t v = nc.v_init, u = nc.u_init, fv = nc.v_init, fu = nc.u_init;
    auto top = run(nc, "x = +max", v, u, INT32_MAX, neuron_steps);
    top.note = fmt::format("the fastest this configuration fires: 1 spike per {:.1f} steps",
                           double(top.steps) / double(std::max<uint64_t>(1, top.spikes)));
    res.neurons.push_back(top);
    auto bottom = run(nc, "x = -max", v, u, INT32_MIN, neuron_steps);
    bottom.note = bottom.spikes == 0 ? "silent" : "FIRES";
    res.neurons.push_back(bottom);
    auto hi = run(big, "max gain, J = +512 mV/step", v, u, INT32_MAX, neuron_steps);
    hi.note = hi.spikes == hi.steps ? "a spike every step" : "MISSED spikes";
    res.neurons.push_back(hi);
    auto lo = run(big, "max gain, J = -512 mV/step", v, u, INT32_MIN, neuron_steps);
    lo.note = lo.spikes == 0 && v == hls::izh::kVMin ? "silent, v pinned at V_MIN" : "NOT pinned";
    res.neurons.push_back(lo);
    NeuronEdge alt{who + "max gain, +-512 mV alternating", 0, 0, true, ""};
    for (uint64_t s = 0; s < neuron_steps; ++s) {
      const auto one = run(big, "", v, u, (s & 1) ? INT32_MIN : INT32_MAX, 1);
      alt.steps += 1, alt.spikes += one.spikes, alt.in_range = alt.in_range && one.in_range;
    }
    res.neurons.push_back(alt);
    // Recovery: rest 1000 steps (1 s of 1 ms frames), then a firm press
    // (x = 16384: g = 0.5 for the receptors) for 10 000; the spike trains
    // and the final state must equal a fresh neuron's.
    const uint64_t rest = 1000, press = 10000;
    auto r1 = run(nc, "rest after the extremes", v, u, 0, rest);
    run(nc, "", fv, fu, 0, rest);
    auto p1 = run(nc, "x = 16384 after the extremes", v, u, 16384, press);
    const auto p0 = run(nc, "", fv, fu, 16384, press);
    p1.note = fmt::format("fresh neuron: {} spikes; state afterwards {}", p0.spikes,
                          v == fv && u == fu ? "identical" : "differs");
    recovered = recovered && p1.spikes == p0.spikes && v == fv && u == fu;
    res.neurons.push_back(r1);
    res.neurons.push_back(p1);
  }
  res.recovered = recovered;
  res.seconds = wall_seconds() - t0;
  return res;
}

std::string format_stability(const StabilityResult& r) {
  std::string s = fmt::format(
      "Exact sliding DFT (K {}, N {}, 12-bit worst-case input) against the direct sum of its "
      "window's terms; golden naive recursive and damped (r 0.9999) SDFTs against the direct "
      "DFT, max amplitude error in LSB:\n{:>14} {:>12} {:>14} {:>14}\n",
      r.carriers, r.window, "sample", "exact LSB", "naive LSB", "damped LSB");
  int64_t worst = 0;
  for (const auto& d : r.drift) {
    s += fmt::format("{:>14} {:>12} {:>14.4g} {:>14.4g}\n", d.sample, d.exact_lsb, d.naive_err,
                     d.damped_err);
    worst = std::max(worst, d.exact_lsb);
  }
  s += fmt::format("exact: {} LSB from the direct sum over {} samples ({})\n\n", worst, r.samples,
                   worst == 0 ? "bit-exact" : "MISMATCH");
  s += "Izhikevich neurons (hls, both layers of the top's plan, one step per frame) at the edges "
       "of their input range:\n";
  for (const auto& e : r.neurons)
    s += fmt::format("  {:<46} {:>11} steps {:>11} spikes  in range: {}  {}\n", e.phase, e.steps,
                     e.spikes, e.in_range ? "yes" : "NO", e.note);
  s += fmt::format("recovery (same spikes and state as a fresh neuron): {}\n",
                   r.recovered ? "yes" : "NO");
  s += fmt::format("{:.0f} s wall\n", r.seconds);
  return s;
}

void write_stability_report(const std::string& path, const StabilityResult& r) {
  report::Page page("eskin stability: exact vs naive vs damped sliding DFT");
  page.text(fmt::format("{} samples of worst-case 12-bit input, {} carriers, N = {}. The exact "
                        "sliding DFT's distance from the direct sum is plotted as 1e-3 LSB when it "
                        "is 0 (log axis). Regenerate: eskin bench stability (docs/bench.md).",
                        r.samples, r.carriers, r.window));
  nlohmann::json ex = nlohmann::json::array(), na = nlohmann::json::array(),
                 da = nlohmann::json::array();
  for (const auto& d : r.drift) {
    ex.push_back({{"x", double(d.sample)}, {"y", d.exact_lsb ? double(d.exact_lsb) : 1e-3}});
    na.push_back({{"x", double(d.sample)}, {"y", std::max(d.naive_err, 1e-16)}});
    da.push_back({{"x", double(d.sample)}, {"y", std::max(d.damped_err, 1e-16)}});
  }
  const auto set = [](const char* label, const nlohmann::json& data, const char* colour) {
    return nlohmann::json{{"label", label}, {"data", data}, {"borderColor", colour},
                          {"backgroundColor", colour}, {"showLine", true}};
  };
  page.chart({{"type", "scatter"},
              {"data", {{"datasets", {set("exact (integer, vs direct sum)", ex, "#2ca02c"),
                                      set("naive recursive (double)", na, "#d62728"),
                                      set("damped r = 0.9999 (double)", da, "#1f77b4")}}}},
              {"options",
               {{"scales",
                 {{"x", {{"type", "logarithmic"}, {"title", {{"display", true}, {"text", "samples"}}}}},
                  {"y", {{"type", "logarithmic"},
                         {"title", {{"display", true}, {"text", "max amplitude error (LSB)"}}}}}}}}}},
             400);
  std::vector<std::vector<std::string>> rows;
  for (const auto& e : r.neurons)
    rows.push_back({e.phase, std::to_string(e.steps), std::to_string(e.spikes),
                    e.in_range ? "yes" : "NO", e.note});
  page.heading("Neurons at the edges of their range");
  page.table({"phase", "steps", "spikes", "in range", "note"}, rows);
  page.write(path);
}

}  // namespace eskin::bench
