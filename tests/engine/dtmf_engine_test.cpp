// host/engine/dtmf_engine against hls/dtmf_chain.h, the bit-exact spec of
// the FPGA top: same packets (type, t, payload bytes), same order. Both are
// configured from the same plan (hls::make_dtmf_top_plan of the scene at the
// top's 18 MHz clock; the plan does not depend on the clock, which sets only
// CLK_HZ): the engine by engine_config(), the chain by hls::chain_config().
// Scenes: the default (3x3, thesis carriers off bin centres: demixing, ghost
// filter, two neuron layers), the staggered 10x10 (bin-centred carriers,
// rectified-change receptors, three touches), the 32x32 skin (64 carriers,
// N 256, 12-bit ADC, no neurons) and the 64x64 one (128 carriers, N 512,
// 1 MS/s). Each on one thread and on
// several with small chunks, so run, slice and chunk boundaries fall inside
// the recordings. Bound: exact equality (integer arithmetic on both sides).
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "host/engine/dtmf_engine.h"
#include "host/engine/engine_setup.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using eskin::engine::DtmfEngine;
using eskin::engine::EngineConfig;
using eskin::hls::DtmfChainSizes;
using eskin::hls::DtmfTopPlan;

struct Pk {
  uint8_t type;
  uint32_t t;
  std::vector<uint8_t> payload;
  bool operator==(const Pk& o) const { return type == o.type && t == o.t && payload == o.payload; }
};

template <class S>
std::vector<Pk> run_chain(const DtmfTopPlan& plan, const std::vector<uint16_t>& codes,
                          uint32_t* dropped = nullptr) {
  using Chain = eskin::hls::DtmfChain<S>;
  auto chain = std::make_unique<Chain>(eskin::hls::chain_config<S>(plan));
  EXPECT_TRUE(chain->ok());
  auto out = std::make_unique<typename Chain::Packet[]>(Chain::kMaxPackets);
  auto& pk = *reinterpret_cast<typename Chain::Packet(*)[Chain::kMaxPackets]>(out.get());
  std::vector<Pk> r;
  for (size_t i = 0; i < codes.size(); ++i) {
    const int n = chain->push(codes[i], uint32_t(i), pk);
    for (int j = 0; j < n; ++j)
      r.push_back({pk[j].type, pk[j].t, {pk[j].payload, pk[j].payload + pk[j].len}});
  }
  if (dropped) *dropped = chain->spikes_dropped();
  return r;
}

// neuron_work 1: every layer split over the threads, however small.
std::vector<Pk> run_engine(const EngineConfig& e, const std::vector<uint16_t>& codes, int threads,
                           size_t chunk, uint32_t* dropped = nullptr, uint64_t neuron_work = 0) {
  DtmfEngine eng(e);
  const auto ps = eng.run(codes.data(), codes.size(), {threads, chunk, neuron_work});
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
  DtmfTopPlan plan;
};
SceneRun load(const std::string& file) {
  SceneRun r{eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/" + file), {}, {}};
  eskin::sim::WorldModel world(r.scene);
  r.codes = eskin::engine::codes12(world.all_codes(), r.scene.skin.adc.bits);
  r.plan = eskin::hls::make_dtmf_top_plan(
      eskin::sim::dtmf_top_spec(r.scene, eskin::hls::kDtmfTopClkHz));
  return r;
}

// The chain's packets for the plan, and the engine's on 1, 2, 3 and 8
// threads with chunks of several sizes (the neuron layers split by the
// engine's own rule, and over every thread).
template <class S>
std::vector<Pk> check_plan(const DtmfTopPlan& plan, const std::vector<uint16_t>& codes,
                           const std::string& what) {
  const auto want = run_chain<S>(plan, codes);
  const EngineConfig e = eskin::engine::engine_config(plan);
  expect_same(want, run_engine(e, codes, 1, 0), what + ", 1 thread");
  expect_same(want, run_engine(e, codes, 2, 100), what + ", 2 threads, 100-frame chunks");
  expect_same(want, run_engine(e, codes, 3, 77), what + ", 3 threads, 77-frame chunks");
  expect_same(want, run_engine(e, codes, 3, 77, nullptr, 1),
              what + ", 3 threads, 77-frame chunks, neurons on every thread");
  expect_same(want, run_engine(e, codes, 8, 500), what + ", 8 threads, 500-frame chunks");
  expect_same(want, run_engine(e, codes, 8, 500, nullptr, 1),
              what + ", 8 threads, 500-frame chunks, neurons on every thread");
  return want;
}

TEST(DtmfEngine, DefaultSceneEqualsChainPacketForPacket) {
  const auto s = load("neuroskin2.yaml");
  ASSERT_TRUE(s.plan.spec.demix && s.plan.spec.ghost && s.plan.spec.spikes);
  const auto want = check_plan<DtmfChainSizes<3, 3, 32>>(s.plan, s.codes, "default");
  EXPECT_GE(count(want, eskin::hls::kDtmfAmplitudes), 100u);
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsDense), 100u);
  EXPECT_GE(count(want, eskin::hls::kDtmfSpikes), 10u);
}

