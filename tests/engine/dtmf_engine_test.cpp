// host/engine/dtmf_engine against hls/dtmf_chain.h, the bit-exact spec of
// the FPGA top: same packets (type, t, payload bytes), same order, for the
// default scene (3x3, N 32, every sample a step), a 16x16 skin (the top's
// 16x16 build: N 128, step 16) and the 32x32 skin (64 carriers, N 256,
// 12-bit ADC), on one thread and on several with small chunks (so segment,
// slice and chunk boundaries all fall inside the recordings).
// Bound: exact equality (integer arithmetic on both sides).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "hls/dtmf_chain.h"
#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using eskin::engine::DtmfEngine;
using eskin::engine::EngineConfig;

struct Pk {
  uint8_t type;
  uint32_t t;
  std::vector<uint8_t> payload;
  bool operator==(const Pk& o) const { return type == o.type && t == o.t && payload == o.payload; }
};

// The chain configured like an engine config (for runs off the top's plan).
template <class Chain>
typename Chain::Config chain_config(const EngineConfig& e) {
  typename Chain::Config c;
  c.sdft.carriers = e.carriers();
  for (int k = 0; k < e.carriers(); ++k) c.sdft.inc[k] = e.inc[size_t(k)];
  c.taxel = e.taxel;
  c.neuron = e.neuron;
  c.step = e.step;
  c.decim_amp = e.decim_amp;
  c.decim_tax = e.decim_tax;
  c.mask = e.mask;
  return c;
}

template <class Chain>
std::vector<Pk> run_chain(const typename Chain::Config& cfg, const std::vector<uint16_t>& codes,
                          uint32_t* dropped = nullptr) {
  auto chain = std::make_unique<Chain>(cfg);
  EXPECT_TRUE(chain->ok());
  auto out = std::make_unique<typename Chain::Packet[]>(3);
  auto& p3 = *reinterpret_cast<typename Chain::Packet(*)[3]>(out.get());
  std::vector<Pk> r;
  for (size_t i = 0; i < codes.size(); ++i) {
    const int n = chain->push(codes[i], uint32_t(i), p3);
    for (int j = 0; j < n; ++j)
      r.push_back({p3[j].type, p3[j].t, {p3[j].payload, p3[j].payload + p3[j].len}});
  }
  if (dropped) *dropped = chain->spikes_dropped();
  return r;
}

std::vector<Pk> run_engine(const EngineConfig& e, const std::vector<uint16_t>& codes, int threads,
                           size_t chunk, uint32_t* dropped = nullptr) {
  DtmfEngine eng(e);
  const auto ps = eng.run(codes.data(), codes.size(), {threads, chunk});
  std::vector<Pk> r;
  for (const auto& p : ps.packets)
    r.push_back({p.type, p.t, {ps.payload(p), ps.payload(p) + p.len}});
  if (dropped) *dropped = ps.spikes_dropped;
  return r;
}

void expect_same(const std::vector<Pk>& want, const std::vector<Pk>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(got[i] == want[i]) << what << ": packet " << i << " type " << int(want[i].type)
                                   << " t " << want[i].t << " (got type " << int(got[i].type)
                                   << " t " << got[i].t << ")";
}

size_t count(const std::vector<Pk>& v, uint8_t type) {
  size_t n = 0;
  for (const auto& p : v) n += p.type == type;
  return n;
}

struct SceneRun {
  eskin::sim::Scene scene;
  std::vector<uint16_t> codes;
};
SceneRun load(const std::string& path) {
  SceneRun r{eskin::sim::load_scene(path), {}};
  eskin::sim::WorldModel world(r.scene);
  r.codes = eskin::engine::codes12(world.all_codes(), r.scene.skin.adc.bits);
  return r;
}

eskin::hls::DtmfTopPlan plan_of(const eskin::sim::Scene& sc, long clk_hz = 12000000) {
  return eskin::engine::top_plan(sc.skin, sc.decoder, sc.neuron, true, clk_hz);
}

template <class Chain>
void check_scene(const std::vector<uint16_t>& codes, const EngineConfig& e,
                 const typename Chain::Config& chain_cfg, size_t min_spike_packets) {
  const auto want = run_chain<Chain>(chain_cfg, codes);
  EXPECT_GE(count(want, eskin::hls::kDtmfAmplitudes), 10u);
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsDense), 10u);
  EXPECT_GE(count(want, eskin::hls::kDtmfSpikes), min_spike_packets);
  expect_same(want, run_engine(e, codes, 1, size_t(1) << 18), "1 thread");
  expect_same(want, run_engine(e, codes, 2, 1000), "2 threads, 1000-step chunks");
  expect_same(want, run_engine(e, codes, 3, 777), "3 threads, 777-step chunks");
  expect_same(want, run_engine(e, codes, 8, 5000), "8 threads, 5000-step chunks");
}

// The top's own build for the scene: engine from the plan, chain from the
// plan's chain_config (hls/dtmf_top_config.h), two independent copies.
template <class Chain>
void check_plan(const SceneRun& s, size_t min_spike_packets) {
  const auto plan = plan_of(s.scene);
  check_scene<Chain>(s.codes, eskin::engine::engine_config(plan),
                     eskin::hls::chain_config<Chain>(plan), min_spike_packets);
}

