// rtl/dtmf_chain.v (the streaming datapath) against hls/dtmf_chain.h, packet
// by packet, with the test playing the control plane.
//
// Frames: ADC codes through the chain's own front end (SdftBank, and
// CarrierDemix when the plan demixes: DtmfChain::push's steps, run here to
// get the tokens the datapath takes), the frame's K tokens into the block.
// The control plane (C++ here, the frame engine in the top) configures the
// two neuron layers (hls::neuron_block words) and resets their state, then
// per frame reads the K magnitudes back from the block's RAM, builds the
// AMPLITUDES packet from them, runs hls/ghost_filter.h's frame() step on
// them, writes the sites it added into the mask, pulses sites_done, sends
// the frame's header (t; dense and sparse, spike recording and the spike
// window's end from DtmfChain's decimation counters and the output mask),
// and after the frame's last taxel applies the release the block reported
// (tax_site) to its filter.
//
// Bound: exact. The packets of each type equal the reference's, in order
// (the block's two packet sources share the output packet by packet, so
// SPIKES may come before or after a later frame's taxel packets; each
// packet whole):
//   3x3, 10x10: DtmfChain itself (the default scene neuroskin2, demixed,
//     neurons off and on; the staggered 10x10 scene, bin-centred, neurons
//     on), spike windows of 2 frames with neurons;
//   64x64: DtmfChain itself on the 64x64 scene (bin-centred, not demixed,
//     two presses and a slide; neurons off and on, spike windows of 2
//     frames, 1024 events a packet); and for what the scene does not reach (random
//     codes, frames' packet mixes other than DtmfChain's decimation, spike
//     recording off, windows of 1 frame) its frame() body step by step from
//     the same kernels (ChainFrame below, the default scene's neuron
//     constants), which every scene run checks against DtmfChain frame by
//     frame, 64x64 included.
// Random token gaps, control-plane delays, header delays and output
// back-pressure (seeded); out_data must hold while stalled. The runs must
// reach what they are for: sites added and released, sparse packets with
// entries, SPIKES packets with events of both layers.
// Timing (nothing stalls): a frame every K + R C + 24 clocks with no packet
// (taxel_reconstruct's period; the tokens wait in carrier_magnitude), with
// the neurons on too when their spikes are not recorded, and the dense /
// sparse periods stated at timing_run, at 3x3 and 64x64.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vdtmf_chain.h"
#include "Vdtmf_chain_10.h"
#include "Vdtmf_chain_64.h"
#include "clocked_dut.h"
#include "eskin/dtmf_top_plan.h"
#include "hls/dtmf_chain.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"
#include "ucode/dtmf_engine_image.h"

namespace {

namespace hls = eskin::hls;
using Bytes = std::vector<uint8_t>;

struct Token {
  uint8_t k = 0;
  int32_t re = 0, im = 0;
  bool last = false;
};

struct FrameIn {
  uint32_t t = 0;
  std::vector<Token> tok;
  bool amp = false, dense = false, sparse = false;  // this frame's packets
  uint16_t sparse_min = 0;
  bool spikes = false, close = false;  // record this frame's spikes; the window ends
};

// A packet as the output FIFO holds it.
template <class P>
Bytes fifo(const P& p) {
  Bytes b;
  b.push_back(p.type);
  for (int i = 0; i < 4; ++i) b.push_back(uint8_t(p.t >> (8 * i)));
  b.push_back(uint8_t(p.len & 0xFFu));
  b.push_back(uint8_t(p.len >> 8));
  b.insert(b.end(), p.payload, p.payload + p.len);
  return b;
}

// DtmfChain::frame's body, from the same kernels: the reference of frames
// whose packets DtmfChain's decimation would not ask for.
template <int R, int C, int MAX>
struct ChainFrame {
  static constexpr int K = R + C, T = R * C;
  using Tax = hls::TaxelPacketizer<R, C>;
  struct Packet {
    uint8_t type = 0;
    uint32_t t = 0;
    uint16_t len = 0;
    uint8_t payload[4 * T + 2 * K + 5 * MAX + 2] = {};
  };
  hls::TaxelReconstruct<R, C> taxel;
  std::unique_ptr<hls::GhostFilter<R, C, 4>> ghost = std::make_unique<hls::GhostFilter<R, C, 4>>();
  bool ghost_on = true;
  bool neurons = false;
  std::unique_ptr<hls::IzhikevichLayer<T>> l0, l1;
  hls::SynapseWeights<R, C> synapse;
  std::unique_ptr<hls::SpikeEncoder<MAX>> enc = std::make_unique<hls::SpikeEncoder<MAX>>();
  std::vector<uint16_t> g = std::vector<uint16_t>(T);
  std::unique_ptr<bool[]> s0 = std::make_unique<bool[]>(T), s1 = std::make_unique<bool[]>(T);

  void set_neurons(const hls::IzhikevichConfig& c0, const hls::IzhikevichConfig& c1,
                   const hls::SynapseWeightsConfig& w) {
    neurons = true;
    l0 = std::make_unique<hls::IzhikevichLayer<T>>(c0);
    l1 = std::make_unique<hls::IzhikevichLayer<T>>(c1);
    EXPECT_TRUE(synapse.configure(w));
  }

