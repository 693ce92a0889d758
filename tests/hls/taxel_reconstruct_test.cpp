// hls/taxel_reconstruct.h against the golden model (host/golden/
// taxel_reconstruct.h) on random magnitudes and on the magnitude frames of
// the default scene (scenes/neuroskin2.yaml through the golden exact SDFT).
// Magnitude units in this test: the DFT window sum |sum x e^-jwn| = amp*N/2,
// rounded to an integer (MAG_W = 16, no shift); the golden model gets the
// same integers divided by F = full_carrier_lsb * N/2, so only the kernel's
// own arithmetic is compared.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "hls/isqrt.h"
#include "hls/taxel_reconstruct.h"
#include "hls/taxel_reconstruct_config.h"
#include "host/golden/sdft_bank.h"
#include "host/golden/taxel_reconstruct.h"
#include "sim/scene.h"
#include "sim/world_model.h"

using namespace eskin;
using hls::TaxelMode;

namespace {

using Kernel = hls::TaxelReconstruct<16, 16, 16, 32>;

struct Frame { std::vector<uint16_t> row, col; };

std::vector<Frame> random_frames(int rows, int cols, int n, uint32_t seed, int max_mag) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> mag(0, max_mag);
  std::vector<Frame> f{size_t(n)};
  for (auto& fr : f) {
    for (int i = 0; i < rows; ++i) fr.row.push_back(uint16_t(mag(rng)));
    for (int j = 0; j < cols; ++j) fr.col.push_back(uint16_t(mag(rng)));
  }
  return f;
}

// Default scene -> per-sample magnitude frames (every `hop`-th sample).
std::vector<Frame> scene_frames(const sim::Scene& sc, int hop, double& full_mag) {
  sim::WorldModel world(sc);
  auto codes = world.all_codes();
  auto bank = golden::make_sdft_bank(DftVariant::Exact, sc.skin.carrier_freqs_hz(),
                                     sc.skin.adc.rate_hz, sc.decoder);
  const double half_n = sc.decoder.window / 2.0;
  full_mag = sc.skin.full_carrier_lsb() * half_n;
  std::vector<Frame> out;
  for (size_t n = 0; n < codes.size(); ++n) {
    bank->push(codes[n] - sc.skin.adc.mid_code());
    if (!bank->full() || n % size_t(hop)) continue;
    Frame f;
    for (int k = 0; k < bank->carriers(); ++k) {
      const uint16_t m = uint16_t(std::lround(bank->magnitude(k) * half_n));
      (k < sc.skin.rows ? f.row : f.col).push_back(m);
    }
    out.push_back(f);
  }
  return out;
}

// Run one frame through the kernel; returns its taxels as a dense matrix
// (-1 where no token was emitted) and checks the token order and `last`.
std::vector<std::vector<int64_t>> run(Kernel& k, const Frame& f) {
  const int R = int(f.row.size()), C = int(f.col.size());
  for (int i = 0; i < R + C; ++i) {
    const bool closed = k.push({uint8_t(i), i < R ? f.row[size_t(i)] : f.col[size_t(i - R)]});
    EXPECT_EQ(closed, i == R + C - 1);
  }
  std::vector<std::vector<int64_t>> t(size_t(R), std::vector<int64_t>(size_t(C), -1));
  hls::TaxelToken tok;
  int n = 0, prev = -1;
  while (k.pop(tok)) {
    EXPECT_GT(tok.row * C + tok.col, prev) << "row-major order";
    prev = tok.row * C + tok.col;
    t[tok.row][tok.col] = tok.value;
    ++n;
    EXPECT_EQ(tok.last, k.pending() == 0);
  }
  EXPECT_EQ(n, k.active_rows() * k.active_cols());
  return t;
}

Eigen::VectorXd vec(const std::vector<uint16_t>& v, double scale) {
  Eigen::VectorXd x(Eigen::Index(v.size()));
  for (size_t i = 0; i < v.size(); ++i) x[Eigen::Index(i)] = v[i] / scale;
  return x;
}

hls::TaxelReconstructConfig base(int rows, int cols, TaxelMode mode) {
  hls::TaxelReconstructConfig c;
  c.rows = uint8_t(rows);
  c.cols = uint8_t(cols);
  c.mode = mode;
  return c;
}

