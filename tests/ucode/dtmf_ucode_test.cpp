// The DTMF microcode (rtl/ucode/dtmf_chain.fe) on the frame engine's
// instruction-set model, inside a clocked model of the top's IO
// (tests/ucode/dtmf_top_model.h), against hls/dtmf_chain.h: every data packet
// equal, byte for byte, on the default scene, the staggered 10x10 scene and
// a 5x7 skin under random carriers; the engine finishes every frame inside
// its frame period (no frame lost), with the clock counts printed. With the
// neuron unit (NEURON_UNIT: its ports modelled by hls::IzhikevichUnitPort)
// the same packets in fewer clocks, SET_NEURON at run time included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dtmf_top_model.h"
#include "random_carriers.h"
#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "ucode/dtmf_frame_bound.h"
#include "ucode/dtmf_ucode.h"
#include "ucode/frame_engine.h"
#include "ucode/frame_engine_asm.h"
#include "hls/synapse_weights.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"
#include "eskin/skin_config.h"

namespace {

using namespace eskin;

// The chain's packets of one push, as the top model's.
template <class Pk>
void append_packets(std::vector<dtmf_model::Packet>& want, const Pk* pk, int np) {
  for (int i = 0; i < np; ++i)
    want.push_back({pk[i].type, pk[i].t, {pk[i].payload, pk[i].payload + pk[i].len}});
}

// Every data packet the top model sent (status packets aside) equals the
// chain's, in order; the last frame's few may still be in the engine when
// the samples end. Returns how many were compared.
template <class S>
size_t expect_data_packets_equal(const dtmf_model::TopModel<S>& top,
                                 const std::vector<dtmf_model::Packet>& want, const std::string& what) {
  std::vector<dtmf_model::Packet> got;
  for (const auto& p : top.packets())
    if (p.type != hls::kDtmfStatus) got.push_back(p);
  EXPECT_GE(got.size() + 4, want.size()) << what;
  const size_t n = std::min(got.size(), want.size());
  size_t same = 0;
  while (same < n && got[same] == want[same]) ++same;
  EXPECT_EQ(same, n) << what << ": packet " << same << " differs (type "
                     << int(want[same].type) << ")";
  return same;
}

// The top model and the chain on the same 12-bit codes: every data packet
// equal; returns the engine's longest frame, in clocks.
template <class S>
uint64_t compare_codes(const std::string& what, const hls::DtmfTopPlan& plan, long period,
                       const std::vector<uint16_t>& codes) {
  dtmf_model::TopModel<S> top(plan, period);
  auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
  EXPECT_TRUE(chain->ok());
  std::vector<dtmf_model::Packet> want;
  typename hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
  for (size_t n = 0; n < codes.size(); ++n) {
    top.sample(codes[n]);
    append_packets(want, pk, chain->push(codes[n], uint32_t(n), pk));
  }
  EXPECT_EQ(top.frame_overruns(), 0u);
  EXPECT_GT(want.size(), 250u);  // every case: hundreds of frames of every type
  const size_t same = expect_data_packets_equal(top, want, what);
  std::printf("%s%s: %zu packets equal; the engine's longest frame %llu clocks of %ld available\n",
              what.c_str(),
              plan.spec.neuron_lanes ? " with the neuron lanes"
              : plan.spec.neuron_unit ? " with the neuron unit" : "",
              same,
              (unsigned long long)top.max_frame_clocks(), period * plan.step);
  EXPECT_LE(top.max_frame_clocks(), uint64_t(period * plan.step));
  return top.max_frame_clocks();
}

template <class S>
uint64_t compare_scene(const std::string& scene_file, long clk_hz, bool neuron_unit = false,
                       int lanes = 0) {
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/" + scene_file);
  auto spec = sim::dtmf_top_spec(sc, clk_hz);
  spec.neuron_unit = neuron_unit;
  spec.neuron_lanes = lanes;
  const long period = std::lround(double(clk_hz) / sc.skin.adc.rate_hz);
  sim::WorldModel world(sc);
  std::vector<uint16_t> codes;
  for (int c : world.all_codes()) codes.push_back(uint16_t(c << (12 - sc.skin.adc.bits)));
  return compare_codes<S>(scene_file, hls::make_dtmf_top_plan(spec), period, codes);
}

TEST(DtmfUcode, DefaultSceneEqualsTheChain) {
  compare_scene<hls::DtmfChainSizes<3, 3, 32>>("scenes/neuroskin2.yaml", hls::kDtmfTopClkHz);
}

TEST(DtmfUcode, Staggered10x10EqualsTheChain) {
  compare_scene<hls::DtmfChainSizes<10, 10, 64>>("scenes/staggered10x10.yaml", 96000000);
}

// The neuron_unit routine: the same packets as the chain (both layers'
// spikes are in them), on both scenes. Bound on the clocks (the engine's
// timing, docs/frame_engine.md: one clock an instruction at best): the
// izhikevich_layer routine runs at least 77 instructions per neuron plus
// its loop's 9; on every path 7 of them are min/max (one more B clock
// each), 7 shift by a DMEM count (a clock loads it, then steps; or no
// overlap after a count of 0: one more each), 2 are rnd 14 (the rounding
// clock: one more each) and 2 jump on A (a bubble each): at least 104
// clocks. nu_layer's loop: 19 instructions of one clock (the wait's
// included), one bubble after the wait, and no longer wait: the unit
// answers 14 clocks after the `out` that starts it, and the 16 instructions
// from there to the next wait take 16 clocks: 20 clocks a neuron. Each
// layer adds at most 40 (its prologue: 11 instructions, a bubble for the
// j.eq; its epilogue: a wait of at most 14, 9 instructions and ret). At
// least 84 fewer per neuron: the 10x10 scene updates 200 neurons every
// frame in two layers, so its longest frame is at least 200 x 84 - 2 x 40
// = 16 720 clocks shorter (16 700 asserted).
// The unit's lanes (NEURON_LANES: they keep the state and the flags): the
// same packets, and shorter again. The unit's level loop takes at least 14
// clocks a neuron and synapse_weights 12 a taxel: 2 800 + 1 200 for the
// 10x10 scene; with lanes layer 0 takes 3 a neuron and layer 1 none of
// its own (synapse_weights, 8 a taxel, starts its neurons): 300 + 800.
// Against the 2 900 saved, the lanes record each spike after the layer
// (11 clocks, the unit's loops 8 inline: at most 3 x 200 more), wait for
// each layer's last write-back (at most 16 clocks twice) and set the next
// neuron (2 clocks twice): at least 2 900 - 600 - 36 > 2 200 fewer.
TEST(DtmfUcode, NeuronUnitGivesTheSamePacketsInFewerClocks) {
  using S3 = hls::DtmfChainSizes<3, 3, 32>;
  using S10 = hls::DtmfChainSizes<10, 10, 64>;
  compare_scene<S3>("scenes/neuroskin2.yaml", hls::kDtmfTopClkHz, true);
  const uint64_t soft = compare_scene<S10>("scenes/staggered10x10.yaml", 96000000);
  const uint64_t unit = compare_scene<S10>("scenes/staggered10x10.yaml", 96000000, true);
  const uint64_t lanes = compare_scene<S10>("scenes/staggered10x10.yaml", 96000000, true, 5);
  EXPECT_LE(unit + 16700, soft);
  EXPECT_LE(lanes + 2200, unit);
  std::printf("10x10 scene, longest frame: %llu clocks with the neurons on the engine, %llu on the "
              "unit, %llu on its lanes\n",
              (unsigned long long)soft, (unsigned long long)unit, (unsigned long long)lanes);
}

// A rows x cols skin of the default scene's ADC at 96 MHz and 600 frames
// of its random on/off carriers (each at 0 or 1.2 full carriers, the taxel
// rule's range), switched every 3 frames.
struct RandomSkin {
  hls::DtmfTopSpec spec;
  long period = 0;
  std::vector<uint16_t> codes;
};
RandomSkin random_skin(int rows, int cols) {
  sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  sc.skin.rows = rows, sc.skin.cols = cols;
  const auto f = plan_carriers(rows + cols, sc.skin.adc.rate_hz, 32);
  sc.skin.row_freq_hz.assign(f.begin(), f.begin() + rows);
  sc.skin.col_freq_hz.assign(f.begin() + rows, f.end());
  sc.skin.freq_error.clear();
  const long clk_hz = 96000000;
  RandomSkin r;
  r.spec = sim::dtmf_top_spec(sc, clk_hz);
  r.period = std::lround(double(clk_hz) / r.spec.sample_hz);
  const double full = r.spec.full_carrier_lsb * std::ldexp(1.0, 12 - r.spec.adc_bits);
  const int step = int(std::lround(r.spec.frame_ms * r.spec.sample_hz / 1000.0));
  r.codes = dtmf_stimulus::random_carrier_codes(f, r.spec.sample_hz, full, 600 * step, 3 * step, 7);
  return r;
}
RandomSkin random_5x7() { return random_skin(5, 7); }

// A 5 x 7 skin (rows != columns, so a row/column mix-up shows) driven by
// random on/off carriers, switched every 3 frames: many lines rise and
// fall at once (the ghost filter's pairing, its candidate list up to K),
// and most neurons, those on the border included, spike (the synapse
// sums' margin). Exact: every data packet equals the chain's, with the
// neurons on the engine and on the unit.
TEST(DtmfUcode, RandomCarriersOn5x7EqualTheChain) {
  using S = hls::DtmfChainSizes<5, 7, 32>;
  auto [spec, period, codes] = random_5x7();
  for (int unit : {0, 1, 2}) {  // 2: the lanes
    spec.neuron_unit = unit > 0;
    spec.neuron_lanes = unit == 2 ? 5 : 0;
    compare_codes<S>("random carriers, 5x7", hls::make_dtmf_top_plan(spec), period, codes);
  }
}

// carrier_magnitude's bound with demixing: y is saturated to 24 bits, so
// re and im reach 2^23 and p = re^2 + im^2 nearly 2^47, past the 48-bit
// accumulator's room for 4 p (MAG_SHIFT = 0) from p = 2^45; the kernel
// (hls/carrier_magnitude.h) gives 65535 for every p >= 2^32. No ADC input
// gets there (window sums of 12-bit codes through the builder's matrix stay
// near the sums), so the test plays the DFT: the engine and the chain's
// demix kernel get the same full-scale sums (|sum| = 2^17 - 1, ACC_W = 18),
// their signs chosen each frame against the kernel's rotation so that they
// add up in rows 0 and 1 of a matrix whose entries there are all the
// largest Q2.14 value (what a host can send with SET_DEMIX_COEF): carrier
// 0's p passes 2^45 (counted). The engine's AMPLITUDES packets equal the
// chain's kernels (hls/dtmf_chain.h: Demix, then Magnitude) on those sums.
TEST(DtmfUcode, DemixedMagnitudeSaturatesPastTheAccumulatorsRoom) {
  using S = hls::DtmfChainSizes<5, 7, 32>;
  using Chain = hls::DtmfChain<S>;
  using Token = hls::CarrierDemixToken;
  constexpr int K = S::K, DIM = 2 * K + 1;
  auto [spec, period, codes] = random_5x7();
  spec.demix = true;
  auto plan = hls::make_dtmf_top_plan(spec);
  ASSERT_EQ(plan.mag_shift, 0);  // the routine's q = 4 p path
  plan.mask |= hls::kMaskAmplitudes;
  plan.decim_amp = 1;
  for (int i = 0; i < 2 * DIM; ++i) plan.demix.coef.at(size_t(i)) = 32767;  // rows 0 and 1
  typename Chain::Demix demix;
  ASSERT_TRUE(demix.configure(hls::chain_config<S>(plan).demix_cfg));
  dtmf_model::TopModel<S> top(plan, period);
  constexpr int32_t kFull = (1 << (S::ACC_W - 1)) - 1;
  std::vector<std::vector<uint8_t>> want;  // AMPLITUDES payloads, frame by frame
  int beyond = 0;                          // frames with carrier 0's p >= 2^45
  top.on_frame = [&](std::vector<int32_t>& sums) {
    Token tok[K + 1], out[K];
    for (int k = 0; k <= K; ++k) tok[k] = {uint8_t(k), kFull, kFull, k == K};
    const auto y0 = [&] {  // row 0 (= row 1) on these tokens, the kernel's state kept
      auto d = demix;
      for (const Token& t : tok) d.push(t, out);
      return out[0].re;
    };
    for (Token& t : tok) {  // y0 is linear in each token's pair: the best signs one by one
      int32_t best_re = t.re, best_im = t.im, best = y0();
      for (int sgn = 1; sgn < 4; ++sgn) {
        t.re = sgn & 1 ? -kFull : kFull, t.im = sgn & 2 ? -kFull : kFull;
        const int32_t y = y0();
        if (y > best) best = y, best_re = t.re, best_im = t.im;
      }
      t.re = best_re, t.im = best_im;
    }
    for (const Token& t : tok) demix.push(t, out);
    const int64_t re = out[0].re, im = out[0].im;
    beyond += re * re + im * im >= int64_t(1) << 45;
    std::vector<uint8_t> pay;
    for (int k = 0; k < K; ++k) {
      const uint32_t m = Chain::Magnitude::magnitude(out[k].re, out[k].im);
      pay.push_back(uint8_t(m)), pay.push_back(uint8_t(m >> 8));
    }
    want.push_back(pay);
    for (int k = 0; k <= K; ++k) sums[size_t(2 * k)] = tok[k].re, sums[size_t(2 * k + 1)] = tok[k].im;
  };
  for (size_t n = 0; n < size_t(S::N + 60 * plan.step); ++n) top.sample(codes.at(n));
  std::vector<std::vector<uint8_t>> got;
  for (const auto& p : top.packets())
    if (p.type == hls::kDtmfAmplitudes) got.push_back(p.payload);
  EXPECT_EQ(top.frame_overruns(), 0u);
  EXPECT_GE(beyond, 50);
  ASSERT_GE(got.size() + 2, want.size());  // the last frame may still be in the engine
  ASSERT_LE(got.size(), want.size());
  int saturated = 0;
  for (size_t f = 0; f < got.size(); ++f) {
    ASSERT_EQ(got[f], want[f]) << "frame " << f << ": carrier 0's magnitude "
                               << (got[f][0] | got[f][1] << 8) << ", the chain's "
                               << (want[f][0] | want[f][1] << 8);
    saturated += want[f][0] == 0xFF && want[f][1] == 0xFF;
  }
  EXPECT_EQ(saturated, int(got.size()));
  std::printf("%zu frames, carrier 0's p >= 2^45 in %d: every AMPLITUDES packet the chain's\n",
              got.size(), beyond);
}

// The ghost filter's argmax takes four lines a loop and the last (n - 1) &
// 3 lines of a dimension of n by name: skins whose rows and columns give
// every count of loops (0, 1, 2) and of last lines (0..3), one line alone
// (1 x 6) included, with random carriers (the 5x7 test's stimulus: many
// lines rise at once, so the pairing takes several argmaxes a frame and
// equal rises tie). Exact: every data packet equals the chain's.
template <int R, int C>
void compare_random_skin() {
  auto [spec, period, codes] = random_skin(R, C);
  spec.neuron_unit = true;
  for (int lanes : {0, 5}) {  // the unit; the lanes (their synapse_weights' starts too)
    spec.neuron_lanes = lanes;
    compare_codes<hls::DtmfChainSizes<R, C, 32>>(
        "random carriers, " + std::to_string(R) + "x" + std::to_string(C),
        hls::make_dtmf_top_plan(spec), period, codes);
  }
}
TEST(DtmfUcode, GhostArgmaxOnEveryLineCountEqualsTheChain) {
  compare_random_skin<4, 8>();
  compare_random_skin<8, 4>();
  compare_random_skin<1, 6>();
  compare_random_skin<2, 9>();
}

// The paths a full spike window and a chain without the ghost filter
// take: the 5x7 random carriers with 48 spike events in a window of 20
// frames (T = 35 neurons a layer), so a window starts with room for a
// whole layer (the spike encoder's loop without the room test), then fills
// within a layer (the tested loop) and then holds MAXSPK events (the rest
// of the flags added up as drops: hundreds of spikes dropped); and the
// same codes with the ghost filter off (every taxel its product, no site
// rule). Exact: every data packet equals the chain's, with the neurons on
// the engine and on the unit (whose layer loops record the events: the
// level loop, and with the receptors on the input's change the change
// loop too, each with its drop path), and the engine's drop count (SPKDROP, the
// STATUS field) equals the chain's spike encoder's, far below the 16-bit
// saturation.
TEST(DtmfUcode, FullSpikeWindowsAndNoGhostFilterEqualTheChain) {
  using S = hls::DtmfChainSizes<5, 7, 32, 4, 48>;
  auto [spec, period, codes] = random_5x7();
  for (bool ghost : {true, false})
    for (int unit : {0, 1, 2, 3, 4}) {  // 2, 4: receptors on the input's change; 3, 4: lanes
      spec.ghost = ghost;
      spec.neuron_unit = unit > 0;
      spec.neuron_change = unit == 2 || unit == 4;
      spec.neuron_lanes = unit >= 3 ? 5 : 0;
      auto plan = hls::make_dtmf_top_plan(spec);
      plan.max_spikes = S::MAX_SPIKES;
      plan.decim_tax = 20;  // a spike window of 20 frames
      const std::string what = std::string("48 spikes a window, ghost filter ") +
                               (ghost ? "on" : "off") +
                               (spec.neuron_change ? ", input change" : "");
      if (spec.neuron_change) {
        ASSERT_TRUE(plan.neuron[0].input_change) << "the change loop";
      }
      compare_codes<S>(what, plan, period, codes);
      // The drop counts, on a fresh pair (compare_codes keeps neither): the
      // chain's after each frame, the engine's after the last frame it
      // released (the samples may end while it runs one more).
      dtmf_model::TopModel<S> top(plan, period);
      auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
      typename hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
      std::vector<uint32_t> chain_drops;  // after frame i + 1
      for (size_t n = 0; n < codes.size(); ++n) {
        top.sample(codes[n]);
        chain->push(codes[n], uint32_t(n), pk);
        if (chain->frames() > chain_drops.size()) chain_drops.push_back(chain->spikes_dropped());
      }
      ASSERT_GT(top.frames_done(), 0u);
      ASSERT_LE(top.frames_done(), chain_drops.size());
      const uint32_t want = chain_drops[top.frames_done() - 1];
      const uint32_t drops = top.engine().dmem(uint32_t(top.image().symbol("SPKDROP")));
      std::printf("%s%s: %u spikes dropped in %u frames\n", what.c_str(),
                  unit >= 3 ? ", neuron lanes" : unit ? ", neuron unit" : "", drops,
                  top.frames_done());
      // Receptors on the input's change spike only while it moves: with
      // the ghost filter's sites few of them do, and the window fills
      // once (one drop, which still takes the change loop's drop path).
      EXPECT_GT(want, spec.neuron_change && ghost ? 0u : 500u);
      EXPECT_LT(want, 65535u);
      EXPECT_EQ(drops, want);
    }
  // Spikes not recorded (mask bit 2 clear) on the unit: its loops still
  // take each spike's path (x1 = 2 MAXSPK sends every one to the drop
  // path), which must then count nothing: SPKDROP stays 0 over the ghost
  // filter off's thousands of spikes, and the packets equal the chain's.
  spec.ghost = false;
  spec.neuron_unit = true;
  spec.neuron_change = false;
  for (int lanes : {0, 5}) {
    spec.neuron_lanes = lanes;
    auto plan = hls::make_dtmf_top_plan(spec);
    plan.max_spikes = S::MAX_SPIKES;
    plan.decim_tax = 20;
    plan.mask &= ~4;
    compare_codes<S>("spikes not recorded", plan, period, codes);
    dtmf_model::TopModel<S> top(plan, period);
    for (size_t n = 0; n < codes.size(); ++n) top.sample(codes[n]);
    ASSERT_GT(top.frames_done(), 500u);
    EXPECT_EQ(top.engine().dmem(uint32_t(top.image().symbol("SPKDROP"))), 0u);
  }
}

// SET_NEURON changes sent to the top model at run time, each once the
// engine has released frame `after_frame`, and applied to the chain before
// the next one; the default scene with the neuron unit and without. Exact:
// every data packet equals the chain's.
struct NeuronChange {
  uint32_t after_frame;
  int layer, param;
  int32_t value;
};
template <class Changes>
void expect_neuron_changes_equal_the_chain(Changes changes_of) {
  using S = hls::DtmfChainSizes<3, 3, 32>;
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  sim::WorldModel world(sc);
  std::vector<uint16_t> codes;
  for (int c : world.all_codes()) codes.push_back(uint16_t(c << (12 - sc.skin.adc.bits)));
  for (int unit : {1, 0, 2}) {  // 2: the lanes
    auto spec = sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz);
    spec.neuron_unit = unit > 0;
    spec.neuron_lanes = unit == 2 ? 5 : 0;
    const auto plan = hls::make_dtmf_top_plan(spec);
    const std::vector<NeuronChange> changes = changes_of(plan);
    const long period = std::lround(double(hls::kDtmfTopClkHz) / sc.skin.adc.rate_hz);
    dtmf_model::TopModel<S> top(plan, period);
    auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
    std::vector<dtmf_model::Packet> want;
    hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
    size_t sent = 0, applied = 0;
    for (size_t n = 0; n < codes.size(); ++n) {
      if (sent < changes.size() && top.frames_done() >= changes[sent].after_frame) {
        const NeuronChange& c = changes[sent++];
        const uint32_t v = uint32_t(c.value);
        top.command({0x83, uint8_t(sent), 5, 0, uint8_t(c.layer << 4 | c.param), uint8_t(v),
                     uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)});
      }
      if (applied < changes.size() && chain->frames() >= changes[applied].after_frame) {
        const NeuronChange& c = changes[applied++];
        auto cfg = chain->neuron_config(c.layer);
        ASSERT_TRUE(hls::apply_neuron_param(cfg, c.param, c.value));
        chain->set_neuron(c.layer, cfg);
      }
      top.sample(codes[n]);
      append_packets(want, pk, chain->push(codes[n], uint32_t(n), pk));
    }
    EXPECT_EQ(sent, changes.size());
    EXPECT_EQ(applied, changes.size());
    EXPECT_GT(want.size(), 1000u);
    expect_data_packets_equal(top, want, unit ? "unit" : "engine");
  }
}