  template <int SHIFT>
  std::vector<Bytes> frame(const FrameIn& f) {
    uint16_t mag[K];
    for (int k = 0; k < K; ++k)
      mag[k] = uint16_t(hls::CarrierMagnitude<24, 16, SHIFT>::magnitude(f.tok[size_t(k)].re,
                                                                        f.tok[size_t(k)].im));
    taxel.lines(mag);
    if (ghost_on) {
      ghost->frame(mag);
      ghost->release([this](int i, int j) { return taxel.value(i, j); });
    }
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j)
        g[size_t(i * C + j)] = (!ghost_on || ghost->site(i, j)) ? taxel.value(i, j) : 0;
    const bool record = neurons && f.spikes;
    if (record) enc->frame(f.t);
    if (neurons) {
      for (int i = 0; i < T; ++i) s0[i] = l0->update(i, g[size_t(i)]);
      for (int i = 0; i < T; ++i) s1[i] = l1->update(i, synapse.input(s0.get(), i / C, i % C));
      if (record) {
        for (int i = 0; i < T; ++i)
          if (s0[i]) enc->spike(0, uint16_t(i));
        for (int i = 0; i < T; ++i)
          if (s1[i]) enc->spike(1, uint16_t(i));
      }
    }
    std::vector<Bytes> out;
    auto p = std::make_unique<Packet[]>(2);
    if (f.amp) {
      p[0].type = hls::kDtmfAmplitudes, p[0].t = f.t, p[0].len = 0;
      for (int k = 0; k < K; ++k)
        p[0].payload[p[0].len++] = uint8_t(mag[k]), p[0].payload[p[0].len++] = uint8_t(mag[k] >> 8);
      out.push_back(fifo(p[0]));
    }
    const int n = Tax::frame(g.data(), f.t, f.dense, f.sparse, f.sparse_min, p.get());
    for (int i = 0; i < n; ++i) out.push_back(fifo(p[i]));
    if (f.close && record && enc->close_packet(p[0])) out.push_back(fifo(p[0]));
    return out;
  }
};

template <class V, int R, int C>
struct Bench : ClockedDut<V> {
  static constexpr int K = R + C, T = R * C;
  using ClockedDut<V>::m;
  using ClockedDut<V>::cycle;
  using ClockedDut<V>::tick;

  std::mt19937 rng;
  double p_in = 1.0, p_hdr = 1.0, p_out = 1.0, p_cp = 1.0;  // chance a clock
  bool ghost = true;
  hls::GhostFilterConfig ghost_cfg;
  std::unique_ptr<hls::GhostFilter<R, C, 4>> gf = std::make_unique<hls::GhostFilter<R, C, 4>>();
  std::vector<FrameIn> frames;

  // Observed.
  Bytes out;                      // the block's bytes
  std::vector<Bytes> amplitudes;  // the control plane's AMPLITUDES packets
  std::vector<uint64_t> first_token_edge;  // per frame
  std::vector<uint64_t> last_taxel_edge;   // per frame
  std::vector<uint64_t> hdr_edge;          // per frame
  std::vector<uint64_t> out_edge;          // per byte
  bool static_sites = false;  // sites_done held high (a static mask), no pairing
  bool neurons = false;
  hls::IzhikevichConfig neuron[2];
  hls::SynapseWeightsConfig synapse;
  uint64_t sites_written = 0, sites_released = 0;
  bool assertion_fail = false;

  explicit Bench(uint32_t seed) : rng(seed) {
    m.hdr_valid = 0;
    m.mask_we = 0;
    m.sites_done = 0;
    m.mag_raddr = 0;
    m.nu_cfg_we = 0;
    m.nu_init = 0;
    m.out_free = 0xFFFF;
    this->reset();
  }
  bool coin(double p) { return p >= 1.0 || std::uniform_real_distribution<double>(0, 1)(rng) < p; }

