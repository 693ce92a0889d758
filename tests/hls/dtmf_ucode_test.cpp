// The DTMF microcode (rtl/ucode/dtmf_chain.fe) on the frame engine's
// instruction-set model, inside a clocked model of the top's IO
// (tests/hls/dtmf_top_model.h), against hls/dtmf_chain.h: every data packet
// equal, byte for byte, on the default scene and the staggered 10x10 scene;
// the engine finishes every frame inside its frame period (no frame lost),
// with the clock counts printed.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "dtmf_top_model.h"
#include "hls/dtmf_chain.h"
#include "hls/dtmf_top_config.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using namespace eskin;

template <class S>
void compare_scene(const std::string& scene_file, long clk_hz) {
  const sim::Scene sc = sim::load_scene(ESKIN_SOURCE_DIR "/" + scene_file);
  const auto plan = hls::make_dtmf_top_plan(sim::dtmf_top_spec(sc, clk_hz));
  const long period = std::lround(double(clk_hz) / sc.skin.adc.rate_hz);
  dtmf_model::TopModel<S> top(plan, period);
  auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
  ASSERT_TRUE(chain->ok());
  sim::WorldModel world(sc);
  const auto codes = world.all_codes();
  const int up = 12 - sc.skin.adc.bits;
  std::vector<dtmf_model::Packet> want;
  typename hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
  for (size_t n = 0; n < codes.size(); ++n) {
    const uint16_t code = uint16_t(codes[n] << up);
    top.sample(code);
    const int np = chain->push(code, uint32_t(n), pk);
    for (int i = 0; i < np; ++i)
      want.push_back({pk[i].type, pk[i].t, {pk[i].payload, pk[i].payload + pk[i].len}});
  }
  std::vector<dtmf_model::Packet> got;
  for (const auto& p : top.packets())
    if (p.type != hls::kDtmfStatus) got.push_back(p);
  EXPECT_EQ(top.frame_overruns(), 0u);
  ASSERT_GT(want.size(), 250u);  // both scenes: hundreds of frames of every type
  // The last frame's packets may still be in the engine when the samples end.
  ASSERT_GE(got.size() + 4, want.size());
  const size_t n = std::min(got.size(), want.size());
  for (size_t i = 0; i < n; ++i) {
    ASSERT_EQ(got[i].type, want[i].type) << "packet " << i;
    ASSERT_EQ(got[i].t, want[i].t) << "packet " << i;
    ASSERT_EQ(got[i].payload, want[i].payload) << "packet " << i << " type " << int(want[i].type);
  }
  std::printf("%s: %zu packets equal; the engine's longest frame %llu clocks of %ld available\n",
              scene_file.c_str(), n, (unsigned long long)top.max_frame_clocks(),
              period * plan.step);
  EXPECT_LE(top.max_frame_clocks(), uint64_t(period * plan.step));
}

TEST(DtmfUcode, DefaultSceneEqualsTheChain) {
  compare_scene<hls::DtmfChainSizes<3, 3, 32>>("scenes/neuroskin2.yaml", hls::kDtmfTopClkHz);
}

TEST(DtmfUcode, Staggered10x10EqualsTheChain) {
  compare_scene<hls::DtmfChainSizes<10, 10, 64>>("scenes/staggered10x10.yaml", 96000000);
}

}  // namespace