// SET_NEURON at run time reaches the neuron unit: the unit's constants are
// the DMEM words the command changes, copied to it at every layer. Four
// changes at frames 60-240 (layer 1's gain, layer 0's input mode, which
// switches the unit between x and x - x_prev, layer 0's v_reset, layer 1's
// x_shift); each was applied, at once, to its layer.
TEST(DtmfUcode, SetNeuronAtRunTimeReachesTheNeuronUnit) {
  expect_neuron_changes_equal_the_chain([](const hls::DtmfTopPlan& plan) {
    return std::vector<NeuronChange>{
        {60, 1, 2, plan.neuron[1].gain / 2},
        {120, 0, 13, plan.neuron[0].input_change ? 0 : 1},
        {180, 0, 0, -60 * (int32_t(1) << 22)},  // -60 mV, Q9.22
        {240, 1, 4, plan.neuron[1].x_shift + 1},
    };
  });
}

// c4 U at its widest: s4 = 0 and m4 = -32768 (both in SET_NEURON's
// range), so c4 U = m4 U reaches 2^45 once U saturates at 2^30; the chain
// (int64) and the unit (47 bits) keep it whole, and so must the
// izhikevich_layer routine (it once kept the low 32 bits: at U = 2^30 the
// term vanished). Also a large u_jump, which drives U to its bounds.
TEST(DtmfUcode, WideRecoveryTermEqualsTheChain) {
  expect_neuron_changes_equal_the_chain([](const hls::DtmfTopPlan&) {
    return std::vector<NeuronChange>{
        {40, 0, 11, 0},                                // s4
        {41, 0, 10, -32768},                           // m4
        {42, 0, 1, (int32_t(1) << 30) - 1},            // u_jump
        {43, 1, 11, 0},
        {44, 1, 10, 32767},
    };
  });
}

