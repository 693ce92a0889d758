#include "host/bench/throughput.h"

#include <fftw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "host/bench/timing.h"
#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"
#include "host/golden/golden_decoder.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace eskin::bench {

const ThroughputRow& ThroughputResult::row(const std::string& name) const {
  for (const auto& r : rows)
    if (r.name == name) return r;
  throw std::out_of_range("throughput: no row " + name);
}

namespace {

// with_hypot: the magnitudes by std::hypot, as this row computed them
// before (the row the first ratios were measured against); else
// by the square root of the squares, the reference: hypot guards against
// an overflow no window sum comes near, at several times the cost.
Rate fftw_stft(const std::vector<double>& x, const std::vector<double>& freqs, double fs, int n,
               double min_s, bool with_hypot) {
  std::vector<int> nearest;
  for (double f : freqs) nearest.push_back(int(std::lround(f / fs * n)));
  double* in = fftw_alloc_real(size_t(n));
  fftw_complex* out = fftw_alloc_complex(size_t(n / 2 + 1));
  fftw_plan plan = fftw_plan_dft_r2c_1d(n, in, out, FFTW_MEASURE);
  std::vector<double> ring(2 * size_t(n), 0.0);
  // A doubled ring makes the window one contiguous copy.
  Rate r = timed(x.size(), min_s, [&] {
    std::fill(ring.begin(), ring.end(), 0.0);
    double sum = 0.0;
    size_t pos = 0;
    for (double v : x) {
      pos = pos + 1 == size_t(n) ? 0 : pos + 1;
      ring[pos] = ring[pos + size_t(n)] = v;
      std::memcpy(in, &ring[pos + 1], sizeof(double) * size_t(n));
      fftw_execute(plan);
      if (with_hypot)
        for (int b : nearest) sum += std::hypot(out[b][0], out[b][1]);
      else
        for (int b : nearest) sum += std::sqrt(out[b][0] * out[b][0] + out[b][1] * out[b][1]);
    }
    return sum * 2.0 / n;
  });
  fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return r;
}

}  // namespace

hls::DtmfTopPlan feasible_plan(const sim::Scene& sc, long& clk_hz) {
  clk_hz = hls::kDtmfTopClkHz;  // the plan's chain does not depend on the clock
  return engine::top_plan(sc.skin, sc.decoder, sc.neuron, true, clk_hz);
}

