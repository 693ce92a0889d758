#include "host/bench/scale.h"

#include <fmt/format.h>
#include <malloc.h>

#include <memory>
#include <random>

#include "host/bench/timing.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/engine/exact_sdft.h"
#include "host/golden/sdft_bank.h"

namespace eskin::bench {
namespace {

// Heap bytes in use (glibc): what a decoder allocates for its state.
double heap_mib() { return double(mallinfo2().uordblks) / (1024.0 * 1024.0); }

}  // namespace

std::vector<ScaleRow> run_scale(int max_side, double min_s) {
  const double fs = 35000;  // carriers scale with fs: rates are per sample
  std::vector<ScaleRow> out;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int32_t> code(-2048, 2047);
  std::vector<int32_t> x(1 << 15);
  for (auto& v : x) v = code(rng);
  std::vector<double> xd(x.begin(), x.end());
  for (int side : {3, 8, 16, 32, 64, 128, 256}) {
    if (side > max_side) break;
    ScaleRow r;
    r.rows = r.cols = side;
    r.carriers = 2 * side;
    r.window = 1 << hls::sdft_ceil_log2(2 * r.carriers + 2);
    const auto freqs = plan_carriers(r.carriers, fs, r.window);
    DecoderConfig dec;
    dec.window = r.window;
    {
      const double m0 = heap_mib();
      auto bank = golden::make_sdft_bank(DftVariant::Exact, freqs, fs, dec);
      r.golden_mib = heap_mib() - m0;
      const size_t n = std::max<size_t>(256, size_t(2e7 / r.carriers));
      r.golden_sps = timed(std::min(n, xd.size()), min_s, [&] {
        double s = 0;
        for (size_t i = 0; i < std::min(n, xd.size()); ++i) {
          bank->push(xd[i]);
          for (int k = 0; k < r.carriers; ++k) s += bank->magnitude(k);
        }
        return s;
      }).samples_per_s;
    }
    {
      const double m0 = heap_mib();
      std::vector<uint32_t> inc;
      for (double f : freqs) inc.push_back(hls::sdft_phase_increment(f, fs));
      const int acc = hls::sdft_min_acc_width(r.window, 12);
      engine::ExactSdft bank(engine::SdftWidthsRt{r.window, 12, 16, 10, acc, 0}, inc);
      r.engine_mib = heap_mib() - m0;  // state only: before the output buffer
      // Every sample a frame: its K magnitudes (golden's workload).
      std::vector<uint16_t> mags(x.size() * size_t(r.carriers));
      const engine::MagnitudeWidths mw{acc, 16, acc - 16 > 0 ? acc - 16 : 0};
      r.engine_sps = timed(x.size(), min_s, [&] {
        bank.push_block(x.data(), x.size(), {0, 1}, mw, mags.data());
        return double(mags[mags.size() - 1]);
      }).samples_per_s;
    }
    out.push_back(r);
  }
  return out;
}

std::string format_scale(const std::vector<ScaleRow>& rows) {
  std::string s = fmt::format("{:>9} {:>5} {:>6} {:>14} {:>14} {:>10} {:>10}\n", "skin", "K", "N",
                              "golden S/s", "engine S/s", "golden MiB", "engine MiB");
  std::string g35, e35, g1m, e1m;
  for (const auto& r : rows) {
    const std::string name = fmt::format("{}x{}", r.rows, r.cols);
    s += fmt::format("{:>9} {:>5} {:>6} {:>14.4g} {:>14.4g} {:>10.2f} {:>10.2f}\n", name,
                     r.carriers, r.window, r.golden_sps, r.engine_sps, r.golden_mib, r.engine_mib);
    if (r.golden_sps >= 35000) g35 = name;
    if (r.engine_sps >= 35000) e35 = name;
    if (r.golden_sps >= 1e6) g1m = name;
    if (r.engine_sps >= 1e6) e1m = name;
  }
  const auto or_none = [](const std::string& v) { return v.empty() ? std::string("none") : v; };
  s += fmt::format("largest skin kept up with on one core: 35 kSPS golden {}, engine {}; "
                   "1 MSPS golden {}, engine {}\n",
                   or_none(g35), or_none(e35), or_none(g1m), or_none(e1m));
  s += "memory: heap bytes of the decoder's state (engine: the window's terms N x K x 8 bytes, "
       "sums, phases, sine tables)\n";
  return s;
}

}  // namespace eskin::bench