// synapse_weights looks each taxel's sum up in a 512-word table (SWT, one
// word per 3x3 spike pattern) that sw_table keeps: built at boot from the
// plan's weights, updated by SET_WEIGHT with the new weight minus the old
// on the 256 patterns that hold its bit. Random weights of the whole int16
// range at boot and 27 changes at run time (every weight three times, its
// extremes -32768 and 32767 included), on the 5x7 random carriers (most
// neurons spike, borders included), neurons on the engine and on the unit.
// Exact, three ways: after every frame (1) every table word equals the sum
// of its pattern's weights; (2) every layer-1 input (X2IN) equals
// hls::SynapseWeights on the layer-0 flags the engine left in S0 (the
// off-grid neighbours of the border taxels count as 0: the last row's
// code reads layer 1's first row below it, the row above row 0 is a zero
// row); (3) every data packet equals the chain's, the weights set on it at
// the same frames. Negative controls: the last row's mask keeping its
// bits below fails (2) at frame 7; the m <= 8 update one step short fails
// (1) at frame 1.
TEST(DtmfUcode, SetWeightKeepsTheSynapseTableExact) {
  using S = hls::DtmfChainSizes<5, 7, 32>;
  constexpr int R = 5, C = 7, T = R * C;
  auto [spec, period, codes] = random_5x7();
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> any16(-32768, 32767);
  for (bool unit : {false, true}) {
    spec.neuron_unit = unit;
    auto plan = hls::make_dtmf_top_plan(spec);
    for (auto& w : plan.synapse.w) w = int16_t(any16(rng));
    struct Change {
      uint32_t after_frame;
      int id;
      int16_t w;
    };
    std::vector<Change> changes;
    for (int n = 0; n < 27; ++n)
      changes.push_back({uint32_t(30 + 15 * n), (n * 4) % 9,
                         int16_t(n % 9 == 0 ? -32768 : n % 9 == 1 ? 32767 : any16(rng))});
    dtmf_model::TopModel<S> top(plan, period);
    auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
    hls::SynapseWeights<R, C> golden;
    ASSERT_TRUE(golden.configure(plan.synapse));
    const auto sym = [&top](const char* n) { return uint32_t(top.image().symbol(n)); };
    const uint32_t swt = sym("SWT"), s0 = sym("S0"), x2in = sym("X2IN");
    // Weight d's bit in a pattern (the layout ucode/dtmf_engine_image.h gives
    // KC_SWBIT): column (1 - dc), row (1 - dr) within it.
    const auto bit = [](int d) { return 3 * (2 - d % 3) + (2 - d / 3); };
    std::vector<dtmf_model::Packet> want;
    hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
    size_t sent = 0, applied = 0;
    uint32_t checked = 0;
    std::vector<bool> seen(512, false);  // the 3x3 patterns the frames held
    uint32_t s1_row0 = 0;  // layer-1 flags set in row 0: what the next frame's last row reads below
    for (size_t n = 0; n < codes.size(); ++n) {
      if (top.frames_done() > checked) {  // a frame is done; the next one is not in
        checked = top.frames_done();
        for (uint32_t code = 0; code < 512; ++code) {
          int32_t sum = 0;
          for (int d = 0; d < 9; ++d)
            if (code >> bit(d) & 1) sum += golden.config().w[d];
          ASSERT_EQ(int32_t(top.engine().dmem(swt + code)), sum)
              << "SWT[" << code << "] after frame " << checked << (unit ? ", unit" : "");
        }
        for (int c = 0; c < C; ++c) s1_row0 += top.engine().dmem(s0 + uint32_t(T + c)) != 0;
        bool flags[T];
        for (int i = 0; i < T; ++i) flags[i] = top.engine().dmem(s0 + uint32_t(i)) != 0;
        for (int i = 0; i < T; ++i) {
          ASSERT_EQ(int32_t(top.engine().dmem(x2in + uint32_t(i))), golden.input(flags, i / C, i % C))
              << "X2IN[" << i << "] after frame " << checked << (unit ? ", unit" : "");
          int code = 0;
          for (int d = 0; d < 9; ++d) {
            const int r = i / C + d / 3 - 1, c = i % C + d % 3 - 1;
            if (r >= 0 && r < R && c >= 0 && c < C && flags[r * C + c])
              code |= 1 << bit(d);
          }
          seen[size_t(code)] = true;
        }
      }
      if (sent < changes.size() && top.frames_done() >= changes[sent].after_frame) {
        const Change& c = changes[sent++];
        const uint16_t v = uint16_t(c.w);
        top.command({0x88, uint8_t(sent), 3, 0, uint8_t(c.id), uint8_t(v), uint8_t(v >> 8)});
        golden.set_weight(c.id, c.w);  // in effect from the next frame on
      }
      if (applied < changes.size() && chain->frames() >= changes[applied].after_frame) {
        chain->set_weight(changes[applied].id, changes[applied].w);
        ++applied;
      }
      top.sample(codes[n]);
      append_packets(want, pk, chain->push(codes[n], uint32_t(n), pk));
    }
    EXPECT_EQ(sent, changes.size());
    EXPECT_GT(checked, 550u);
    const auto patterns = std::count(seen.begin(), seen.end(), true);
    EXPECT_GT(patterns, 100);  // the lookups read many different table words
    EXPECT_GT(s1_row0, 100u);  // the last row's code read set flags below it (S1's), masked off
    const size_t same = expect_data_packets_equal(top, want, unit ? "unit" : "engine");
    std::printf("SET_WEIGHT x %zu%s: %u frames' tables and layer-1 inputs exact (%ld spike patterns), %zu packets equal\n",
                sent, unit ? ", neuron unit" : "", checked, long(patterns), same);
  }
}