// Bound on |g_hls - g_true| in UQ1.15 LSB: floor of the root loses < 1 input
// unit (32768/F LSB), the rounded reciprocal is off by <= 1/2 (r*0.5/2^s LSB
// for a root r < 2^16), the final rounding adds 1/2.
double g_bound(const hls::TaxelReconstructConfig& c, double full) {
  return 32768.0 / full + 65535.0 * 0.5 / std::ldexp(1.0, c.recip_shift) + 0.5;
}

}  // namespace

// isqrt = floor(sqrt(x)) exactly: checked on perfect squares and their
// neighbours (where a floor error would show) and on random radicands.
TEST(TaxelReconstructHls, IsqrtIsExactFloor) {
  for (uint64_t r = 0; r < 65536; r += 7) {
    const uint32_t sq = uint32_t(r * r);
    EXPECT_EQ(hls::isqrt<16>(sq), r);
    if (sq) { EXPECT_EQ(hls::isqrt<16>(sq - 1), r - 1); }
    if (r < 65535) { EXPECT_EQ(hls::isqrt<16>(uint32_t((r + 1) * (r + 1) - 1)), r); }
  }
  EXPECT_EQ(hls::isqrt<16>(0xFFFFFFFFu), 65535u);
  std::mt19937 rng(5);
  for (int n = 0; n < 200000; ++n) {
    const uint32_t x = rng();
    const uint64_t r = hls::isqrt<16>(x);
    ASSERT_TRUE(r * r <= x && (r + 1) * (r + 1) > x) << x;
  }
}

// Product form, no shift, TAX_W = 32: the integer product of two 16-bit
// magnitudes is < 2^32, so the kernel must equal golden's (exact in double
// below 2^53) bit for bit, on random frames of several sizes.
TEST(TaxelReconstructHls, ProductIsExact) {
  for (int size : {3, 10, 16}) {
    Kernel k;
    ASSERT_TRUE(k.configure(base(size, size, TaxelMode::Product)));
    for (const auto& f : random_frames(size, size, 200, uint32_t(size), 65535)) {
      auto t = run(k, f);
      auto gold = golden::taxel_product(vec(f.row, 1.0), vec(f.col, 1.0));
      for (int i = 0; i < size; ++i)
        for (int j = 0; j < size; ++j) ASSERT_EQ(double(t[size_t(i)][size_t(j)]), gold(i, j));
    }
  }
}

// Product form with shift s into TAX_W = 16: round half up gives |v - P/2^s|
// <= 1/2 unless P/2^s exceeds the 16-bit range, where v saturates at 65535.
TEST(TaxelReconstructHls, ProductShiftRoundsAndSaturates) {
  hls::TaxelReconstruct<4, 4, 16, 16> k;
  auto c = base(4, 4, TaxelMode::Product);
  c.shift = 14;
  ASSERT_TRUE(k.configure(c));
  int saturated = 0;
  for (const auto& f : random_frames(4, 4, 500, 9, 65535)) {
    for (int i = 0; i < 8; ++i) k.push({uint8_t(i), i < 4 ? f.row[size_t(i)] : f.col[size_t(i - 4)]});
    hls::TaxelToken tok;
    while (k.pop(tok)) {
      const double exact = double(f.row[tok.row]) * f.col[tok.col] / 16384.0;
      if (exact >= 65535.5) { EXPECT_EQ(tok.value, 65535u); ++saturated; }
      else EXPECT_LE(std::abs(double(tok.value) - exact), 0.5);
    }
  }
  EXPECT_GT(saturated, 0);  // the saturation branch was exercised
}

// Activity mask: only rows and columns whose magnitude >= threshold are
// emitted, row-major; the emitted set must equal the crossings of golden's
// lines above the threshold (and the product there must still be exact).
TEST(TaxelReconstructHls, ActiveMaskSkipsIdleLines) {
  Kernel k;
  auto c = base(10, 10, TaxelMode::Product);
  c.active_threshold = 40000;
  ASSERT_TRUE(k.configure(c));
  int skipped = 0;
  for (const auto& f : random_frames(10, 10, 300, 11, 65535)) {
    auto t = run(k, f);
    auto gold = golden::taxel_product(vec(f.row, 1.0), vec(f.col, 1.0));
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) {
        const bool on = f.row[size_t(i)] >= 40000 && f.col[size_t(j)] >= 40000;
        skipped += !on;
        ASSERT_EQ(t[size_t(i)][size_t(j)], on ? int64_t(gold(i, j)) : -1);
      }
  }
  EXPECT_GT(skipped, 0);
}