  void run(size_t expect_bytes, const hls::TaxelReconstructConfig& tc) {
    m.cfg_recip = tc.recip;
    m.cfg_recip_shift = tc.recip_shift;
    m.cfg_ghost = ghost;
    m.cfg_release = ghost_cfg.release;
    m.cfg_neurons = neurons;
    for (int w = 0; w < 5; ++w) m.cfg_w[w] = 0;
    for (int k = 0; k < 9; ++k)
      m.cfg_w[k / 2] |= uint32_t(uint16_t(synapse.w[k])) << (16 * (k % 2));
    if (neurons) {
      for (int l = 0; l < 2; ++l) {
        const auto w = hls::neuron_block(neuron[l]);
        for (int a = 0; a <= 16; ++a) {
          m.nu_cfg_we = uint8_t(1 << l), m.nu_cfg_addr = uint8_t(a), m.nu_cfg_data = uint32_t(w[size_t(a)]);
          tick();
        }
      }
      m.nu_cfg_we = 0;
      m.nu_init = 1;
      tick();
      m.nu_init = 0;
      for (int k = 0; k < T + 2 && m.nu_busy; ++k) tick();
      ASSERT_FALSE(m.nu_busy) << "init";
    }
    size_t fi = 0, ti = 0;     // token source: frame, token
    size_t hi = 0;             // next header
    size_t cp_frame = 0;       // the frame the control plane serves
    size_t tax_frame = 0;      // the frame whose taxels come out
    size_t sites_given = 0;    // sites_done pulses so far
    enum { WAIT, READ, WRITE, DONE, WAIT_TAX } cp = WAIT;
    int rd = 0;
    std::vector<uint16_t> mags(static_cast<size_t>(K));
    std::vector<int> adds;
    size_t add_i = 0;
    std::vector<uint8_t> seen_site(static_cast<size_t>(T));
    int tax_n = 0;
    bool held = false;
    uint8_t held_data = 0;
    first_token_edge.assign(frames.size(), 0);
    const uint64_t deadline = cycle + 60 * (frames.size() * (T + K) + expect_bytes) + 10000;
    while (cycle < deadline) {
      if (fi == frames.size() && tax_frame == frames.size() && out.size() >= expect_bytes &&
          m.idle && !m.out_valid)
        break;
      // Tokens.
      m.in_valid = fi < frames.size() && coin(p_in);
      if (m.in_valid) {
        const Token& t = frames[fi].tok[ti];
        m.in_k = t.k;
        m.in_re = uint32_t(t.re) & 0xFFFFFFu;
        m.in_im = uint32_t(t.im) & 0xFFFFFFu;
        m.in_last = t.last;
      }
      // Headers, in frame order.
      m.hdr_valid = hi < frames.size() && coin(p_hdr);
      if (m.hdr_valid) {
        m.hdr_t = frames[hi].t;
        m.hdr_dense = frames[hi].dense;
        m.hdr_sparse = frames[hi].sparse;
        m.hdr_sparse_min = frames[hi].sparse_min;
        m.hdr_spikes = frames[hi].spikes;
        m.hdr_close = frames[hi].close;
      }
      // Control plane.
      m.mask_we = 0;
      m.sites_done = static_sites;
      const bool act = coin(p_cp);
      int issued_rd = -1;
      switch (cp) {
        case WAIT:
          if (m.mag_ready && act) cp = READ, rd = 0;
          break;
        case READ:
          if (rd < K && act) m.mag_raddr = uint8_t(rd), issued_rd = rd++;
          break;
        case WRITE:
          if (add_i < adds.size() && act) {
            m.mask_we = 1;
            m.mask_addr = uint32_t(adds[add_i++]);
            m.mask_din = 1;
          } else if (add_i == adds.size()) {
            cp = DONE;
          }
          break;
        case DONE:
          if (act || static_sites) m.sites_done = 1, ++sites_given, cp = WAIT_TAX;
          break;
        case WAIT_TAX:
          if (tax_frame > cp_frame) ++cp_frame, cp = WAIT;
          break;
        default:
          break;
      }
      m.out_ready = coin(p_out);
      m.clk = 0;
      m.eval();
      if (held) {
        EXPECT_TRUE(m.out_valid) << "byte withdrawn while stalled, byte " << out.size();
        EXPECT_EQ(m.out_data, held_data) << "out_data changed while stalled, byte " << out.size();
      }
      const bool in_take = m.in_valid && m.in_ready;
      const bool hdr_take = m.hdr_valid && m.hdr_ready;
      const bool out_take = m.out_valid && m.out_ready;
      if (out_take) out.push_back(m.out_data);
      held = m.out_valid && !m.out_ready;
      held_data = m.out_data;
      const bool tax = m.tax_valid;
      const bool site = m.tax_site;
      tick();
      if (in_take) {
        if (ti == 0) first_token_edge[fi] = cycle;
        if (++ti == size_t(K)) ti = 0, ++fi;
      }
      if (hdr_take) ++hi, hdr_edge.push_back(cycle);
      if (out_take) out_edge.push_back(cycle);
      // The read port is registered: this edge's address, this edge's data.
      if (issued_rd >= 0) mags[size_t(issued_rd)] = uint16_t(m.mag_rdata);
      if (cp == READ && rd == K) {
        // All K read: AMPLITUDES, then the pairing.
        const FrameIn& f = frames[cp_frame];
        if (f.amp) {
          Bytes b = {hls::kDtmfAmplitudes};
          for (int i = 0; i < 4; ++i) b.push_back(uint8_t(f.t >> (8 * i)));
          b.push_back(uint8_t((2 * K) & 0xFF));
          b.push_back(uint8_t((2 * K) >> 8));
          for (uint16_t v : mags) b.push_back(uint8_t(v)), b.push_back(uint8_t(v >> 8));
          amplitudes.push_back(b);
        }
        adds.clear();
        add_i = 0;
        if (ghost) {
          std::vector<uint8_t> before(static_cast<size_t>(T));
          for (int n = 0; n < T; ++n) before[size_t(n)] = gf->site(n / C, n % C);
          gf->frame(mags.data());
          for (int n = 0; n < T; ++n)
            if (gf->site(n / C, n % C) && !before[size_t(n)]) adds.push_back(n);
          sites_written += adds.size();
        }
        cp = WRITE;
      }
      if (tax) {
        if (!static_sites && sites_given <= tax_frame)
          ADD_FAILURE() << "a taxel before sites_done, frame " << tax_frame;
        seen_site[size_t(tax_n)] = site;
        if (++tax_n == T) {
          if (ghost) {
            for (int n = 0; n < T; ++n)
              sites_released += gf->site(n / C, n % C) && !seen_site[size_t(n)];
            gf->release([&](int i, int j) { return seen_site[size_t(i * C + j)] ? 0xFFFF : 0; });
          }
          last_taxel_edge.push_back(cycle);
          ++tax_frame;
          tax_n = 0;
        }
      }
    }
    ASSERT_LT(cycle, deadline) << "the block did not finish: frames in " << fi << ", served "
                               << tax_frame << ", bytes " << out.size() << " of " << expect_bytes;
  }
};