// SET_CARRIER_INC's frame increment (FINC, the carrier demixer's phase
// step a frame): the microcode forms STEP x inc mod 2^32 on the engine's
// 16 x 16 multiplier from inc's halves. Bound: exact, against the 64-bit
// product here, for increments that take every case of the split: bit 15
// clear and set (the low half reads negative, a carry into the high half),
// the high half plus that carry reaching 2^15 (inc >= 0x7FFF8000, where it
// reads -2^15), and the extremes 1 and 2^31 - 1; at STEP 35 (the default
// scene) and 1000 (1 MS/s).
TEST(DtmfUcode, SetCarrierIncFormsTheFrameIncrement) {
  using S = hls::DtmfChainSizes<3, 3, 32>;
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  for (const double fs : {sc.skin.adc.rate_hz, 1e6}) {
    auto spec = sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz);
    spec.sample_hz = fs;
    spec.demix = spec.demix && fs == sc.skin.adc.rate_hz;  // its tables are for the scene's rate
    const auto plan = hls::make_dtmf_top_plan(spec);
    dtmf_model::TopModel<S> top(plan, 2000);  // the engine keeps up: commands are not delayed
    const uint32_t finc = uint32_t(top.image().symbol("FINC"));
    const uint32_t incs[] = {1u,          0x7FFFu,     0x8000u,     0x0ABC8001u, 0x12345678u,
                             0x4000C000u, 0x7FFF7FFFu, 0x7FFF8000u, 0x7FFFFFFFu};
    uint8_t seq = 0;
    for (const uint32_t inc : incs) {
      const int k = seq % plan.K;
      top.command({0x81, ++seq, 5, 0, uint8_t(k), uint8_t(inc), uint8_t(inc >> 8),
                   uint8_t(inc >> 16), uint8_t(inc >> 24)});
      for (int n = 0; n < 50; ++n) top.sample(2048);
      EXPECT_EQ(top.engine().dmem(finc + 2 * uint32_t(k)), uint32_t(uint64_t(plan.step) * inc))
          << "STEP " << plan.step << ", inc 0x" << std::hex << inc;
    }
    EXPECT_EQ(plan.step, fs == 1e6 ? 1000 : 35);
  }
}

