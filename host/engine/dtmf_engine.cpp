#include "host/engine/dtmf_engine.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <variant>

#include "hls/carrier_demix.h"
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

// The chain's demixer (hls::CarrierDemix, DEMIX_W 24) at run-time K <= 64;
// N and ACC_W only bound its static checks, the arithmetic does not use them.
constexpr int kDemixKMax = 64, kDemixW = 24;
using Demix = hls::CarrierDemix<kDemixKMax, 4, 32, kDemixW>;
// The chain's ghost filter at run-time sizes. Its results depend on the
// configured rows, columns and lookback only, not on the template's
// maxima; but its arrays are the maxima's size and it clears them (the
// history on configure, an R_MAX x C_MAX pairing table every frame), so the
// engine takes the smallest instance that holds the skin.
using GhostSmall = hls::GhostFilter<16, 16, 64>;
using GhostMid = hls::GhostFilter<64, 64, 256>;
using GhostLarge = hls::GhostFilter<127, 127, DtmfEngine::kMaxLookback>;
using GhostAny = std::variant<std::unique_ptr<GhostSmall>, std::unique_ptr<GhostMid>,
                              std::unique_ptr<GhostLarge>>;

GhostAny make_ghost(const hls::GhostFilterConfig& g) {
  const auto fits = [&g](int r, int c, int l) {
    return g.rows <= r && g.cols <= c && g.lookback <= l;
  };
  GhostAny out;
  const auto set = [&g, &out](auto p) {
    p->configure(g);
    out = std::move(p);
  };
  if (fits(16, 16, 64)) set(std::make_unique<GhostSmall>());
  else if (fits(64, 64, 256)) set(std::make_unique<GhostMid>());
  else set(std::make_unique<GhostLarge>());
  return out;
}

struct SpikeEvent {
  uint32_t frame;  // within the chunk
  uint16_t neuron;
};

}  // namespace

// Per-chunk buffers: per frame K magnitudes, K line roots, T taxel values,
// T layer-0 spike flags; spike events per layer and neuron slice.
struct DtmfEngine::Chunk {
  std::vector<uint16_t> mags, roots, g;
  std::unique_ptr<bool[]> s0;
  std::vector<std::vector<SpikeEvent>> spikes[2];
};

// What carries from one chunk to the next.
struct DtmfEngine::State {
  GhostAny ghost;  // when the chain filters ghosts
  std::vector<int32_t> v[2], u[2], x_prev[2];
  bool win_open = false;  // the spike window (hls/spike_encoder.h)
  uint32_t win_t = 0;
  std::vector<uint8_t> win;  // its events, 5 bytes each
};

DtmfEngine::DtmfEngine(EngineConfig cfg) : cfg_(std::move(cfg)) {
  const EngineConfig& c = cfg_;
  // The top's limit (common/eskin/dtmf_top_plan.h): 128 DFT channels.
  require(c.rows >= 1 && c.cols >= 1 && c.rows <= 127 && c.cols <= 127 &&
              c.carriers() + (c.demix ? 1 : 0) <= 128,
          "rows/cols", "1..128 DFT channels (carriers, + DC when demixing)");
  require(c.taxels() <= 65536, "rows/cols", "rows * cols <= 65536 neurons");
  require(int(c.inc.size()) == c.carriers() + (c.demix ? 1 : 0), "inc",
          "one phase increment per carrier (+ the DC channel when demixing)");
  require(c.sdft.xw == 12, "sdft.xw", "12 (code - 2048)");
  require(c.mag_shift >= 0 && c.mag_shift <= 24, "mag_shift", "0..24");
  check_widths(c.sdft, MagnitudeWidths{c.sdft.acc_w, 16, c.mag_shift});
  mw_ = MagnitudeWidths{c.demix ? kDemixW : c.sdft.acc_w, 16, c.mag_shift};
  if (c.demix) {
    const int k = c.carriers(), dim = 2 * k + 1;
    const auto& d = c.demix_tables;
    require(k <= kDemixKMax, "demix", "at most 64 carriers");
    require(d.carriers == k && int(d.inc.size()) == k && int(d.phase0.size()) == k &&
                int(d.qsin.size()) == Demix::Config::QN && int(d.coef.size()) == dim * dim,
            "demix_tables", "K increments and phases, the quarter sine, a (2K+1)^2 matrix");
  }
  require(c.taxel.rows == c.rows && c.taxel.cols == c.cols, "taxel.rows/cols",
          "the skin's rows and cols");
  require(c.taxel.recip >= 1 && c.taxel.recip <= 32767 && c.taxel.recip_shift <= 31, "taxel",
          "recip 1..32767, recip_shift 0..31");
  require(!c.ghost || (c.ghost_cfg.rows == c.rows && c.ghost_cfg.cols == c.cols &&
                       c.ghost_cfg.lookback >= 1 && c.ghost_cfg.lookback <= kMaxLookback),
          "ghost_cfg", "the skin's rows and cols, lookback 1..4096");
  require(c.synapse.rows == c.rows && c.synapse.cols == c.cols, "synapse.rows/cols",
          "the skin's rows and cols");
  require(c.step >= 1, "step", ">= 1");
  require(c.decim_amp >= 1 && c.decim_tax >= 1, "decim_amp/decim_tax", ">= 1");
  require(c.max_spikes >= 1 && c.max_spikes <= 65536 / hls::kSpikeEventBytes, "max_spikes",
          "1..13107");
}