// Conductance form vs golden taxel_g on random magnitudes: bound g_bound().
TEST(TaxelReconstructHls, ConductanceWithinQBound) {
  const double full = 8192.0 * 0.75;  // a full carrier = 6144 input units
  Kernel k;
  auto c = base(5, 7, TaxelMode::Conductance);
  hls::set_full_carrier(full, c);
  ASSERT_TRUE(k.configure(c));
  const double bound = g_bound(c, full);
  double worst = 0;
  for (const auto& f : random_frames(5, 7, 400, 13, 12000)) {
    auto t = run(k, f);
    auto gold = golden::taxel_g(vec(f.row, full), vec(f.col, full));
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 7; ++j) {
        // saturation at 0xFFFF is 1-Lipschitz: the same bound holds after it
        const double want = std::min(65535.0, gold(i, j) * 32768.0);
        worst = std::max(worst, std::abs(t[size_t(i)][size_t(j)] - want));
      }
  }
  EXPECT_LE(worst, bound) << "bound " << bound;
}

// Pressure form on the default scene's frames vs golden taxel_pressure.
// Bound (in output LSB, p_lsb = 1/64 kPa):
//   S * (g_bound + 1/2)       g error and the breakpoints' g quantisation,
//                             S = steepest segment (output LSB per g LSB) of
//                             the curve or of the quantised table;
//   + 1/2 + 1/2 + seg/2^(ss+1) p quantisation, final rounding, slope rounding
//                             over the widest segment (seg g-LSB wide);
//   + chord                   the PWL table's own deviation from the curve,
//                             measured densely in double from golden's
//                             Conductance::inverse (not from the kernel).
// Taxels with g beyond the last breakpoint are clamped by design: skipped.
TEST(TaxelReconstructHls, PressureOnDefaultSceneWithinBound) {
  const auto sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  double full = 0;
  const auto frames = scene_frames(sc, 7, full);
  ASSERT_GT(frames.size(), 2000u);
  const Conductance& cond = sc.skin.conductance;
  const double p_lsb = 1.0 / 64.0, g_last = 0.75;
  double gp[16], pp[16];
  for (int s = 0; s < 16; ++s) {  // denser where the inverse is steep
    gp[s] = g_last * (1.0 - std::pow(1.0 - s / 15.0, 1.5));
    pp[s] = cond.inverse(gp[s]);
  }
  auto c = base(sc.skin.rows, sc.skin.cols, TaxelMode::Pressure);
  hls::set_full_carrier(full, c);
  hls::set_pwl(gp, pp, 16, p_lsb, c, 32);
  Kernel k;
  ASSERT_TRUE(k.configure(c));
  double S = 0, chord = 0, seg = 0;
  for (int s = 0; s < 15; ++s) {
    S = std::max(S, (pp[s + 1] - pp[s]) / p_lsb / ((gp[s + 1] - gp[s]) * 32768.0));
    // the quantised table's own slopes (builder output) may be a bit steeper
    S = std::max(S, c.slope[s] / std::ldexp(1.0, c.slope_shift));
    seg = std::max(seg, (gp[s + 1] - gp[s]) * 32768.0 + 1.0);
    for (int q = 0; q <= 200; ++q) {
      const double g = gp[s] + (gp[s + 1] - gp[s]) * q / 200.0;
      const double lin = pp[s] + (pp[s + 1] - pp[s]) * q / 200.0;
      chord = std::max(chord, std::abs(lin - cond.inverse(g)) / p_lsb);
    }
  }
  const double bound = S * (g_bound(c, full) + 0.5) + 1.0 +
                       seg / std::ldexp(1.0, c.slope_shift + 1) + chord;
  double worst = 0;
  int compared = 0;
  for (const auto& f : frames) {
    auto t = run(k, f);
    auto gg = golden::taxel_g(vec(f.row, full), vec(f.col, full));
    auto gold = golden::taxel_pressure(vec(f.row, full), vec(f.col, full), cond);
    for (int i = 0; i < sc.skin.rows; ++i)
      for (int j = 0; j < sc.skin.cols; ++j) {
        if (gg(i, j) > g_last - 0.01) continue;
        worst = std::max(worst, std::abs(t[size_t(i)][size_t(j)] - gold(i, j) / p_lsb));
        ++compared;
      }
  }
  EXPECT_GT(compared, 10000);
  EXPECT_LE(worst, bound) << "S " << S << " chord " << chord;
}