// Checks the block's packets and the control plane's amplitudes against
// the expected ones, type by type in order (the block's two packet sources
// share the port packet by packet, so types may interleave across frames;
// AMPLITUDES are the engine's).
template <class B>
void check(const B& b, const std::vector<std::vector<Bytes>>& want, bool want_dense = true,
           bool want_sparse = true, bool want_spikes = false) {
  std::vector<Bytes> want_type[6], got_type[6];
  for (const auto& fr : want)
    for (const auto& p : fr) want_type[p[0] % 6].push_back(p);
  got_type[hls::kDtmfAmplitudes] = b.amplitudes;
  for (size_t at = 0; at < b.out.size();) {
    ASSERT_LE(at + 7, b.out.size()) << "a packet cut short at byte " << at;
    const size_t len = size_t(b.out[at + 5] | b.out[at + 6] << 8);
    ASSERT_LE(at + 7 + len, b.out.size()) << "a packet cut short at byte " << at;
    const uint8_t type = b.out[at];
    ASSERT_TRUE(type >= hls::kDtmfTaxelsDense && type <= hls::kDtmfSpikes) << "type " << int(type);
    got_type[type].push_back(Bytes(b.out.begin() + long(at), b.out.begin() + long(at + 7 + len)));
    at += 7 + len;
  }
  for (int t = 1; t <= 4; ++t) {
    ASSERT_EQ(got_type[t].size(), want_type[t].size()) << "packets of type " << t;
    for (size_t i = 0; i < want_type[t].size(); ++i)
      ASSERT_EQ(got_type[t][i], want_type[t][i]) << "packet " << i << " of type " << t;
  }
  // The frames reach what they are for.
  size_t sparse = 0;
  for (const auto& p : want_type[hls::kDtmfTaxelsSparse]) sparse += p.size() > 7;
  if (want_dense) {
    EXPECT_GT(want_type[hls::kDtmfTaxelsDense].size(), 0u);
  }
  if (want_sparse) {
    EXPECT_GT(sparse, 0u);
  }
  if (want_spikes) {
    EXPECT_GT(want_type[hls::kDtmfSpikes].size(), 2u);
    size_t layer_events[2] = {0, 0};
    for (const auto& p : want_type[hls::kDtmfSpikes])
      for (size_t e = 7; e + 5 <= p.size(); e += 5) ++layer_events[p[e + 2] & 1];
    EXPECT_GT(layer_events[0], 0u) << "layer 0 events";
    EXPECT_GT(layer_events[1], 0u) << "layer 1 events";
  }
}