// Frames [f0, f1) (chunk_f0 <= f0): DFT sums with warm-up, demixing,
// magnitudes, line roots and, without a ghost filter, taxel values.
void DtmfEngine::stage_frames(const uint16_t* codes, uint64_t f0, uint64_t f1, Chunk& c,
                              uint64_t chunk_f0) const {
  const int k = cfg_.carriers(), ks = int(cfg_.inc.size()), r = cfg_.rows, cols = cfg_.cols;
  const uint64_t step = uint64_t(cfg_.step), n = uint64_t(cfg_.sdft.n);
  ExactSdft bank(cfg_.sdft, cfg_.inc);
  // Frame f's window is samples f step .. f step + N - 1.
  bank.start_at(f0 * step);
  std::unique_ptr<Demix> demix;
  if (cfg_.demix) {
    auto d = std::make_unique<Demix::Config>();
    const auto& t = cfg_.demix_tables;
    d->carriers = k;
    for (int i = 0; i < k; ++i) {
      d->inc[i] = t.inc[size_t(i)];
      d->phase0[i] = uint32_t(t.phase0[size_t(i)] + uint32_t(f0) * t.inc[size_t(i)]);
    }
    std::copy(t.qsin.begin(), t.qsin.end(), d->qsin);
    std::copy(t.coef.begin(), t.coef.end(), d->coef);
    demix = std::make_unique<Demix>();
    demix->configure(*d);
  }
  std::vector<int32_t> x(4096), sums, re(static_cast<size_t>(k)), im(static_cast<size_t>(k));
  Demix::Token out[kDemixKMax];  // the demixer's output (cleared once, not every frame)
  const FrameClock clock{f0 * step + n - 1, cfg_.step};  // frame f0 first: its window is full
  const uint64_t end = (f1 - 1) * step + n;  // after frame f1 - 1's newest sample
  size_t frame = size_t(f0 - chunk_f0);
  for (uint64_t a = f0 * step; a < end;) {
    const size_t len = size_t(std::min<uint64_t>(x.size(), end - a));
    for (size_t i = 0; i < len; ++i) x[i] = int32_t(codes[a + i] & 0xFFFu) - 2048;
    // Without demixing the magnitudes come out of the sample loop itself.
    uint16_t* mags0 = c.mags.data() + frame * size_t(k);
    if (demix) sums.resize(2 * size_t(ks) * (len / step + 2));
    const size_t got = demix ? bank.push_block(x.data(), len, clock, sums.data())
                             : bank.push_block(x.data(), len, clock, mw_, mags0);
    a += len;
    if (frame + got > size_t(f1 - chunk_f0)) throw std::logic_error("stage_frames: frame count");
    for (size_t j = 0; j < got; ++j, ++frame) {
      uint16_t* mag = c.mags.data() + frame * size_t(k);
      uint16_t* root = c.roots.data() + frame * size_t(k);
      if (demix) {
        const int32_t* s = sums.data() + j * 2 * size_t(ks);
        for (int i = 0; i <= k; ++i) demix->push({uint8_t(i), s[i], s[ks + i], i == k}, out);
        for (int i = 0; i < k; ++i) re[size_t(i)] = out[i].re, im[size_t(i)] = out[i].im;
        magnitudes(re.data(), im.data(), k, mw_, mag);
      }
      for (int i = 0; i < k; ++i) root[i] = hls::taxel_line_root(mag[i]);
      if (cfg_.ghost || c.g.empty()) continue;
      uint16_t* g = c.g.data() + frame * size_t(cfg_.taxels());
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < cols; ++j) g[i * cols + j] = hls::taxel_value(root[i], root[r + j], cfg_.taxel);
    }
  }
}

