// hls/taxel_reconstruct.h (one root per line, one multiply per taxel)
// against the golden taxel_g (host/golden/taxel_reconstruct.h) on random
// magnitudes and on the default scene's magnitudes as the FPGA chain makes
// them (hls/dtmf_chain.h). Magnitude units: the chain's (window sums of
// 12-bit codes); the golden model gets the same integers divided by F, one
// full carrier's magnitude, so only the kernel's own arithmetic is compared.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "hls/taxel_reconstruct.h"
#include "host/golden/taxel_reconstruct.h"
#include "sim/dtmf_top_spec.h"
#include "sim/scene.h"
#include "sim/world_model.h"

using namespace eskin;

namespace {

// The bound of hls/taxel_reconstruct.h, in UQ1.15 LSB.
double bound(double mi, double mj, double F, double g) {
  return std::ldexp(1.0, 15) * (std::sqrt(mi) + std::sqrt(mj)) / (128.0 * F) +
         std::ldexp(g, -15) + 0.5;
}

hls::TaxelReconstructConfig config_for(double F, int rows, int cols) {
  hls::TaxelReconstructConfig c;
  c.rows = uint8_t(rows);
  c.cols = uint8_t(cols);
  int rs = 0;
  while (std::ldexp(1.0, 15 + rs) / F < 16384.0) ++rs;
  c.recip_shift = uint8_t(rs);
  c.recip = uint16_t(std::lround(std::ldexp(1.0, 15 + rs) / F));
  return c;
}

// Exact: root = floor(sqrt(mag) 2^7) for every 16-bit magnitude, against an
// independent long-double square root.
TEST(TaxelReconstructHls, LineRootsAreExactFloors) {
  for (uint32_t m = 0; m < 65536; ++m) {
    const auto r = hls::taxel_line_root(uint16_t(m));
    const long double want = std::floor(std::sqrt((long double)m * 16384.0L));
    ASSERT_EQ(r, uint16_t(want)) << m;
    ASSERT_LT(r, 32768) << "root must be a positive 16-bit signed operand";
  }
}

// Bound (derived in the header): |g - 2^15 sqrt(mi mj) / F| <= 2^15 (sqrt mi
// + sqrt mj) / (2^7 F) + 2^-15 g + 1/2, g saturating at 65535; 200 000
// random pairs at three full-carrier scales, including the extremes 0 and
// 65535.
TEST(TaxelReconstructHls, ValuesWithinTheDerivedBoundOfGolden) {
  std::mt19937 rng(7);
  for (double F : {9929.7, 2482.4, 40000.0}) {
    const auto cfg = config_for(F, 1, 1);
    hls::TaxelReconstruct<1, 1> k;
    ASSERT_TRUE(k.configure(cfg));
    double worst = 0;
    for (int n = 0; n < 200000; ++n) {
      const uint16_t mi = n < 4 ? uint16_t((n & 1) * 65535) : uint16_t(rng());
      const uint16_t mj = n < 4 ? uint16_t((n >> 1) * 65535) : uint16_t(rng());
      const uint16_t mags[2] = {mi, mj};
      k.lines(mags);
      const Eigen::MatrixXd g = golden::taxel_g(Eigen::VectorXd::Constant(1, mi / F),
                                                Eigen::VectorXd::Constant(1, mj / F));
      const double want = std::min(65535.0, g(0, 0) * 32768.0);
      const double err = std::fabs(k.value(0, 0) - want);
      ASSERT_LE(err, bound(mi, mj, F, want)) << mi << " " << mj << " F " << F;
      worst = std::max(worst, err / bound(mi, mj, F, want));
    }
    std::printf("[taxel_reconstruct] F %.1f: worst error %.2f of the bound\n", F, worst);
  }
}

// The default scene through the FPGA chain: every frame's taxel values
// (without ghost correction) within the bound of golden taxel_g of the same
// magnitudes; a single touch's value equals 2^15 g of its truth within the
// same bound plus the magnitude's own error (checked in dtmf_chain_test).
TEST(TaxelReconstructHls, DefaultSceneFramesWithinTheBound) {
  using S = hls::DtmfChainSizes<3, 3, 32>;
  const auto sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  auto spec = sim::dtmf_top_spec(sc);
  spec.ghost = false;
  const auto plan = hls::make_dtmf_top_plan(spec);
  auto chain = std::make_unique<hls::DtmfChain<S>>(hls::chain_config<S>(plan));
  sim::WorldModel world(sc);
  const auto codes = world.all_codes();
  typename hls::DtmfChain<S>::Packet pk[hls::DtmfChain<S>::kMaxPackets];
  size_t frames = 0, lit = 0;
  for (size_t n = 0; n < codes.size(); ++n) {
    if (chain->push(uint16_t(codes[n] << 2), uint32_t(n), pk) == 0) continue;
    ++frames;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double mi = chain->magnitude(i), mj = chain->magnitude(3 + j);
        const double want = std::min(65535.0, 32768.0 * std::sqrt(mi * mj) / plan.full_mag);
        const double got = chain->taxel(i * 3 + j);
        ASSERT_LE(std::fabs(got - want), bound(mi, mj, plan.full_mag, want)) << n;
        lit += got > 1638;  // > 0.05 of a full carrier
      }
  }
  EXPECT_EQ(frames, 600u);
  EXPECT_GT(lit, 300u);
}

TEST(TaxelReconstructHls, ConfigErrorsNameTheField) {
  hls::TaxelReconstruct<3, 3> k;
  const char* bad = nullptr;
  hls::TaxelReconstructConfig c = config_for(9929.7, 3, 3);
  c.rows = 4;
  EXPECT_FALSE(k.configure(c, &bad));
  EXPECT_STREQ(bad, "rows (expected 1..R_MAX)");
  c.rows = 3;
  c.recip = 40000;
  EXPECT_FALSE(k.configure(c, &bad));
  EXPECT_STREQ(bad, "recip (expected 1..32767)");
  c.recip = 100;
  EXPECT_TRUE(k.configure(c, &bad));
}

}  // namespace