// A scene through the plan: DtmfChain's packets, the chain's front end's
// tokens. Frames [0, max_frames).
template <class S, class V>
void scene_run(const std::string& scene_file, size_t max_frames, bool neurons, uint32_t seed,
               double p_in, double p_hdr, double p_out, double p_cp) {
  const eskin::sim::Scene sc = eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/" + scene_file);
  auto plan = hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(sc));
  // The spike capacity of the block's build (dtmf_chain_test.cmake: 256,
  // 1024 at 64x64); the plan's is the frame engine's 256.
  plan.max_spikes = S::MAX_SPIKES;
  // On the heap: at 64x64 the configuration holds a 257 x 257 demix table.
  const auto cfgp = std::make_unique<typename hls::DtmfChain<S>::Config>(hls::chain_config<S>(plan));
  auto& cfg = *cfgp;
  cfg.neurons = neurons;
  cfg.mask = hls::kMaskAmplitudes | hls::kMaskTaxels | hls::kMaskSparse |
             (neurons ? hls::kMaskSpikes : 0);
  cfg.sparse_min = uint16_t(plan.ghost.release);
  cfg.decim_amp = 2;
  cfg.decim_tax = neurons ? 2 : 1;
  auto chain = std::make_unique<hls::DtmfChain<S>>(cfg);
  ASSERT_TRUE(chain->ok());
  using Chain = hls::DtmfChain<S>;
  auto bank = std::make_unique<typename Chain::Bank>();
  ASSERT_TRUE(bank->configure(cfg.sdft));
  auto demix = std::make_unique<typename Chain::Demix>();
  if (cfg.demix) {
    ASSERT_TRUE(demix->configure(cfg.demix_cfg));
  }
  auto compp = std::make_unique<ChainFrame<S::R, S::C, S::MAX_SPIKES>>();
  auto& comp = *compp;
  ASSERT_TRUE(comp.taxel.configure(cfg.taxel));
  ASSERT_TRUE(comp.ghost->configure(cfg.ghost_cfg));
  comp.ghost_on = cfg.ghost;
  if (neurons) comp.set_neurons(cfg.neuron[0], cfg.neuron[1], cfg.synapse);

  eskin::sim::WorldModel world(sc);
  const std::vector<int> codes = world.all_codes();
  const int up = 12 - sc.skin.adc.bits;
  using Bn = Bench<V, S::R, S::C>;
  auto b = std::make_unique<Bn>(seed);
  b->p_in = p_in, b->p_hdr = p_hdr, b->p_out = p_out, b->p_cp = p_cp;
  b->ghost = cfg.ghost;
  b->ghost_cfg = cfg.ghost_cfg;
  ASSERT_TRUE(b->gf->configure(cfg.ghost_cfg));
  b->neurons = neurons;
  b->neuron[0] = cfg.neuron[0], b->neuron[1] = cfg.neuron[1];
  b->synapse = cfg.synapse;
  std::vector<std::vector<Bytes>> want;
  struct Packets {
    typename Chain::Packet p[Chain::kMaxPackets];
  };
  auto pk = std::make_unique<Packets>();
  auto& pka = pk->p;
  int filled = 0, phase = 0;
  uint32_t amp_cnt = 0, tax_cnt = 0;
  size_t expect_bytes = 0;
  for (size_t n = 0; n < codes.size() && b->frames.size() < max_frames; ++n) {
    const uint16_t code = uint16_t(codes[n] << up);
    const int np = chain->push(code, uint32_t(n), pka);
    typename Chain::Bank::Token tok[S::K + 1];
    bank->push(int32_t(code & 0xFFFu) - 2048, tok);
    bool fr = false;
    if (filled < S::N) {
      if (++filled == S::N) phase = 0, fr = true;
    } else {
      phase = phase + 1 == cfg.step ? 0 : phase + 1;
      fr = phase == 0;
    }
    ASSERT_TRUE(np == 0 || fr) << "frame timing, sample " << n;
    if (!fr) continue;
    FrameIn f;
    f.t = uint32_t(n);
    f.amp = amp_cnt == 0;
    amp_cnt = amp_cnt + 1 >= cfg.decim_amp ? 0 : amp_cnt + 1;
    // The control plane's decimation (DtmfChain's counters).
    const bool tax_sel = tax_cnt == 0, win_end = tax_cnt + 1 >= cfg.decim_tax;
    tax_cnt = win_end ? 0 : tax_cnt + 1;
    f.dense = f.sparse = tax_sel, f.sparse_min = cfg.sparse_min;
    f.spikes = neurons, f.close = win_end;
    typename Chain::Demix::Token dm[S::K];
    if (cfg.demix)
      for (int k = 0; k <= S::K; ++k)
        demix->push(typename Chain::Demix::Token{uint8_t(k), tok[k].re, tok[k].im, k == S::K}, dm);
    for (int k = 0; k < S::K; ++k)
      f.tok.push_back(Token{uint8_t(k), cfg.demix ? dm[k].re : tok[k].re,
                            cfg.demix ? dm[k].im : tok[k].im, k == S::K - 1});
    std::vector<Bytes> ps;
    for (int i = 0; i < np; ++i) ps.push_back(fifo(pka[i]));
    // The composition is DtmfChain's frame.
    ASSERT_EQ(comp.template frame<S::MAG_SHIFT>(f), ps) << "composition, frame " << b->frames.size();
    for (const auto& p : ps)
      if (p[0] != hls::kDtmfAmplitudes) expect_bytes += p.size();
    want.push_back(ps);
    b->frames.push_back(f);
  }
  b->run(expect_bytes, cfg.taxel);
  check(*b, want, true, true, neurons);
  EXPECT_GT(b->sites_written, 0u) << "released " << b->sites_released;
  EXPECT_GT(b->sites_released, 0u);
}

// The 64x64 skin (128 carriers at bins 2..129 of a 512-sample window, no
// demixing, a frame every 128 samples) with the chain's front end
// (SdftBank) on synthetic codes: touches (1..3 at a time, pressed for a few
// frames: their row and column carry a full carrier each, every other line
// a tenth of one) and, from frame `noise_from` on, uniform random codes.
// Reference: ChainFrame (DtmfChain::frame's body). The frames' packets
// vary: AMPLITUDES every other frame, dense on two frames of three, sparse
// on every other.
struct Skin64 {
  static constexpr int R = 64, C = 64, K = 128, T = 4096, N = 512, STEP = 128, SHIFT = 4;
  static constexpr int MAX_SPIKES = 1024;
  static constexpr double kFull = 30.0;  // one full carrier's amplitude, ADC LSB
  hls::TaxelReconstructConfig taxel;
  hls::GhostFilterConfig ghost;
  Skin64() {
    // One full carrier: window sum N/2 A G >> SHIFT magnitude units.
    const double F = N / 2.0 * kFull * (32767.0 / 32768.0) / 16.0;
    taxel.rows = R, taxel.cols = C;
    int rs = 0;
    while (std::ldexp(1.0, 15 + rs) / F < 16384.0) ++rs;
    taxel.recip_shift = uint8_t(rs);
    taxel.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + rs) / F));
    ghost.rows = R, ghost.cols = C, ghost.lookback = N / STEP;
    ghost.onset = uint16_t(0.05 * F), ghost.pair_tol = uint16_t(0.02 * F);
    ghost.release = uint16_t(std::ceil(0.05 * 32768));
  }
};