// The ghost filter over the chunk's frames in order: taxel = value at an
// active site, else 0 (hls/dtmf_chain.h).
void DtmfEngine::stage_ghost(State& st, Chunk& c, size_t frames) const {
  const int k = cfg_.carriers(), r = cfg_.rows, cols = cfg_.cols, t = cfg_.taxels();
  std::visit([&](auto& ghost) {
    for (size_t f = 0; f < frames; ++f) {
      const uint16_t* root = c.roots.data() + f * size_t(k);
      const auto value = [&](int i, int j) {
        return hls::taxel_value(root[i], root[r + j], cfg_.taxel);
      };
      ghost->frame(c.mags.data() + f * size_t(k));
      ghost->release(value);
      if (c.g.empty()) continue;
      uint16_t* g = c.g.data() + f * size_t(t);
      for (int i = 0; i < r; ++i)
        for (int j = 0; j < cols; ++j) g[i * cols + j] = ghost->site(i, j) ? value(i, j) : 0;
    }
  }, st.ghost);
}

// Both neuron layers, each split by neuron over the threads.
void DtmfEngine::stage_neurons(State& st, Chunk& c, size_t frames, int threads,
                               uint64_t work) const {
  const int t = cfg_.taxels(), cols = cfg_.cols;
  // A slice per thread, each at least `work` updates (RunOptions).
  const int sl = int(std::max<uint64_t>(
      1, std::min<uint64_t>(uint64_t(std::min(threads, t)), frames * uint64_t(t) / work)));
  hls::SynapseWeights<127, 127> syn;
  syn.configure(cfg_.synapse);
  for (int layer = 0; layer < 2; ++layer) {
    auto& events = c.spikes[layer];
    events.assign(size_t(sl), {});
    const hls::IzhikevichConfig& nc = cfg_.neuron[layer];
    parallel(sl, [&](int s) {
      const int j0 = int(int64_t(t) * s / sl), j1 = int(int64_t(t) * (s + 1) / sl);
      int32_t* v = st.v[layer].data();
      int32_t* u = st.u[layer].data();
      int32_t* xp = st.x_prev[layer].data();
      auto& out = events[size_t(s)];
      for (size_t f = 0; f < frames; ++f) {
        const uint16_t* g = c.g.data() + f * size_t(t);
        bool* s0 = c.s0.get() + f * size_t(t);
        for (int j = j0; j < j1; ++j) {
          int32_t x = layer == 0 ? int32_t(g[j]) : syn.input(s0, j / cols, j % cols);
          if (nc.input_change) {  // IzhikevichLayer::update's rectified change
            const int64_t d = int64_t(x) - xp[j];
            xp[j] = x;
            x = d > 0 ? int32_t(std::min<int64_t>(d, INT32_MAX)) : 0;
          }
          const bool spike = hls::izhikevich_update(nc, v[j], u[j], x);
          if (layer == 0) s0[j] = spike;
          if (spike) out.push_back({uint32_t(f), uint16_t(j)});
        }
      }
    });
  }
}

