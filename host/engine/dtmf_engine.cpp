#include "host/engine/dtmf_engine.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

#include "hls/dtmf_chain.h"

namespace eskin::engine {
namespace {

void require(bool ok, const std::string& field, const std::string& expected) {
  if (!ok) throw std::invalid_argument("engine." + field + ": expected " + expected);
}

// Runs f(i) for i in 0..n-1 on up to n threads (the caller's thread takes i = 0).
template <class F>
void parallel(int n, F&& f) {
  if (n <= 0) return;
  std::vector<std::thread> pool;
  for (int i = 1; i < n; ++i) pool.emplace_back([&f, i] { f(i); });
  f(0);
  for (auto& t : pool) t.join();
}

struct SpikeEvent {
  uint32_t step;    // step within the chunk
  uint32_t neuron;
};

// Conductance and product taxels of one row against every column, in double
// where that is exact: m_i m_j < 2^32, r * recip < 2^32, so every value is an
// integer below 2^53 and floor(sqrt) of an integer below 2^52 is exact (see
// magnitude_fast_ok). round_sat(x, s, bits) = min((x + 2^(s-1)) >> s, 2^bits - 1).
__attribute__((target_clones("avx512f", "avx2", "default")))
void taxel_row_fast(double mi, const uint16_t* mj, int cols, bool conductance, int shift,
                    double recip, int recip_shift, double tax_max, uint16_t* out) {
  const double half = shift > 0 ? std::ldexp(1.0, shift - 1) : 0.0, sc = std::ldexp(1.0, -shift);
  const double rhalf = recip_shift > 0 ? std::ldexp(1.0, recip_shift - 1) : 0.0;
  const double rsc = std::ldexp(1.0, -recip_shift);
  for (int j = 0; j < cols; ++j) {
    const double p = mi * double(mj[j]);
    double v;
    if (conductance) {
      const double r = std::floor(std::sqrt(p));
      const double g = std::min(std::floor((r * recip + rhalf) * rsc), 65535.0);
      v = std::min(g, tax_max);
    } else {
      v = std::min(std::floor((p + half) * sc), tax_max);
    }
    out[j] = uint16_t(int32_t(v));
  }
}

}  // namespace

// Per-chunk buffers: K magnitudes and T taxels per step, spikes per slice.
struct DtmfEngine::Chunk {
  std::vector<uint16_t> mags, tax;
  std::vector<std::vector<SpikeEvent>> spikes;
};

DtmfEngine::DtmfEngine(EngineConfig cfg) : cfg_(std::move(cfg)) {
  const EngineConfig& c = cfg_;
  require(c.rows >= 1 && c.cols >= 1 && c.rows + c.cols <= 255, "rows/cols",
          "rows, cols >= 1 and rows + cols <= 255 (8-bit carrier index)");
  require(c.taxels() <= 65536, "rows/cols", "rows * cols <= 65536 neurons");
  require(int(c.inc.size()) == c.carriers(), "inc", "one phase increment per carrier");
  require(c.mag_w >= 1 && c.mag_w <= 16 && c.tax_w >= 1 && c.tax_w <= 16, "mag_w/tax_w",
          "1..16 (packets carry u16)");
  mw_ = MagnitudeWidths{c.sdft.acc_w, c.mag_w, c.mag_shift};
  check_widths(c.sdft, mw_);
  require(c.step >= 1, "step", ">= 1");
  require(c.decim_amp >= 1 && c.decim_tax >= 1, "decim_amp/decim_tax", ">= 1");
  require(c.max_spikes >= 1, "max_spikes", ">= 1");
  require(c.taxel.rows == c.rows && c.taxel.cols == c.cols, "taxel.rows/cols",
          "the skin's rows and cols");
  hls::TaxelReconstructConfig one = c.taxel;
  one.rows = one.cols = 1;
  const char* bad = nullptr;
  if (!tax_kernel_.configure(one, &bad)) require(false, "taxel", bad ? bad : "a valid table");
  require(c.taxel.mode != hls::TaxelMode::Pressure || (c.mag_w == 16 && c.tax_w == 16),
          "taxel.mode", "Pressure mode with MAG_W = TAX_W = 16");
}

uint32_t DtmfEngine::taxel(uint32_t mi, uint32_t mj) const {
  uint16_t v = 0;
  const uint16_t mj16 = uint16_t(mj);
  if (cfg_.taxel.mode == hls::TaxelMode::Pressure) return tax_kernel_.taxel(mi, mj);
  taxel_row_fast(double(mi), &mj16, 1, cfg_.taxel.mode == hls::TaxelMode::Conductance,
                 cfg_.taxel.shift, double(cfg_.taxel.recip), cfg_.taxel.recip_shift,
                 std::ldexp(1.0, cfg_.tax_w) - 1, &v);
  return v;
}

void DtmfEngine::taxel_row(const uint16_t* mags, uint16_t* out) const {
  const int r = cfg_.rows, c = cfg_.cols;
  if (cfg_.taxel.mode == hls::TaxelMode::Pressure) {
    for (int i = 0; i < r; ++i)
      for (int j = 0; j < c; ++j) out[i * c + j] = uint16_t(tax_kernel_.taxel(mags[i], mags[r + j]));
    return;
  }
  const bool cond = cfg_.taxel.mode == hls::TaxelMode::Conductance;
  const double tax_max = std::ldexp(1.0, cfg_.tax_w) - 1;
  for (int i = 0; i < r; ++i)
    taxel_row_fast(double(mags[i]), mags + r, c, cond, cfg_.taxel.shift, double(cfg_.taxel.recip),
                   cfg_.taxel.recip_shift, tax_max, out + size_t(i) * size_t(c));
}

// Samples [s0, s1) of the recording (s0, s1 multiples of step, s0 >= chunk_s0):
// DFT with warm-up, magnitudes and (when wanted) taxels of every step in it.
void DtmfEngine::stage_dft(const uint16_t* codes, size_t n_total, uint64_t s0, uint64_t s1,
                           Chunk& c, uint64_t chunk_s0) const {
  const int k = cfg_.carriers(), t = cfg_.taxels();
  ExactSdft bank(cfg_.sdft, cfg_.inc);
  const uint64_t warm = s0 >= uint64_t(cfg_.sdft.n) ? s0 - uint64_t(cfg_.sdft.n) : 0;
  bank.start_at(warm);
  std::vector<int32_t> x(4096);
  const auto convert = [&](uint64_t a, size_t len) {
    for (size_t i = 0; i < len; ++i) x[i] = int32_t(codes[a + i] & 0xFFFu) - 2048;
  };
  for (uint64_t a = warm; a < s0;) {
    const size_t len = size_t(std::min<uint64_t>(x.size(), s0 - a));
    convert(a, len);
    bank.push_block(x.data(), len);
    a += len;
  }
  const uint64_t end = std::min<uint64_t>(s1, n_total);
  size_t set = size_t((s0 - chunk_s0) / uint64_t(cfg_.step));
  for (uint64_t a = s0; a < end;) {
    const size_t len = size_t(std::min<uint64_t>(x.size(), end - a));
    convert(a, len);
    set += bank.push_block(x.data(), len, cfg_.step, mw_, c.mags.data() + set * size_t(k));
    a += len;
  }
  if (c.tax.empty()) return;
  const size_t first = size_t((s0 - chunk_s0) / uint64_t(cfg_.step));
  for (size_t s = first; s < set; ++s)
    taxel_row(c.mags.data() + s * size_t(k), c.tax.data() + s * size_t(t));
}

PacketStream DtmfEngine::run(const uint16_t* codes, size_t n, const RunOptions& opt) const {
  const EngineConfig& cf = cfg_;
  const int k = cf.carriers(), t = cf.taxels(), threads = std::max(1, opt.threads);
  const uint64_t step = uint64_t(cf.step);
  const bool want_spikes = cf.mask & hls::kMaskSpikes;
  const bool want_tax = want_spikes || (cf.mask & hls::kMaskTaxels);
  const size_t chunk_steps = std::max<size_t>(1, opt.chunk_steps);
  const uint64_t total_steps = (uint64_t(n) + step - 1) / step;

  PacketStream ps;
  std::vector<int32_t> v(size_t(t), cf.neuron.v_init), u(size_t(t), cf.neuron.u_init);
  std::vector<std::pair<uint16_t, uint16_t>> win;  // open spike window: {dt, neuron}
  uint32_t win_t = 0;
  bool win_open = false;
  const auto begin = [&ps](uint8_t type, uint32_t at) {
    ps.packets.push_back({type, at, uint32_t(ps.bytes.size()), 0});
  };
  const auto put16 = [&ps](uint16_t x) {
    ps.bytes.push_back(uint8_t(x & 0xFFu));
    ps.bytes.push_back(uint8_t(x >> 8));
    ps.packets.back().len += 2;
  };

  Chunk c;
  for (uint64_t g0 = 0; g0 < total_steps; g0 += chunk_steps) {
    const uint64_t g1 = std::min<uint64_t>(total_steps, g0 + chunk_steps);
    const size_t steps = size_t(g1 - g0);
    c.mags.assign(steps * size_t(k), 0);
    c.tax.assign(want_tax ? steps * size_t(t) : 0, 0);
    // Stage 1: time segments (whole steps) in parallel.
    const int seg = int(std::min<uint64_t>(uint64_t(threads), steps));
    parallel(seg, [&](int i) {
      const uint64_t a = g0 + steps * uint64_t(i) / uint64_t(seg);
      const uint64_t b = g0 + steps * uint64_t(i + 1) / uint64_t(seg);
      stage_dft(codes, n, a * step, b * step, c, g0 * step);
    });
    // Stage 2: neuron slices in parallel, each over every step of the chunk.
    const int sl = want_spikes ? std::min(threads, t) : 0;
    c.spikes.assign(size_t(sl), {});
    parallel(sl, [&](int i) {
      const int j0 = int(int64_t(t) * i / sl), j1 = int(int64_t(t) * (i + 1) / sl);
      auto& out = c.spikes[size_t(i)];
      for (size_t s = 0; s < steps; ++s) {
        const uint16_t* x = c.tax.data() + s * size_t(t);
        for (int j = j0; j < j1; ++j)
          if (hls::izhikevich_update(cf.neuron, v[size_t(j)], u[size_t(j)], x[j]))
            out.push_back({uint32_t(s), uint32_t(j)});
      }
    });
    // Stage 3: packets in the chain's order.
    std::vector<size_t> cursor(size_t(sl), 0);
    for (size_t s = 0; s < steps; ++s) {
      const uint64_t g = g0 + s;
      const uint32_t ts = uint32_t(g * step);
      if (g % cf.decim_amp == 0 && (cf.mask & hls::kMaskAmplitudes)) {
        begin(hls::kDtmfAmplitudes, ts);
        for (int i = 0; i < k; ++i) put16(c.mags[s * size_t(k) + size_t(i)]);
      }
      if (g % cf.decim_tax == 0 && (cf.mask & hls::kMaskTaxels)) {
        begin(hls::kDtmfTaxelsDense, ts);
        ps.bytes.push_back(uint8_t(cf.rows));
        ps.bytes.push_back(uint8_t(cf.cols));
        ps.packets.back().len += 2;
        for (int i = 0; i < t; ++i) put16(c.tax[s * size_t(t) + size_t(i)]);
      }
      if (!win_open) {
        win_open = true;
        win_t = ts;
      }
      for (int i = 0; i < sl; ++i) {
        const auto& ev = c.spikes[size_t(i)];
        for (size_t& p = cursor[size_t(i)]; p < ev.size() && ev[p].step == s; ++p) {
          if (int(win.size()) < cf.max_spikes)
            win.push_back({uint16_t(ts - win_t), uint16_t(ev[p].neuron)});
          else
            ++ps.spikes_dropped;
        }
      }
      if (g % cf.decim_tax == uint64_t(cf.decim_tax) - 1) {  // the window's last step
        if (!win.empty()) {
          begin(hls::kDtmfSpikes, win_t);
          for (const auto& [dt, neuron] : win) {
            put16(dt);
            ps.bytes.push_back(0);  // layer 0: receptors
            ps.packets.back().len += 1;
            put16(neuron);
          }
        }
        win.clear();
        win_open = false;
      }
    }
  }
  return ps;
}

}  // namespace eskin::engine