// The output FIFO's word port (hls::OutFifoPort; rtl/dtmf_top.v 0x209): a
// word's bits 15:8 take the FIFO in the clock after its `out`, so a FIFO
// write in that clock throws, and one a clock later follows the word's
// two bytes. On the engine's model, so that the clocks are the
// instructions' own (`out`s one instruction apart are one clock apart).
struct FifoIo {
  hls::OutFifoPort fifo;
  std::vector<uint8_t> out;
  uint32_t io_read(uint16_t, uint64_t) { return 0; }
  void io_write(uint16_t a, uint32_t d, uint64_t c) { fifo.write(a, d, c, &out); }
  uint16_t events(uint64_t) { return 0; }
};
std::vector<uint8_t> fifo_bytes(const std::string& body) {
  hls::fe_asm::Options opt;
  opt.symbols = {{"IO_OUT_BYTE", hls::kIoOutByte}, {"IO_OUT_WORD", hls::kIoOutWord}};
  const auto prog = hls::fe_asm::assemble(body + "\nend: j end\n", "fifo_test", opt);
  hls::FrameEngine<hls::FrameEngineConfig> e;
  e.load_program(prog.words.data(), uint32_t(prog.words.size()));
  FifoIo io;
  for (size_t i = 0; i + 1 < prog.words.size(); ++i) e.step(io);
  return io.out;
}