template <class V>
void skin64_run(int frames, int noise_from, uint32_t seed, double p_in, double p_hdr, double p_out,
                double p_cp) {
  using S = Skin64;
  const S skin;
  std::mt19937 rng(seed);
  hls::SdftBankConfig<S::K + 1> sc;
  sc.carriers = S::K;
  for (int k = 0; k < S::K; ++k) sc.inc[k] = uint32_t(2 + k) << 23;  // bin 2 + k of 512
  auto bank = std::make_unique<hls::SdftBank<S::K + 1, S::N, 12, 16, 10, 22>>();
  ASSERT_TRUE(bank->configure(sc));
  auto comp = std::make_unique<ChainFrame<S::R, S::C, S::MAX_SPIKES>>();
  ASSERT_TRUE(comp->taxel.configure(skin.taxel));
  ASSERT_TRUE(comp->ghost->configure(skin.ghost));
  // The neurons of the default scene's plan (one step a frame), the
  // synapse at 64x64.
  const auto plan = hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(
      eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml")));
  hls::SynapseWeightsConfig syn = plan.synapse;
  syn.rows = S::R, syn.cols = S::C;
  comp->set_neurons(plan.neuron[0], plan.neuron[1], syn);
  auto b = std::make_unique<Bench<V, S::R, S::C>>(seed);
  b->p_in = p_in, b->p_hdr = p_hdr, b->p_out = p_out, b->p_cp = p_cp;
  b->ghost = true;
  b->ghost_cfg = skin.ghost;
  ASSERT_TRUE(b->gf->configure(skin.ghost));
  b->neurons = true;
  b->neuron[0] = plan.neuron[0], b->neuron[1] = plan.neuron[1];
  b->synapse = syn;

  struct Touch {
    int i, j, left;
  };
  std::vector<Touch> touches;
  std::vector<double> phase(S::K);
  for (auto& p : phase) p = std::uniform_real_distribution<double>(0, 6.283)(rng);
  std::vector<std::vector<Bytes>> want;
  size_t expect_bytes = 0;
  uint32_t n = 0;
  const int samples = S::N + (frames - 1) * S::STEP;
  std::vector<double> amp(S::K);
  for (int s = 0; s < samples; ++s, ++n) {
    const int f = s < S::N ? 0 : (s - S::N) / S::STEP + 1;
    if (s == 0 || (s >= S::N && (s - S::N) % S::STEP == 0)) {
      // The touches of this frame.
      for (auto& t : touches) --t.left;
      touches.erase(std::remove_if(touches.begin(), touches.end(), [](const Touch& t) { return t.left <= 0; }),
                    touches.end());
      if (touches.size() < 3 && rng() % 3 == 0)
        touches.push_back(Touch{int(rng() % S::R), int(rng() % S::C), 4 + int(rng() % 12)});
      for (int k = 0; k < S::K; ++k) amp[size_t(k)] = 0.1 * S::kFull;
      for (const auto& t : touches) amp[size_t(t.i)] += S::kFull, amp[size_t(S::R + t.j)] += S::kFull;
    }
    int code;
    if (f >= noise_from) {
      code = int(rng() % 4096);
    } else {
      double x = 2048.0 + std::normal_distribution<double>(0, 1.0)(rng);
      for (int k = 0; k < S::K; ++k)
        x += amp[size_t(k)] * std::cos(6.283185307179586 * (2 + k) * s / S::N + phase[size_t(k)]);
      code = std::clamp(int(std::lround(x)), 0, 4095);
    }
    hls::SdftBankToken tok[S::K + 1];
    bank->push(code - 2048, tok);
    if (s + 1 < S::N || (s + 1 - S::N) % S::STEP != 0) continue;
    FrameIn fr;
    fr.t = n;
    const size_t fn = b->frames.size();
    fr.amp = fn % 2 == 0;
    fr.dense = fn % 3 != 2;
    fr.sparse = fn % 2 == 1 || fn % 5 == 0;
    fr.sparse_min = uint16_t(fn % 4 == 0 ? 0 : skin.ghost.release);
    fr.spikes = fn % 7 != 3;  // mask bit 2 off now and then
    fr.close = fn % 3 != 0;   // windows of 1 and 2 frames
    for (int k = 0; k < S::K; ++k)
      fr.tok.push_back(Token{uint8_t(k), tok[k].re, tok[k].im, k == S::K - 1});
    const auto ps = comp->template frame<S::SHIFT>(fr);
    for (const auto& p : ps)
      if (p[0] != hls::kDtmfAmplitudes) expect_bytes += p.size();
    want.push_back(ps);
    b->frames.push_back(fr);
  }
  ASSERT_EQ(int(b->frames.size()), frames);
  b->run(expect_bytes, skin.taxel);
  check(*b, want, true, true, true);
  EXPECT_GT(b->sites_written, 0u);
  EXPECT_GT(b->sites_released, 0u);
}

TEST(DtmfChain, DefaultSceneBytesExactUnderRandomStalls) {
  scene_run<hls::DtmfChainSizes<3, 3, 32>, Vdtmf_chain>("scenes/neuroskin2.yaml", 600, false, 1, 0.7,
                                                         0.5, 0.6, 0.5);
  scene_run<hls::DtmfChainSizes<3, 3, 32>, Vdtmf_chain>("scenes/neuroskin2.yaml", 600, true, 11, 0.7,
                                                         0.5, 0.6, 0.5);
}


TEST(DtmfChain, Staggered10x10SceneBytesExactUnderRandomStalls) {
  scene_run<hls::DtmfChainSizes<10, 10, 64>, Vdtmf_chain_10>("scenes/staggered10x10.yaml", 300, true,
                                                              2, 0.8, 0.6, 0.7, 0.6);
}

// The 64x64 scene (128 bin-centred carriers, N 512, a frame every 1000
// samples at 1 MS/s: two presses and a slide) against DtmfChain at 64x64
// itself, ghost filter on, neurons off (every frame's taxels) and on, every
// frame of the scene (30).
TEST(DtmfChain, Skin64x64SceneBytesExactUnderRandomStalls) {
  using S = hls::DtmfChainSizes<64, 64, 512, 4, 1024>;
  scene_run<S, Vdtmf_chain_64>("scenes/skin64x64.yaml", 30, false, 4, 0.7, 0.5, 0.6, 0.5);
  scene_run<S, Vdtmf_chain_64>("scenes/skin64x64.yaml", 30, true, 5, 0.8, 0.5, 0.7, 0.5);
}

TEST(DtmfChain, Skin64x64BytesExactUnderRandomStalls) {
  skin64_run<Vdtmf_chain_64>(40, 34, 3, 0.8, 0.5, 0.7, 0.5);
}


// Timing with nothing stalling (tokens every clock, sites_done held high,
// headers ready, out_ready high, ghost off), from the blocks' stated
// latencies (their headers): token 0 taken at edge E; carrier_magnitude's
// MAG_W + 5 = 21 clocks and taxel_reconstruct's 25 put the first taxel at
// E + K + 45; the last taxel L of a frame then
//   no packet:     T - 1 later; the next frame's last taxel K + T + 24
//                  after L (taxel_reconstruct's period);
//   dense:         2 (T - 1) later (two bytes a taxel, each taxel's bytes
//                  on the 2 edges after its handshake); the next K + 2T +
//                  23 after L (the dense packet's last byte at L + 2, the
//                  next header at L + 3, its taxel 0 at L + K + 25 >= L +
//                  13);
//   dense, sparse: the sparse packet (n entries) from L + 5 to L + 11 + 4n
//                  (the output arbiter's grant takes a clock a packet),
//                  the next header at L + 12 + 4n, its taxel 0 at
//                  max(L + K + 25, L + 23 + 4n) (taxel k 10 + 2k edges
//                  after the header, taxel_packetizer's, and the grant),
//                  so the next frame's last taxel max(K + 25, 23 + 4n) +
//                  2 (T - 1) after L;
//   neurons, no packet, spikes not recorded: as with no packet: the
//                  layers, the synapse and the event sequencer finish the
//                  frame before the next frame's taxels come (K + 25 clocks
//                  after L), so they add nothing to the period;
//   neurons, spikes recorded, a window a frame (n events in the SPIKES
//                  packet, n1 layer-1 spikes): layer 0's events go to the
//                  encoder beside the taxels; after L come the synapse's
//                  last row and the layers' pipelines, layer 1's events a
//                  clock each and the SPIKES packet, then the next header.
//                  dtmf_chain_frame_clocks charges such a frame K + 45 +
//                  T - 1 + 1 + dtmf_chain_spike_tail_clocks (C + 40 + n1 +
//                  8 + 5n), the fixed parts as if nothing overlapped: the
//                  period is at most that with n1 = T (the bound's worst,
//                  which holds whatever n1 was, dropped events included),
//                  and, where no event was dropped (n1 read from the
//                  packet), above the period by no more than those fixed
//                  parts (K + 45 + C + 40 - 1): the n1 and 5n terms are
//                  clocks the chain spends, not overlapped ones.
template <class V, int R, int C, int SHIFT, int S_MAX>
void timing_run(int mode, uint32_t seed) {
  constexpr int K = R + C, T = R * C;
  std::mt19937 rng(seed);
  hls::TaxelReconstructConfig tc;
  tc.rows = R, tc.cols = C, tc.recip = 1, tc.recip_shift = 0;  // g = sqrt(m_i m_j)
  auto comp = std::make_unique<ChainFrame<R, C, S_MAX>>();
  ASSERT_TRUE(comp->taxel.configure(tc));
  comp->ghost_on = false;
  auto b = std::make_unique<Bench<V, R, C>>(seed);
  b->ghost = false;
  b->static_sites = true;
  if (mode >= 3) {  // the layers on; 4: spikes recorded
    const auto plan = hls::make_dtmf_top_plan(eskin::sim::dtmf_top_spec(
        eskin::sim::load_scene(std::string(ESKIN_SOURCE_DIR) + "/scenes/neuroskin2.yaml")));
    b->neurons = true;
    b->neuron[0] = plan.neuron[0], b->neuron[1] = plan.neuron[1];
    b->synapse = plan.synapse;
    b->synapse.rows = R, b->synapse.cols = C;
    comp->set_neurons(b->neuron[0], b->neuron[1], b->synapse);
  }
  std::vector<std::vector<Bytes>> want;
  std::vector<int> lit, events, events1;
  size_t expect_bytes = 0;
  const int frames = mode == 4 ? 16 : 6;  // 4: enough frames for both layers to spike
  for (int f = 0; f < frames; ++f) {
    FrameIn fr;
    fr.t = uint32_t(rng());
    fr.dense = mode == 1 || mode == 2;
    fr.sparse = mode == 2;
    fr.sparse_min = uint16_t(f < 3 ? 1 : 3000);  // many lit, then fewer
    fr.spikes = fr.close = mode == 4;
    for (int k = 0; k < K; ++k) {
      // magnitudes 0 .. 5657 (shift 0); 4: 0 .. 42426, a strong drive
      const int32_t a = int32_t(rng() % (mode == 4 ? 30000 : 4000));
      fr.tok.push_back(Token{uint8_t(k), a >> SHIFT << SHIFT, int32_t(rng() % 4000) - 2000, k == K - 1});
    }
    const auto ps = comp->template frame<SHIFT>(fr);
    int n = 0, ev = 0, ev1 = 0;
    for (const auto& p : ps) {
      expect_bytes += p.size();
      if (p[0] == hls::kDtmfTaxelsSparse) n = (p[5] | p[6] << 8) / 4;
      if (p[0] == hls::kSpikesPacketType) {
        ev = (p[5] | p[6] << 8) / hls::kSpikeEventBytes;
        for (int e = 0; e < ev; ++e) ev1 += p[7 + 5 * size_t(e) + 2];  // the event's layer byte
      }
    }
    lit.push_back(n);
    events.push_back(ev);
    events1.push_back(ev1);
    want.push_back(ps);
    b->frames.push_back(fr);
  }
  b->run(expect_bytes, tc);
  check(*b, want, mode == 1 || mode == 2, mode == 2);
  ASSERT_EQ(b->last_taxel_edge.size(), size_t(frames));

  const int64_t per_taxel = mode == 1 || mode == 2 ? 2 : 1;
  if (mode == 2) {  // both bounds of the period are reached: the line roots' and the sparse packet's
    int by_sparse = 0;
    for (int f = 0; f + 1 < frames; ++f) by_sparse += 23 + 4 * lit[size_t(f)] > K + 25;
    EXPECT_GT(by_sparse, 0);
    EXPECT_LT(by_sparse, frames - 1);
  }
  EXPECT_EQ(int64_t(b->last_taxel_edge[0] - b->first_token_edge[0]), K + 45 + per_taxel * (T - 1));
  if (mode == 4) {  // the spike tail, against the formula the bound takes
    hls::DtmfTopPlan plan;
    plan.C = C, plan.T = T, plan.K = K;
    plan.spec.spikes = true;
    const int64_t fixed = K + 45 + T;  // the frame's part: first token to last taxel, + 1
    int with1 = 0, full = 0;
    for (int f = 1; f < frames; ++f) {
      const int64_t d = int64_t(b->last_taxel_edge[size_t(f)] - b->last_taxel_edge[size_t(f - 1)]);
      const int n = events[size_t(f - 1)], n1 = events1[size_t(f - 1)];
      plan.max_spikes = n;
      const int64_t most = hls::dtmf_chain_frame_clocks(plan, hls::kMaskSpikes);
      EXPECT_EQ(most, fixed + hls::dtmf_chain_spike_tail_clocks(C, T, n));
      EXPECT_LE(d, most) << "frame " << f << " events " << n;
      if (n < S_MAX) {  // none dropped: the packet holds every layer-1 spike
        const int64_t exact = fixed + hls::dtmf_chain_spike_tail_clocks(C, n1, n);
        EXPECT_LE(d, exact) << "frame " << f << " events " << n << " layer 1 " << n1;
        EXPECT_GE(d, exact - (K + 45 + C + 40 - 1)) << "frame " << f << " events " << n;
      }
      with1 += n1 > 0;
      full += n == S_MAX;
      std::printf("frame %d: %d events (%d of layer 1), period %lld, the bound's %lld\n", f, n,
                  n1, (long long)d, (long long)most);
    }
    EXPECT_GT(with1, 0);  // layer 1's events were in the tail
    if (T > S_MAX) {  // and, on the large skin, windows with drops
      EXPECT_GT(full, 0);
    }
    return;
  }
  for (int f = 1; f < frames; ++f) {
    const int64_t L = int64_t(b->last_taxel_edge[size_t(f - 1)]);
    int64_t want_d = mode == 0 || mode == 3 ? K + T + 24 : mode == 1 ? K + 2 * T + 23
                                                        : std::max<int64_t>(K + 25, 23 + 4 * lit[size_t(f - 1)]) + 2 * (T - 1);
    EXPECT_EQ(int64_t(b->last_taxel_edge[size_t(f)]) - L, want_d)
        << "frame " << f << " mode " << mode << " lit " << lit[size_t(f - 1)];
  }
}

TEST(DtmfChain, FrameClocks3x3) {
  for (int mode = 0; mode < 5; ++mode) timing_run<Vdtmf_chain, 3, 3, 0, 256>(mode, 10 + uint32_t(mode));
}

TEST(DtmfChain, FrameClocks64x64) {
  for (int mode = 0; mode < 5; ++mode) timing_run<Vdtmf_chain_64, 64, 64, 4, 1024>(mode, 20 + uint32_t(mode));
}

}  // namespace