// Packets of the chunk's frames in the chain's order.
void DtmfEngine::stage_packets(State& st, const Chunk& c, uint64_t chunk_f0, size_t frames,
                               PacketStream& ps) const {
  const EngineConfig& cf = cfg_;
  const int k = cf.carriers(), t = cf.taxels();
  const bool record = cf.neurons && (cf.mask & hls::kMaskSpikes);
  const auto begin = [&ps](uint8_t type, uint32_t at) {
    ps.packets.push_back({type, at, uint32_t(ps.bytes.size()), 0});
  };
  const auto put8 = [&ps](uint8_t x) {
    ps.bytes.push_back(x);
    ++ps.packets.back().len;
  };
  const auto put16 = [&](uint16_t x) { put8(uint8_t(x & 0xFFu)), put8(uint8_t(x >> 8)); };
  std::vector<size_t> cursor[2];
  for (int l = 0; l < 2; ++l) cursor[l].assign(c.spikes[l].size(), 0);
  const uint16_t lo = cf.sparse_min > 1 ? cf.sparse_min : 1;
  for (size_t f = 0; f < frames; ++f) {
    const uint64_t fg = chunk_f0 + f;
    const uint32_t ts = uint32_t(uint64_t(cf.sdft.n - 1) + fg * uint64_t(cf.step));
    if (record) {  // spike_encoder: this frame's events
      if (!st.win_open) st.win_open = true, st.win_t = ts, st.win.clear();
      const uint16_t dt = uint16_t(ts - st.win_t);
      for (int l = 0; l < 2; ++l)
        for (size_t s = 0; s < c.spikes[l].size(); ++s) {
          const auto& ev = c.spikes[l][s];
          for (size_t& p = cursor[l][s]; p < ev.size() && ev[p].frame == f; ++p) {
            if (int(st.win.size()) >= cf.max_spikes * hls::kSpikeEventBytes) {
              if (ps.spikes_dropped < hls::SpikeEncoder<1>::kDroppedMax) ++ps.spikes_dropped;
              continue;
            }
            const uint16_t nr = ev[p].neuron;
            st.win.insert(st.win.end(), {uint8_t(dt & 0xFFu), uint8_t(dt >> 8), uint8_t(l),
                                         uint8_t(nr & 0xFFu), uint8_t(nr >> 8)});
          }
        }
    }
    const bool tax_sel = fg % cf.decim_tax == 0;
    if (fg % cf.decim_amp == 0 && (cf.mask & hls::kMaskAmplitudes)) {
      begin(hls::kDtmfAmplitudes, ts);
      for (int i = 0; i < k; ++i) put16(c.mags[f * size_t(k) + size_t(i)]);
    }
    const uint16_t* g = c.g.data() + f * size_t(t);
    if (tax_sel && (cf.mask & hls::kMaskTaxels)) {
      begin(hls::kDtmfTaxelsDense, ts);
      put8(uint8_t(cf.rows)), put8(uint8_t(cf.cols));
      for (int i = 0; i < t; ++i) put16(g[i]);
    }
    if (tax_sel && (cf.mask & hls::kMaskSparse)) {
      begin(hls::kDtmfTaxelsSparse, ts);
      for (int i = 0; i < t; ++i)
        if (g[i] >= lo) put8(uint8_t(i / cf.cols)), put8(uint8_t(i % cf.cols)), put16(g[i]);
    }
    if (record && fg % cf.decim_tax == uint64_t(cf.decim_tax) - 1) {  // the window closes
      if (!st.win.empty()) {
        begin(hls::kDtmfSpikes, st.win_t);
        for (uint8_t b : st.win) put8(b);
      }
      st.win_open = false;
    }
  }
}

PacketStream DtmfEngine::run(const uint16_t* codes, size_t n, const RunOptions& opt) const {
  const EngineConfig& cf = cfg_;
  const int k = cf.carriers(), t = cf.taxels(), threads = std::max(1, opt.threads);
  const uint64_t step = uint64_t(cf.step), win = uint64_t(cf.sdft.n);
  const uint64_t total = n >= win ? (uint64_t(n) - win) / step + 1 : 0;
  const bool want_g = (cf.mask & (hls::kMaskTaxels | hls::kMaskSparse)) || cf.neurons;
  const size_t per_frame = 4 * size_t(k) + (want_g ? 3 * size_t(t) : 0);
  const size_t chunk = opt.chunk_frames > 0 ? opt.chunk_frames
                                            : std::max<size_t>(64, (size_t(64) << 20) / per_frame);
  PacketStream ps;
  ps.frames = total;
  State st;
  if (cf.ghost) st.ghost = make_ghost(cf.ghost_cfg);
  for (int l = 0; l < 2; ++l) {
    st.v[l].assign(size_t(t), cf.neuron[l].v_init);
    st.u[l].assign(size_t(t), cf.neuron[l].u_init);
    st.x_prev[l].assign(size_t(t), 0);
  }
  Chunk c;
  for (uint64_t f0 = 0; f0 < total; f0 += chunk) {
    const size_t frames = size_t(std::min<uint64_t>(total - f0, chunk));
    c.mags.assign(frames * size_t(k), 0);
    c.roots.assign(frames * size_t(k), 0);
    c.g.assign(want_g ? frames * size_t(t) : 0, 0);
    // Runs of whole frames in parallel (each warms its own window up).
    const int seg = int(std::min<uint64_t>(uint64_t(threads), frames));
    parallel(seg, [&](int i) {
      const uint64_t a = f0 + frames * uint64_t(i) / uint64_t(seg);
      const uint64_t b = f0 + frames * uint64_t(i + 1) / uint64_t(seg);
      if (a < b) stage_frames(codes, a, b, c, f0);
    });
    if (cf.ghost) stage_ghost(st, c, frames);
    if (cf.neurons) {
      c.s0.reset(new bool[frames * size_t(t)]);
      stage_neurons(st, c, frames, threads, opt.neuron_work > 0 ? opt.neuron_work : 4096);
    } else {
      c.spikes[0].clear(), c.spikes[1].clear();
    }
    stage_packets(st, c, f0, frames, ps);
  }
  return ps;
}

}  // namespace eskin::engine