TEST(DtmfEngine, Staggered10x10EqualsChain) {
  const auto s = load("staggered10x10.yaml");
  ASSERT_FALSE(s.plan.spec.demix);
  ASSERT_TRUE(s.plan.neuron[0].input_change);
  const auto want = check_plan<DtmfChainSizes<10, 10, 64>>(s.plan, s.codes, "10x10");
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsDense), 100u);
  EXPECT_GE(count(want, eskin::hls::kDtmfSpikes), 5u);
}

TEST(DtmfEngine, Skin32x32EqualsChain) {
  const auto s = load("skin32x32.yaml");
  ASSERT_EQ(s.plan.K, 64);
  const auto want = check_plan<DtmfChainSizes<32, 32, 256>>(s.plan, s.codes, "32x32");
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsDense), 5u);
}

// The 64x64 skin at 1 MS/s: 128 carriers (the top's most DFT channels), N
// 512, a frame every 1000 samples (the engine computes each frame's sums
// directly from its window), every frame's amplitudes, dense and sparse
// taxels sent.
TEST(DtmfEngine, Skin64x64EqualsChain) {
  const auto s = load("skin64x64.yaml");
  ASSERT_EQ(s.plan.K, 128);
  ASSERT_FALSE(s.plan.spec.demix);
  DtmfTopPlan p = eskin::engine::with_step(s.plan, s.plan.step, 1);
  p.mask |= eskin::hls::kMaskAmplitudes | eskin::hls::kMaskTaxels | eskin::hls::kMaskSparse;
  const auto want = check_plan<DtmfChainSizes<64, 64, 512>>(p, s.codes, "64x64");
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsDense), 20u);
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsSparse), 20u);
}

// Sparse taxels with a threshold, the ghost filter off, another step (the
// demixer's per-frame rotation, the ghost lookback and the neuron dt follow
// it) and decimations that differ between the streams.
TEST(DtmfEngine, SparseNoGhostStepsAndDecimations) {
  const auto s = load("neuroskin2.yaml");
  DtmfTopPlan p = s.plan;
  p.mask = eskin::hls::kMaskAmplitudes | eskin::hls::kMaskSparse | eskin::hls::kMaskSpikes;
  p.sparse_min = 2000;
  p.decim_amp = 3;
  p.decim_tax = 5;
  const auto want = check_plan<DtmfChainSizes<3, 3, 32>>(p, s.codes, "sparse");
  EXPECT_GE(count(want, eskin::hls::kDtmfTaxelsSparse), 50u);
  p = s.plan;
  p.spec.ghost = false;
  p.mask |= eskin::hls::kMaskSparse;
  check_plan<DtmfChainSizes<3, 3, 32>>(p, s.codes, "no ghost filter");
  p = eskin::engine::with_step(s.plan, 7, 11);
  ASSERT_EQ(p.lookback, 4);
  check_plan<DtmfChainSizes<3, 3, 32>>(p, s.codes, "step 7");
}

// A spike window holding more than MAX_SPIKES events: the same events are
// kept and the same number dropped.
TEST(DtmfEngine, SpikeOverflowDropsLikeTheChain) {
  const auto s = load("neuroskin2.yaml");
  DtmfTopPlan p = s.plan;
  p.max_spikes = 3;
  p.decim_tax = 40;
  uint32_t d_chain = 0, d_eng = 0;
  const auto want = run_chain<DtmfChainSizes<3, 3, 32, 4, 3>>(p, s.codes, &d_chain);
  expect_same(want, run_engine(eskin::engine::engine_config(p), s.codes, 2, 99, &d_eng),
              "max_spikes 3");
  EXPECT_GT(d_chain, 0u) << "the scene must overflow a 3-event window";
  EXPECT_EQ(d_eng, d_chain);
}

TEST(DtmfEngine, RejectsBadConfigNamingTheField) {
  const auto s = load("neuroskin2.yaml");
  EngineConfig e = eskin::engine::engine_config(s.plan);
  e.inc.pop_back();  // the DC channel missing
  try {
    DtmfEngine eng(e);
    FAIL() << "6 increments for 6 carriers + DC accepted";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("engine.inc"), std::string::npos) << ex.what();
  }
  e = eskin::engine::engine_config(s.plan);
  e.demix_tables.coef.pop_back();
  EXPECT_THROW(DtmfEngine{e}, std::invalid_argument);
  e = eskin::engine::engine_config(s.plan);
  e.step = 0;
  EXPECT_THROW(DtmfEngine{e}, std::invalid_argument);
}

}  // namespace