TEST(DtmfUcode, OutputWordPortsSecondByteTakesTheNextClock) {
  using B = std::vector<uint8_t>;
  EXPECT_EQ(fifo_bytes("ldi 0x1234\nout io[IO_OUT_WORD]\nldi 0x56\nout io[IO_OUT_BYTE]"),
            (B{0x34, 0x12, 0x56}));
  EXPECT_EQ(fifo_bytes("ldi 0xABCD\nout io[IO_OUT_WORD]\nshr 8\nout io[IO_OUT_WORD]"),
            (B{0xCD, 0xAB, 0xAB, 0x00}));
  EXPECT_THROW(fifo_bytes("ldi 0x1234\nout io[IO_OUT_WORD]\nout io[IO_OUT_BYTE]"),
               std::logic_error);
  EXPECT_THROW(fifo_bytes("ldi 0x1234\nout io[IO_OUT_WORD]\nout io[IO_OUT_WORD]"),
               std::logic_error);
  // Bytes may follow each other in consecutive clocks; a word may follow a byte.
  EXPECT_EQ(fifo_bytes("ldi 0x0201\nout io[IO_OUT_BYTE]\nout io[IO_OUT_BYTE]\n"
                       "out io[IO_OUT_WORD]"),
            (B{0x01, 0x01, 0x01, 0x02}));
}

// The engine of a build with the barrel shifter, as large as the microcode
// may address.
struct BarrelEngine {
  static constexpr int IW = hls::kDtmfImemBits, DW = 15, KW = 12;
  static constexpr bool FAST_SHIFT = true;
};

// taxel_reconstruct's taxel loop, clock for clock, on the instruction-set
// model with the barrel shifter (the ULX3S's engine). Called on its own
// (PC at its label, the return stack's 0 as the way out) over a 10x10
// skin's DMEM: the roots of every line, the sites as each case sets them,
// RELEASE 0 (no site dropped: v >= 0) or 65535 (every site dropped: the
// roots are small, so v < 65535). What the loop's comment claims, from
// docs/frame_engine.md's Timing (one clock an instruction; min 2; rnd by
// an immediate 2 with the barrel shifter; a DMEM read right after a `st`
// waits a clock, a jump on A right after a write of A too):
//  - a taxel without a site: 6 clocks (ld, lt, j.eq taken; st, addx, djnz);
//  - a site after a site (tr_in): 16: ld, mpy, j.eq, ld.h15, mpy, apac,
//    rnd 2, min 2, st, addx, sub, lt, j.lt, djnz, no wait anywhere;
//  - a site that starts a row or follows a taxel without one (tr_nl): 17,
//    the same instructions with lt in the test's slot and mpy after it.
// So, against a frame without sites: sites only in column 0 add 11 a row;
// sites everywhere add 17 + 16 (C - 1) - 6 C a row; one taxel without a
// site in the middle of a row of sites saves 16 + 16 - (6 + 17) = 9; and
// dropping every site adds tr_rl's ldi and two st: 3 a site. A loop with
// the release test's load right after the store of G (DMEM's one port
// stalls it a clock) takes 17 every site: sites everywhere would add
// R (C - 1) more and the hole save 11, which this test tells apart.
TEST(DtmfUcode, TaxelLoopTakes16ClocksASiteAfterASite) {
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/staggered10x10.yaml");
  auto spec = sim::dtmf_top_spec(sc, 96000000);
  spec.engine_fast_shift = true;
  const hls::DtmfTopPlan plan = hls::make_dtmf_top_plan(spec);
  ASSERT_TRUE(plan.spec.ghost);  // the site rule is the GHOST branch
  const hls::EngineImage im = hls::dtmf_engine_image(plan);
  hls::fe_asm::Options opt;
  for (const auto& [name, value] : im.symbols) opt.symbols[name] = value;
  opt.imem_words = hls::kDtmfImemWords;
  const auto prog = hls::fe_asm::assemble(hls::dtmf_ucode_source(), "dtmf_chain.fe", opt);
  const int R = plan.R, C = plan.C;
  // Clocks of one call of taxel_reconstruct with sites where site(i, j).
  auto clocks = [&](auto site, uint32_t release) {
    auto e = std::make_unique<hls::FrameEngine<BarrelEngine>>();
    e->load_program(prog.words.data(), uint32_t(prog.words.size()));
    e->load_krom(im.krom.data(), uint32_t(im.krom.size()));
    for (int i = 0; i < R; ++i) e->set_dmem(uint32_t(im.symbol("ROOT") + i), 100 + i);
    for (int j = 0; j < C; ++j) e->set_dmem(uint32_t(im.symbol("CRT") + j), 200 + j);
    for (int i = 0; i < R; ++i)
      for (int j = 0; j < C; ++j)
        e->set_dmem(uint32_t(im.symbol("SITE") + i * C + j), site(i, j) ? 1 : 0);
    e->set_dmem(uint32_t(im.symbol("RELEASE")), release);
    e->reset();
    e->set_pc(uint32_t(prog.symbols.at("taxel_reconstruct")));
    hls::FrameEngineNullIo io;
    e->run(io, 100000, [](const auto& f) { return f.pc() == 0; });
    EXPECT_EQ(e->pc(), 0u) << "taxel_reconstruct did not return";
    return int64_t(e->clocks());
  };
  const int64_t none = clocks([](int, int) { return false; }, 0);
  const int64_t first = clocks([](int, int j) { return j == 0; }, 0);
  const int64_t all = clocks([](int, int) { return true; }, 0);
  const int64_t hole = clocks([](int i, int j) { return !(i == 4 && j == 5); }, 0);
  const int64_t dropped = clocks([](int, int) { return true; }, 65535);
  std::printf("taxel_reconstruct on %dx%d: no site %lld clocks, column 0 %lld, every taxel %lld\n",
              R, C, (long long)none, (long long)first, (long long)all);
  EXPECT_EQ(first - none, 11 * R);
  EXPECT_EQ(all - none, int64_t(R) * (17 + 16 * (C - 1) - 6 * C));
  EXPECT_EQ(all - hole, 9);
  EXPECT_EQ(dropped - all, 3 * R * C);
}

}  // namespace