TEST(DtmfEngine, DefaultSceneEqualsChainPacketForPacket) {
  const auto s = load(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  ASSERT_EQ(s.codes.size(), 21000u);
  ASSERT_EQ(plan_of(s.scene).step, 1);
  check_plan<eskin::hls::DtmfChain<3, 3, 32, 12, 16, 10, 18>>(s, 20);
}

// A 16x16 skin as the top builds it at 12 MHz (N 128, a step of several
// samples, a frame buffer); presses so neurons fire.
TEST(DtmfEngine, Skin16x16EqualsChain) {
  auto s = load(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  s.scene = eskin::sim::parse_scene(R"(
name: skin16
seed: 3
duration_s: 0.3
skin:
  rows: 16
  cols: 16
  carriers: auto
  conductance: {kind: saturating, p_half_kpa: 50}
  adc: {rate_hz: 35000, bits: 10, noise_rms_v: 0.001}
decoder: {window: 128, variant: exact}
neuron: {preset: RA, input: level, input_scale: 10}
stimuli:
  - press: {taxel: [3, 12], pressure_kpa: 60, t_start_s: 0.010, ramp_s: 0.005, hold_s: 0.060, release_s: 0.005}
  - press: {taxel: [15, 0], pressure_kpa: 80, t_start_s: 0.100, ramp_s: 0.005, hold_s: 0.150, release_s: 0.005}
)", "skin16 (dtmf_engine_test)");
  eskin::sim::WorldModel world(s.scene);
  s.codes = eskin::engine::codes12(world.all_codes(), 10);
  ASSERT_GT(plan_of(s.scene).step, 1);
  check_plan<eskin::hls::DtmfChain<16, 16, 128, 12, 16, 10, 20>>(s, 5);
}

// 64 carriers, N 256, 12-bit ADC (MAG_SHIFT 0), steps of 8 samples (at
// 12 MHz the top cannot take this skin: 1024 taxels need a step longer than
// the neurons allow; the plan at 100 MHz supplies the constants).
TEST(DtmfEngine, Skin32x32EqualsChain) {
  using Chain = eskin::hls::DtmfChain<32, 32, 256, 12, 16, 10, 21, 16, 0>;
  const auto s = load(ESKIN_SOURCE_DIR "/scenes/skin32x32.yaml");
  const EngineConfig e = eskin::engine::engine_config(plan_of(s.scene, 100000000), 8, 4, 7);
  check_scene<Chain>(s.codes, e, chain_config<Chain>(e), 0);
}

// A spike window holding more than MAX_SPIKES events: the same events are
// kept and the same number dropped. Amplitude-only and spike-only masks
// give the same packets as the chain too.
TEST(DtmfEngine, SpikeOverflowAndMasks) {
  const auto s = load(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  const auto plan = plan_of(s.scene);
  EngineConfig e = eskin::engine::engine_config(plan, 1, 200, 7);
  e.max_spikes = 3;
  uint32_t d_chain = 0, d_eng = 0;
  using Small = eskin::hls::DtmfChain<3, 3, 32, 12, 16, 10, 18, 16, 2, 16, 3>;
  const auto want = run_chain<Small>(chain_config<Small>(e), s.codes, &d_chain);
  expect_same(want, run_engine(e, s.codes, 2, 999, &d_eng), "max_spikes 3");
  EXPECT_GT(d_chain, 0u) << "the scene must overflow a 3-event window";
  EXPECT_EQ(d_eng, d_chain);
  using Chain = eskin::hls::DtmfChain<3, 3, 32, 12, 16, 10, 18>;
  for (uint8_t mask : {uint8_t(1), uint8_t(2), uint8_t(4)}) {
    e = eskin::engine::engine_config(plan, 2, 7, mask);
    expect_same(run_chain<Chain>(chain_config<Chain>(e), s.codes), run_engine(e, s.codes, 2, 1234),
                "mask " + std::to_string(mask));
  }
}

// Every taxel mode of taxel_reconstruct (product, conductance, pressure
// table) against the kernel, on magnitudes spread over the whole u16 range.
TEST(DtmfEngine, TaxelModesEqualKernel) {
  EngineConfig e;
  e.inc.assign(6, 1u << 28);
  e.taxel.recip = 54067;
  e.taxel.recip_shift = 12;
  e.taxel.shift = 9;
  for (int s = 0; s < eskin::hls::kTaxelPwlN; ++s) {
    e.taxel.g_tab[s] = uint16_t(s * 4000);
    e.taxel.p_tab[s] = uint32_t(s * 3000);
    e.taxel.slope[s] = uint16_t(300 + s);
  }
  e.taxel.slope_shift = 10;
  for (auto mode : {eskin::hls::TaxelMode::Product, eskin::hls::TaxelMode::Conductance,
                    eskin::hls::TaxelMode::Pressure}) {
    e.taxel.mode = mode;
    DtmfEngine eng(e);
    eskin::hls::TaxelReconstruct<3, 3, 16, 16> k;
    ASSERT_TRUE(k.configure(e.taxel));
    for (uint32_t mi = 0; mi < 65536; mi += 97)
      for (uint32_t mj : {0u, 1u, 2u, 255u, 4096u, 40000u, 65535u, mi, 65535u - mi})
        ASSERT_EQ(eng.taxel(mi, mj), k.taxel(mi, mj)) << "mode " << int(mode) << " " << mi << " " << mj;
  }
}

TEST(DtmfEngine, RejectsBadConfigNamingTheField) {
  EngineConfig e;
  e.inc.assign(5, 1u);  // 3 + 3 carriers expected
  try {
    DtmfEngine eng(e);
    FAIL() << "5 increments for 6 carriers accepted";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("engine.inc"), std::string::npos) << ex.what();
  }
  e.inc.assign(6, 1u);
  e.step = 0;
  EXPECT_THROW(DtmfEngine{e}, std::invalid_argument);
}

}  // namespace