// Product form on the default scene's frames (every 3rd sample): exact, as on
// random frames (integer product < 2^32, exact in double).
TEST(TaxelReconstructHls, ProductExactOnDefaultScene) {
  const auto sc = sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  double full = 0;
  const auto frames = scene_frames(sc, 3, full);
  Kernel k;
  ASSERT_TRUE(k.configure(base(sc.skin.rows, sc.skin.cols, TaxelMode::Product)));
  for (const auto& f : frames) {
    auto t = run(k, f);
    auto gold = golden::taxel_product(vec(f.row, 1.0), vec(f.col, 1.0));
    for (int i = 0; i < sc.skin.rows; ++i)
      for (int j = 0; j < sc.skin.cols; ++j) ASSERT_EQ(double(t[size_t(i)][size_t(j)]), gold(i, j));
  }
}

// A Table conductance with <= 16 points has an exactly piecewise-linear
// inverse, so the chord term vanishes: bound S*(g_bound+1/2) + 1 + slope term.
TEST(TaxelReconstructHls, PressureExactTableWithinQBound) {
  Conductance cond;
  cond.kind = Conductance::Kind::Table;
  cond.table_p_kpa = {0, 10, 30, 60, 100, 200};
  cond.table_g = {0, 0.2, 0.45, 0.6, 0.7, 0.8};
  double gp[6], pp[6];
  for (int s = 0; s < 6; ++s) { gp[s] = cond.table_g[size_t(s)]; pp[s] = cond.table_p_kpa[size_t(s)]; }
  const double full = 5000.0, p_lsb = 1.0 / 128.0;
  auto c = base(6, 6, TaxelMode::Pressure);
  hls::set_full_carrier(full, c);
  hls::set_pwl(gp, pp, 6, p_lsb, c, 32);
  Kernel k;
  ASSERT_TRUE(k.configure(c));
  double S = 0, seg = 0;
  for (int s = 0; s < 5; ++s) {
    S = std::max(S, (pp[s + 1] - pp[s]) / p_lsb / ((gp[s + 1] - gp[s]) * 32768.0));
    // the quantised table's own slopes (builder output) may be a bit steeper
    S = std::max(S, c.slope[s] / std::ldexp(1.0, c.slope_shift));
    seg = std::max(seg, (gp[s + 1] - gp[s]) * 32768.0 + 1.0);
  }
  const double bound = S * (g_bound(c, full) + 0.5) + 1.0 + seg / std::ldexp(1.0, c.slope_shift + 1);
  double worst = 0;
  for (const auto& f : random_frames(6, 6, 400, 17, 4500)) {
    auto t = run(k, f);
    auto gold = golden::taxel_pressure(vec(f.row, full), vec(f.col, full), cond);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        worst = std::max(worst, std::abs(t[size_t(i)][size_t(j)] - gold(i, j) / p_lsb));
  }
  EXPECT_LE(worst, bound);
}

// Bad configuration is refused and names the field.
TEST(TaxelReconstructHls, RejectsBadConfigNamingField) {
  Kernel k;
  const char* why = nullptr;
  auto c = base(17, 3, TaxelMode::Product);
  EXPECT_FALSE(k.configure(c, &why));
  EXPECT_NE(std::string(why).find("rows"), std::string::npos);
  c = base(3, 3, TaxelMode::Pressure);
  c.g_tab[0] = 5;
  EXPECT_FALSE(k.configure(c, &why));
  EXPECT_NE(std::string(why).find("g_tab[0]"), std::string::npos);
  EXPECT_THROW(hls::set_full_carrier(0.0, c), std::invalid_argument);
}