namespace {

// The streaming build's control plane (STREAM: rtl/dtmf_chain.v does the
// per-taxel work) assembles for scenes/skin64x64.yaml, its 4096 taxels
// taking no DMEM word (the engine keeps no taxel, site, neuron or spike),
// inside the IMEM of every build, and with none of the engine's per-taxel
// routines in it (taxel_reconstruct, izhikevich_layer, synapse_weights,
// sw_table: their labels are absent).
TEST(DtmfUcode, StreamingControlPlaneFitsWithNoTaxelState) {
  auto spec = eskin::sim::dtmf_top_spec(
      eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/skin64x64.yaml"));
  spec.datapath = eskin::hls::DtmfDatapath::Streaming;
  const auto plan = eskin::hls::make_dtmf_top_plan(spec);
  ASSERT_EQ(plan.T, 4096);
  const auto im = eskin::hls::dtmf_engine_image(plan);
  EXPECT_EQ(im.symbol("STREAM"), 1);
  EXPECT_LT(im.dend, 2048) << "DMEM words";
  const auto prog = eskin::hls::dtmf_ucode_program(im);
  const auto words = eskin::hls::dtmf_ucode_words(im);
  EXPECT_LE(words.size(), size_t(eskin::hls::kDtmfImemWords));
  for (const char* l : {"taxel_reconstruct", "izhikevich_layer", "synapse_weights", "sw_table",
                        "carrier_magnitude", "nrn_init"})
    EXPECT_EQ(prog.symbols.count(l), 0u) << l;
  for (const char* l : {"stream_setup", "stream_cfg", "stream_consts", "ghost_filter"})
    EXPECT_EQ(prog.symbols.count(l), 1u) << l;
  // The engine build of the same plan keeps them (and would not fit DMEM).
  spec.datapath = eskin::hls::DtmfDatapath::FrameEngine;
  EXPECT_EQ(eskin::hls::dtmf_engine_image(eskin::hls::make_dtmf_top_plan(spec)).symbol("STREAM"), 0);
  std::printf("skin64x64 control plane: %zu IMEM words, %d DMEM words\n", words.size(), im.dend);
}

}  // namespace

namespace {

// The streaming build's control plane on the top model (the chain's
// magnitudes in the frame buffer: tests/ucode/dtmf_top_model.h) against
// hls/dtmf_chain.h on scenes/planned3x3.yaml with spikes, frame by frame:
//  - AMPLITUDES: every packet equal to the chain's;
//  - the header of frame f: dense and sparse on a taxel frame as the mask
//    asks, spikes recorded, the window's end, from the plan's decimations
//    counted here (hls/dtmf_chain.h's rule);
//  - the sites: those the engine writes for frame f, with the sites left
//    after frame f - 1's release, are exactly the ghost filter's after its
//    frame() step (hls::GhostFilter on the same magnitudes, its release by
//    hls::TaxelReconstruct's values): the chain's mask holds that set when
//    its taxels go.
template <class S>
void control_plane_equals_chain(const char* scene, long clk_hz, bool spikes, size_t min_frames) {
  const sim::Scene sc = sim::load_scene(std::string(ESKIN_SOURCE_DIR "/") + scene);
  auto spec = sim::dtmf_top_spec(sc, clk_hz);
  spec.datapath = hls::DtmfDatapath::Streaming;
  spec.spikes = spikes;
  spec.neuron_unit = false;
  spec.neuron_lanes = 0;
  spec.engine_fast_shift = false;  // TopModel's engine
  const auto plan = hls::make_dtmf_top_plan(spec);
  ASSERT_FALSE(plan.spec.demix);
  ASSERT_TRUE(plan.spec.ghost);
  const long period = std::lround(double(clk_hz) / sc.skin.adc.rate_hz);
  sim::WorldModel world(sc);
  std::vector<uint16_t> codes;
  for (int c : world.all_codes()) codes.push_back(uint16_t(c << (12 - sc.skin.adc.bits)));

  dtmf_model::TopModel<S> top(plan, period);
  auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
  ASSERT_TRUE(chain->ok());
  auto ghost = std::make_unique<hls::GhostFilter<S::R, S::C, S::L_MAX>>();
  ASSERT_TRUE(ghost->configure(hls::chain_config<S>(plan).ghost_cfg));
  auto taxel = std::make_unique<hls::TaxelReconstruct<S::R, S::C>>();
  ASSERT_TRUE(taxel->configure(hls::chain_config<S>(plan).taxel));
  // Per frame: the header the chain's counters give, the sites after frame().
  std::vector<uint32_t> want_hdr;
  std::vector<std::vector<bool>> want_sites;
  std::vector<std::vector<bool>> kept;  // after each frame's release
  std::vector<dtmf_model::Packet> want_amp;
  typename hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
  uint32_t amp_cnt = 0, tax_cnt = 0, frames = 0;
  for (size_t n = 0; n < codes.size(); ++n) {
    top.sample(codes[n]);
    const int np = chain->push(codes[n], uint32_t(n), pk);
    for (int i = 0; i < np; ++i)
      if (pk[i].type == hls::kDtmfAmplitudes)
        want_amp.push_back({pk[i].type, pk[i].t, {pk[i].payload, pk[i].payload + pk[i].len}});
    if (chain->frames() == frames) continue;
    frames = chain->frames();
    uint16_t mag[S::K];
    for (int k = 0; k < S::K; ++k) mag[k] = chain->magnitude(k);
    ghost->frame(mag);
    std::vector<bool> s(S::T);
    for (int i = 0; i < S::T; ++i) s[size_t(i)] = ghost->site(i / S::C, i % S::C);
    want_sites.push_back(s);
    taxel->lines(mag);
    ghost->release([&](int i, int j) { return taxel->value(i, j); });
    for (int i = 0; i < S::T; ++i) s[size_t(i)] = ghost->site(i / S::C, i % S::C);
    kept.push_back(s);
    const bool tax_sel = tax_cnt == 0, win_end = tax_cnt + 1 >= plan.decim_tax;
    tax_cnt = win_end ? 0 : tax_cnt + 1;
    amp_cnt = amp_cnt + 1 >= plan.decim_amp ? 0 : amp_cnt + 1;
    want_hdr.push_back((tax_sel && (plan.mask & hls::kMaskTaxels) ? 1u : 0u) |
                       (tax_sel && (plan.mask & hls::kMaskSparse) ? 2u : 0u) |
                       ((plan.mask & hls::kMaskSpikes) ? 4u : 0u) | (win_end ? 8u : 0u));
  }
  const auto& bus = top.bus();
  ASSERT_GE(want_hdr.size(), min_frames);
  ASSERT_GE(bus.headers.size() + 2, want_hdr.size());  // the last may still be in the engine
  const size_t nf = std::min(bus.headers.size(), want_hdr.size());
  ASSERT_EQ(bus.sites_at_header.size(), bus.headers.size());
  // Every site of the mask cleared once at boot.
  EXPECT_EQ(bus.site_clears.size(), size_t(S::T));
  size_t first = 0, paired = 0;
  for (size_t f = 0; f < nf; ++f) {
    EXPECT_EQ(bus.headers[f], want_hdr[f]) << "frame " << f;
    std::vector<bool> s = f ? kept[f - 1] : std::vector<bool>(S::T);
    for (size_t w = first; w < bus.sites_at_header[f]; ++w) {
      ASSERT_LT(bus.sites[w], uint32_t(S::T)) << "frame " << f;
      s[bus.sites[w]] = true;
    }
    paired += bus.sites_at_header[f] - first;
    first = bus.sites_at_header[f];
    ASSERT_EQ(s, want_sites[f]) << "frame " << f << ": the sites the chain's mask holds";
  }
  EXPECT_GT(paired, 0u) << "no site written: the scene's presses must make some";
  // AMPLITUDES.
  std::vector<dtmf_model::Packet> got_amp;
  for (const auto& p : top.packets())
    if (p.type == hls::kDtmfAmplitudes) got_amp.push_back(p);
  ASSERT_GE(got_amp.size() + 2, want_amp.size());
  for (size_t i = 0; i < std::min(got_amp.size(), want_amp.size()); ++i)
    ASSERT_EQ(got_amp[i], want_amp[i]) << "AMPLITUDES " << i;
  EXPECT_EQ(top.frame_overruns(), 0u);
  std::printf("%s control plane: %zu frames, %zu site writes, longest frame %llu clocks "
              "of %ld\n",
              scene, nf, paired, (unsigned long long)top.max_frame_clocks(), period * plan.step);
}

// The 3x3 scene with spikes at the UP5K's clock, and the 64x64 skin at 1
// MS/s (128 magnitudes a frame, two presses and a slide; the ULX3S's 40
// MHz; the model's bit-serial engine) with the scene's outputs: the control plane of
// the large build, its sites and headers against the kernels'.
TEST(DtmfUcode, StreamingControlPlaneEqualsTheChain) {
  control_plane_equals_chain<hls::DtmfChainSizes<3, 3, 32>>("scenes/planned3x3.yaml",
                                                             hls::kDtmfTopClkHz, true, 250);
  control_plane_equals_chain<hls::DtmfChainSizes<64, 64, 512>>("scenes/skin64x64.yaml", 40000000,
                                                                false, 25);
}

}  // namespace

namespace {

// The ghost filter's pairing at its most: every line rising at once, by
// random amounts far above the onset and the pairing tolerance, on every
// other frame (the others quiet, so the next rises are the whole
// magnitudes again). Each pair empties one line only, so a frame pairs up
// to R + C - 1 times (3x3: 5, where the loop's old bound counted min(R, C)
// = 3), capped at max_pairs (8x8: 8 of 15; hls/ghost_filter.h). The
// streaming build's control plane on the instruction-set model, the
// magnitudes injected where the chain puts them: per frame the sites it
// adds are the kernel's (GhostFilter::frame on the same magnitudes), the
// kernel's pair count reaches the most the plan allows, and the engine's
// longest frame stays within the control plane's static bound (the bound's
// frame less the chain's clocks).
template <class S>
void pairing_at_its_most(int want_pairs) {
  sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  sc.skin.rows = S::R, sc.skin.cols = S::C;  // bin-centred carriers in the window S::N
  sc.decoder.window = S::N;
  const auto f = plan_carriers(S::K, sc.skin.adc.rate_hz, S::N);
  sc.skin.row_freq_hz.assign(f.begin(), f.begin() + S::R);
  sc.skin.col_freq_hz.assign(f.begin() + S::R, f.end());
  sc.skin.freq_error.clear();
  auto spec = sim::dtmf_top_spec(sc, hls::kDtmfTopClkHz);
  spec.datapath = hls::DtmfDatapath::Streaming;
  spec.neuron_unit = false;
  spec.neuron_lanes = 0;
  spec.engine_fast_shift = false;  // TopModel's engine
  const auto plan = hls::make_dtmf_top_plan(spec);
  ASSERT_FALSE(plan.spec.demix);
  ASSERT_EQ(plan.ghost.max_pairs, std::min(8, S::R + S::C - 1));
  const long period = std::lround(double(hls::kDtmfTopClkHz) / spec.sample_hz);
  dtmf_model::TopModel<S> top(plan, period);
  auto ghost = std::make_unique<hls::GhostFilter<S::R, S::C, S::L_MAX>>();
  ASSERT_TRUE(ghost->configure(hls::chain_config<S>(plan).ghost_cfg));
  std::mt19937 rng(77);
  std::uniform_int_distribution<int> level(int(plan.ghost.onset) + 4 * int(plan.ghost.pair_tol) + 50,
                                           int(plan.ghost.onset) + 4 * int(plan.ghost.pair_tol) + 4000);
  std::vector<std::vector<bool>> want_sites;
  std::vector<bool> prev(S::T, false);
  int frames = 0, most = 0;
  top.on_frame = [&](std::vector<int32_t>& mags) {
    uint16_t mag[S::K];
    for (int k = 0; k < S::K; ++k) mag[k] = uint16_t(frames % 2 ? level(rng) : 0);
    for (int k = 0; k < S::K; ++k) mags[size_t(k)] = mag[k];
    ghost->frame(mag);
    most = std::max(most, ghost->pair_steps());
    std::vector<bool> s(S::T);
    for (int i = 0; i < S::T; ++i) s[size_t(i)] = ghost->site(i / S::C, i % S::C);
    want_sites.push_back(s);
    ghost->release([](int, int) { return 0; });  // every site released: each frame's own
    ++frames;
  };
  const size_t n = size_t(plan.N + 41 * plan.step);
  for (size_t i = 0; i < n; ++i) top.sample(uint16_t(2048));
  const auto& bus = top.bus();
  ASSERT_GE(bus.headers.size(), 40u);
  size_t first = 0;
  for (size_t f = 0; f < bus.headers.size(); ++f) {
    std::vector<bool> s(S::T, false);  // the chain's mask: released, then this frame's adds
    for (size_t w = first; w < bus.sites_at_header[f]; ++w) s[bus.sites[w]] = true;
    first = bus.sites_at_header[f];
    ASSERT_EQ(s, want_sites[f]) << "frame " << f;
  }
  EXPECT_EQ(most, want_pairs);
  const auto bound = hls::dtmf_frame_bound(plan);
  std::printf("%dx%d pairing: at most %d pairs a frame; longest control-plane frame %llu clocks, "
              "its bound %llu\n",
              S::R, S::C, most, (unsigned long long)top.max_frame_clocks(),
              (unsigned long long)(bound.frame - bound.chain));
  EXPECT_LE(top.max_frame_clocks(), bound.frame - bound.chain);
  EXPECT_EQ(top.frame_overruns(), 0u);
}

}  // namespace

TEST(DtmfUcode, GhostPairingTakesUpToRPlusCMinusOnePairsAndMaxPairsAtMost) {
  pairing_at_its_most<hls::DtmfChainSizes<3, 3, 32>>(5);
  pairing_at_its_most<hls::DtmfChainSizes<8, 8, 64>>(8);
}