ThroughputResult measure_throughput(const std::string& scene_path, double min_s, int threads) {
  const sim::Scene scene = sim::load_scene(scene_path);
  sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  const std::vector<double> freqs = scene.skin.carrier_freqs_hz();
  const double fs = scene.skin.adc.rate_hz, mid = scene.skin.adc.mid_code();
  const DecoderConfig& dec = scene.decoder;
  const int n = dec.window, k = int(freqs.size());
  std::vector<double> x(codes.size());
  for (size_t i = 0; i < codes.size(); ++i) x[i] = codes[i] - mid;

  ThroughputResult res;
  res.scene = scene.name;
  res.carriers = k;
  res.window = n;
  res.fs = fs;
  res.samples = x.size();
  res.threads = threads;
  const auto add = [&](const std::string& name, const Rate& r, const char* clock) {
    res.rows.push_back({name, r.samples_per_s, 0, r.checksum, clock});
  };
  add("fftw-stft", fftw_stft(x, freqs, fs, n, min_s, false), "cpu");  // the reference (first row)
  add("fftw-stft-hypot", fftw_stft(x, freqs, fs, n, min_s, true), "cpu");

  for (DftVariant v : {DftVariant::Direct, DftVariant::Recursive, DftVariant::Damped,
                       DftVariant::Exact, DftVariant::LsDemix}) {
    if (v == DftVariant::LsDemix && 2 * k + 1 > n) continue;
    add(std::string("golden-") + to_string(v), timed(x.size(), min_s, [&] {
          auto bank = golden::make_sdft_bank(v, freqs, fs, dec);
          double sum = 0.0;
          for (double s : x) {
            bank->push(s);
            for (int c = 0; c < k; ++c) sum += bank->magnitude(c);
          }
          return sum;
        }), "cpu");
  }

  // Engine amplitudes: same workload (every sample: push, K magnitudes).
  // The chain as the top is built for the scene (its step and decimation).
  const engine::EngineConfig ec = engine::engine_config(feasible_plan(scene, res.clk_hz));
  res.chain_step = ec.step;
  const std::vector<uint16_t> c12 = engine::codes12(codes, scene.skin.adc.bits);
  std::vector<int32_t> xi(c12.size());
  for (size_t i = 0; i < c12.size(); ++i) xi[i] = int32_t(c12[i]) - 2048;
  {
    // The K carriers' DFT (no DC channel, no demixing: the FFTW rows'
    // work), every sample a frame: K magnitudes in the sample loop.
    const std::vector<uint32_t> inc(ec.inc.begin(), ec.inc.begin() + k);
    std::vector<uint16_t> mags(xi.size() * size_t(k));
    const engine::MagnitudeWidths mw{ec.sdft.acc_w, 16, ec.mag_shift};
    // Magnitudes (window sums of 12-bit codes >> MAG_SHIFT) back to skin
    // LSB amplitude (2/N |sum|), as the other rows.
    const double to_lsb =
        std::ldexp(2.0 / n, ec.mag_shift) / std::ldexp(1.0, 12 - scene.skin.adc.bits);
    // The bank is built once (its tables; as FFTW's plan) and restarted
    // every pass. The checksum adds the integer magnitudes as integers, in
    // 32-bit runs of 65536 (no overflow): a dependent chain of double adds,
    // one per carrier and sample, would take longer than the engine's work.
    engine::ExactSdft bank(ec.sdft, inc);
    add("engine-amplitudes", timed(xi.size(), min_s, [&] {
          bank.start_at(0);
          bank.push_block(xi.data(), xi.size(), {0, 1}, mw, mags.data());
          uint64_t sum = 0;
          for (size_t a = 0; a < mags.size(); a += 65536) {
            uint32_t run = 0;
            for (size_t i = a; i < std::min(mags.size(), a + 65536); ++i) run += mags[i];
            sum += run;
          }
          return double(sum) * to_lsb;
        }), "cpu");
  }

  golden::GoldenOptions opt;
  opt.spikes = true;
  const DftVariant used = golden::resolve_variant(dec.variant, freqs, fs, dec);
  add(std::string("golden-decoder-") + to_string(used), timed(codes.size(), min_s, [&] {
        golden::GoldenDecoder d(scene.skin, dec, scene.neuron, opt);
        double frames = 0;
        for (int c : codes) frames += d.push(c);
        return frames;
      }), "cpu");
  const engine::DtmfEngine eng(ec);
  add("engine-chain", timed(c12.size(), min_s, [&] {
        return double(eng.run(c12.data(), c12.size(), {1}).packets.size());
      }), "cpu");
  if (threads > 1) {
    add("engine-chain-1t", timed(c12.size(), min_s, [&] {
          return double(eng.run(c12.data(), c12.size(), {1}).packets.size());
        }, true), "wall");
    add(fmt::format("engine-chain-{}t", threads), timed(c12.size(), min_s, [&] {
          return double(eng.run(c12.data(), c12.size(), {threads, 0}).packets.size());
        }, true), "wall");
    // Several skins at once: `threads` recordings (the same stream), each
    // decoded on its own thread; samples/s counts all of them.
    add(fmt::format("engine-{}skins-{}t", threads, threads),
        timed(c12.size() * size_t(threads), min_s, [&] {
          std::vector<size_t> packets(static_cast<size_t>(threads));
          std::vector<std::thread> pool;
          for (int i = 1; i < threads; ++i)
            pool.emplace_back([&, i] {
              packets[size_t(i)] = eng.run(c12.data(), c12.size(), {1}).packets.size();
            });
          packets[0] = eng.run(c12.data(), c12.size(), {1}).packets.size();
          for (auto& t : pool) t.join();
          double sum = 0;
          for (size_t p : packets) sum += double(p);
          return sum;
        }, true), "wall");
  }
  const double ref = res.rows.front().samples_per_s;
  for (auto& r : res.rows) r.vs_fftw = r.samples_per_s / ref;
  return res;
}

std::string format_throughput(const ThroughputResult& r) {
  std::string s = fmt::format(
      "scene {}: {} carriers, N = {}, fs = {:.0f} Hz, {} samples; engine chain as built at {} MHz "
      "(step {})\n", r.scene, r.carriers, r.window, r.fs, r.samples, r.clk_hz / 1000000, r.chain_step);
  s += fmt::format("{:<22} {:>13} {:>10} {:>9} {:>10} {:>6} {:>16}\n", "decoder", "samples/s",
                   "ns/sample", "vs FFTW", "x realtime", "clock", "checksum");
  for (const auto& row : r.rows)
    s += fmt::format("{:<22} {:>13.4g} {:>10.1f} {:>9.3f} {:>10.2f} {:>6} {:>16.8g}\n", row.name,
                     row.samples_per_s, 1e9 / row.samples_per_s, row.vs_fftw,
                     row.samples_per_s / r.fs, row.clock, row.checksum);
  return s;
}

}  // namespace eskin::bench
