// hls/carrier_demix.h (+ its host-side builder) against the golden
// least-squares demixing (host/golden/carrier_demix.h, Eigen SVD) and
// against physics (a lone tone must not leak into the other carriers).
//
// Bounds (derived in docs/carrier_demix.md, computed per frame here):
//  * Builder: cond(G) equals the golden kappa^2 (G = B^T B has the squared
//    condition of B) to 1e-6 relative; each coefficient is within
//    2^-(CF+1) (its rounding) + 1e-6 (frequency quantisation of the 32-bit
//    increments, |dw| <= 2 pi 2^-33, moves G by < N^2 |dw| ~ 1e-7) of the
//    golden (N/2) G^{-1} / gains.
//  * Kernel on given sums: with b_ref = the same integer sums rotated in
//    double by the exact phase of the oldest sample and y_ref = M b_ref
//    (M = golden (N/2) G^{-1} / sum_gain), each output component obeys
//      |y - y_ref|_i <= 1/2                          (output rounding)
//                     + 2^-(CF+1) sum_j |b_j|         (coefficient rounding)
//                     + 1e-6 sum_j |b_j|              (increment quantisation)
//                     + sum_j |M_ij| / G_r e_j        (rotation error)
//    with e_j <= |acc_c| (pi / 2^TW + sqrt(2) 0.5 / A) + sqrt(2)/2 for the
//    sums of carrier c (table index rounding moves the angle by <= pi/2^TW,
//    table entries are rounded to 1/2 LSB of A = 2^(SW-1)-1, each component
//    is rounded once) and e = 1/2 for DC (exact cos 0 = A, sin 0 = 0).
//  * End to end (default scene, hls sdft_bank -> carrier_demix vs golden
//    LsDemix): as above with b_ref the TRUE window sums, plus sdft_bank's own
//    error E per sum (its derived bound, sdft_amplitude_error_bound * N/2)
//    pushed through |M|: sum_j |M_ij| / (G_s G_r) (G_r E + e_j).
//    Magnitudes: |(2/N)|y_k| - golden_k| <= (2/N) sqrt(err_2k^2 + err_2k+1^2).
#include "hls/carrier_demix.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <random>
#include <type_traits>
#include <vector>

#include "hls/carrier_demix_config.h"
#include "hls/dtmf_chain.h"
#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "host/golden/carrier_demix.h"
#include "host/golden/sdft_bank.h"
#include "sim/scene.h"
#include "sim/world_model.h"

namespace {

using eskin::hls::CarrierDemix;
using eskin::hls::SdftBank;

constexpr double kFs = 35000;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};
constexpr int kN = 32, kK = 6, kDim = 2 * kK + 1;
using Demix = CarrierDemix<kK, kN>;   // ACC_W 24, OUT_W 24, TW 10, SW 16, CW 16, CF 14
using Bank = SdftBank<kK + 1, kN>;    // 6 carriers + DC channel, XW 13, CW 16
const double kGs = (std::ldexp(1.0, 15) - 1) / std::ldexp(1.0, 15);  // sdft_bank gain
const double kGr = kGs;  // demix rotation gain, SW = 16: same Q1.15 amplitude
const double kA = std::ldexp(1.0, 15) - 1;
const double kPi = 3.14159265358979323846;

Demix::Config build(const std::vector<double>& f, eskin::hls::CarrierDemixStatus* st_out = nullptr) {
  Demix::Config cfg;
  const auto st = eskin::hls::make_carrier_demix_config<Demix>(f, kFs, kGs, cfg);
  EXPECT_TRUE(st.ok) << st.message;
  if (st_out) *st_out = st;
  return cfg;
}

Bank::Config bank_config(const std::vector<double>& f) {
  Bank::Config cfg;
  EXPECT_TRUE(eskin::hls::make_sdft_bank_config<Bank>(f, kFs, cfg).ok());
  cfg.inc[cfg.carriers] = 0;  // the DC channel: a "carrier" at 0 Hz
  cfg.carriers += 1;
  return cfg;
}

TEST(CarrierDemixConfig, ConditioningAndCoefficientsMatchGolden) {
  eskin::hls::CarrierDemixStatus st;
  const Demix::Config cfg = build(kThesis, &st);
  eskin::golden::CarrierDemix golden(kThesis, kFs, kN, false);
  const double kappa2 = golden.condition_number() * golden.condition_number();
  EXPECT_NEAR(st.condition, kappa2, 1e-6 * kappa2);
  const Eigen::MatrixXd m = golden.normal_inverse() * (kN / 2.0) / (kGs * kGr);
  for (int i = 0; i < kDim; ++i)
    for (int j = 0; j < kDim; ++j)
      ASSERT_LE(std::fabs(std::ldexp(double(cfg.coef[i * kDim + j]), -14) - m(i, j)),
                std::ldexp(1.0, -15) + 1e-6)
          << i << "," << j;
  // The feasibility figures of docs/carrier_demix.md.
  std::printf("thesis carriers, N = 32: cond(G) = %.4f, max|M| = %.4f, ||M||_inf = %.4f\n",
              st.condition, st.max_coef, st.row_norm);
  RecordProperty("condition_number", std::to_string(st.condition));
  EXPECT_LT(st.max_coef, 2.0);  // fits Q2.14 (CW 16, CF 14)
}

TEST(CarrierDemixConfig, ErrorsNameTheField) {
  Demix::Config cfg;
  const auto msg = [&](const std::vector<double>& f) {
    return eskin::hls::make_carrier_demix_config<Demix>(f, kFs, kGs, cfg).message;
  };
  EXPECT_EQ(msg({}).rfind("carriers:", 0), 0u);
  EXPECT_EQ(msg({1, 2, 3, 4, 5, 6, 7}).rfind("carriers:", 0), 0u);
  EXPECT_EQ(msg({1900, 20000}).rfind("carriers[1]:", 0), 0u);
  // Two carriers 100 Hz apart with a 1094 Hz bin: hopeless conditioning.
  const std::string close = msg({5000, 5100});
  EXPECT_EQ(close.rfind("coef[", 0), 0u) << close;
  EXPECT_NE(close.find("condition number"), std::string::npos);
  using Small = CarrierDemix<6, 12>;
  Small::Config scfg;
  const auto st = eskin::hls::make_carrier_demix_config<Small>(kThesis, kFs, kGs, scfg);
  EXPECT_EQ(st.message.rfind("decoder.window:", 0), 0u) << st.message;
}

// Per-component bound on |y - M b| for one frame (see the file header).
// acc: the K+1 input sums; extra: per-sum error already in them (0, or E).
std::vector<double> component_bound(const Eigen::MatrixXd& m_true,
                                    const std::vector<std::complex<double>>& acc,
                                    const std::vector<double>& b_abs, double extra) {
  std::vector<double> e(static_cast<size_t>(kDim));
  for (int c = 0; c < kK; ++c) {
    const double rot = std::abs(acc[size_t(c)]) * (kPi / 1024 + std::sqrt(2.0) * 0.5 / kA) +
                       std::sqrt(2.0) / 2;
    e[size_t(2 * c)] = e[size_t(2 * c + 1)] = kGr * extra + rot;
  }
  e[size_t(2 * kK)] = kGr * extra + 0.5;
  double sum_b = 0;
  for (double v : b_abs) sum_b += v;
  std::vector<double> out(static_cast<size_t>(kDim));
  for (int i = 0; i < kDim; ++i) {
    double s = 0.5 + (std::ldexp(1.0, -15) + 1e-6) * sum_b;
    for (int j = 0; j < kDim; ++j) s += std::fabs(m_true(i, j)) / (kGs * kGr) * e[size_t(j)];
    out[size_t(i)] = s;
  }
  return out;
}

// Runs xs through hls sdft_bank -> carrier_demix; calls check(n, sums, out).
template <class Check>
void run_pipeline(const std::vector<double>& f, const std::vector<int32_t>& xs, Check check) {
  Bank bank;
  ASSERT_TRUE(bank.configure(bank_config(f)));
  Demix demix;
  ASSERT_TRUE(demix.configure(build(f)));
  Bank::Token sums[kK + 1];
  Demix::Token out[kK];
  for (size_t n = 0; n < xs.size(); ++n) {
    ASSERT_EQ(bank.push(xs[n], sums), kK + 1);
    int got = 0;
    for (int k = 0; k <= kK; ++k) {
      const Demix::Token in{sums[k].k, sums[k].re, sums[k].im, sums[k].last};
      got = demix.push(in, out);
      if (k < kK) {
        ASSERT_EQ(got, 0);
      }
    }
    ASSERT_EQ(got, kK);
    for (int k = 0; k < kK; ++k) {
      ASSERT_EQ(out[k].k, k);
      ASSERT_EQ(out[k].last, k == kK - 1);
    }
    check(n, sums, out);
  }
}

std::vector<int32_t> multitone(uint64_t seed, int len, double amp_max, double noise) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> amp(6), ph(6);
  for (int k = 0; k < 6; ++k) amp[size_t(k)] = amp_max * u(rng), ph[size_t(k)] = 2 * kPi * u(rng);
  const double dc = 20 * (u(rng) - 0.5);
  std::vector<int32_t> xs;
  for (int n = 0; n < len; ++n) {
    double v = dc + noise * (u(rng) - 0.5);
    for (int k = 0; k < 6; ++k)
      v += amp[size_t(k)] * std::cos(2 * kPi * kThesis[size_t(k)] / kFs * n + ph[size_t(k)]);
    xs.push_back(int32_t(std::lround(std::clamp(v, -4096.0, 4095.0))));
  }
  return xs;
}

TEST(CarrierDemix, KernelMatchesDoubleDemixOfTheSameSums) {
  eskin::golden::CarrierDemix golden(kThesis, kFs, kN, false);
  const Eigen::MatrixXd m_true = golden.normal_inverse() * (kN / 2.0);
  const Bank::Config bcfg = bank_config(kThesis);
  const auto xs = multitone(5, 30000, 600, 300);
  double worst_ratio = 0;
  run_pipeline(kThesis, xs, [&](size_t n, const Bank::Token* sums, const Demix::Token* out) {
    std::vector<std::complex<double>> acc(static_cast<size_t>(kK + 1));
    Eigen::VectorXd b(kDim);
    std::vector<double> b_abs(static_cast<size_t>(kDim));
    for (int c = 0; c <= kK; ++c) {
      acc[size_t(c)] = {double(sums[c].re), double(sums[c].im)};
      const uint32_t theta = uint32_t(uint64_t(n) + 1 - kN) * bcfg.inc[c];  // oldest sample
      const std::complex<double> p =
          acc[size_t(c)] * std::polar(1.0, 2 * kPi * std::ldexp(double(theta), -32));
      if (c < kK) b[2 * c] = p.real(), b[2 * c + 1] = -p.imag();
      else b[2 * kK] = p.real();
    }
    for (int j = 0; j < kDim; ++j) b_abs[size_t(j)] = std::fabs(b[j]) + 1;
    const Eigen::VectorXd y_ref = m_true * b / kGs;
    const auto bound = component_bound(m_true, acc, b_abs, 0.0);
    for (int k = 0; k < kK; ++k) {
      const double e_re = std::fabs(out[k].re - y_ref[2 * k]);
      const double e_im = std::fabs(out[k].im + y_ref[2 * k + 1]);
      ASSERT_LE(e_re, bound[size_t(2 * k)]) << "sample " << n << " carrier " << k;
      ASSERT_LE(e_im, bound[size_t(2 * k + 1)]) << "sample " << n << " carrier " << k;
      worst_ratio = std::max({worst_ratio, e_re / bound[size_t(2 * k)],
                              e_im / bound[size_t(2 * k + 1)]});
    }
  });
  std::printf("kernel vs double demix of the same sums: worst error / bound = %.3f\n",
              worst_ratio);
}

// The K + 1 window sums of a sample as complex values (the last is the DC
// sum), and per demix input component the magnitude bound |sum| + 1 that
// component_bound() scales its rounding terms by.
void demix_inputs(const Bank::Token* sums, std::vector<std::complex<double>>& acc,
                  std::vector<double>& b_abs) {
  acc.assign(size_t(kK + 1), {});
  b_abs.assign(size_t(kDim), 0.0);
  for (int c = 0; c <= kK; ++c) {
    acc[size_t(c)] = {double(sums[c].re), double(sums[c].im)};
    const double a = std::abs(acc[size_t(c)]) + 1;
    if (c < kK) b_abs[size_t(2 * c)] = b_abs[size_t(2 * c + 1)] = a;
    else b_abs[size_t(2 * kK)] = a;
  }
}

// Sum-domain error of sdft_bank per sum, from its derived amplitude bound.
double sdft_sum_error(double xmax) {
  return eskin::hls::sdft_amplitude_error_bound(eskin::hls::SdftWidths{}, xmax) * kN / 2;
}

TEST(CarrierDemix, DefaultSceneMatchesGoldenLsDemix) {
  const auto scene = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  ASSERT_EQ(scene.skin.carriers(), kK);
  ASSERT_EQ(scene.decoder.window, kN);
  const auto freqs = scene.skin.carrier_freqs_hz();
  eskin::sim::WorldModel world(scene);
  const std::vector<int> codes = world.all_codes();
  const int mid = int(std::lround(scene.skin.adc.mid_code()));
  std::vector<int32_t> xs;
  int32_t xmax = 0;
  for (int c : codes) xs.push_back(c - mid), xmax = std::max(xmax, std::abs(c - mid));
  eskin::DecoderConfig dec = scene.decoder;
  dec.variant = eskin::DftVariant::LsDemix;
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::LsDemix, freqs, kFs, dec);
  eskin::golden::CarrierDemix gd(freqs, kFs, kN, false);
  const Eigen::MatrixXd m_true = gd.normal_inverse() * (kN / 2.0);
  const double e_sdft = sdft_sum_error(xmax);
  double max_err = 0, max_amp = 0, max_bound = 0;
  run_pipeline(freqs, xs, [&](size_t n, const Bank::Token* sums, const Demix::Token* out) {
    golden->push(double(xs[n]));
    std::vector<std::complex<double>> acc;
    std::vector<double> b_abs;
    demix_inputs(sums, acc, b_abs);
    const auto bound = component_bound(m_true, acc, b_abs, e_sdft);
    for (int k = 0; k < kK; ++k) {
      const double mag = 2.0 / kN * std::hypot(double(out[k].re), double(out[k].im));
      const double err = std::fabs(mag - golden->magnitude(k));
      const double lim =
          2.0 / kN * std::hypot(bound[size_t(2 * k)], bound[size_t(2 * k + 1)]) + 1e-6;
      max_err = std::max(max_err, err);
      max_bound = std::max(max_bound, lim);
      max_amp = std::max(max_amp, golden->magnitude(k));
      ASSERT_LE(err, lim) << "sample " << n << " carrier " << k;
    }
  });
  std::printf("default scene: max |hls demix - golden LsDemix| = %.4f LSB (bound <= %.3f), "
              "largest amplitude %.1f LSB\n", max_err, max_bound, max_amp);
  RecordProperty("max_abs_error_lsb", std::to_string(max_err));
  EXPECT_GT(max_amp, 5 * max_bound);  // not vacuous
}

// A lone tone on carrier 2 (5 kHz): without demixing its window sums leak
// into the other carriers (off-bin, rectangular window); the LS fit is exact
// for a signal in the model's span, so after demixing only the fixed-point
// error bounded above remains.
TEST(CarrierDemix, LoneToneDoesNotLeak) {
  const double amp = 1500;
  std::vector<int32_t> xs;
  for (int n = 0; n < 4000; ++n)
    xs.push_back(int32_t(std::lround(amp * std::cos(2 * kPi * 5000 / kFs * n + 0.7))));
  eskin::golden::CarrierDemix gd(kThesis, kFs, kN, false);
  const Eigen::MatrixXd m_true = gd.normal_inverse() * (kN / 2.0);
  const double e_sdft = sdft_sum_error(amp);
  double leak_raw = 0, leak_demixed = 0, worst_ratio = 0, own = 0;
  run_pipeline(kThesis, xs, [&](size_t n, const Bank::Token* sums, const Demix::Token* out) {
    if (n < kN) return;  // window not full yet
    std::vector<std::complex<double>> acc;
    std::vector<double> b_abs;
    demix_inputs(sums, acc, b_abs);
    const auto bound = component_bound(m_true, acc, b_abs, e_sdft);
    for (int k = 0; k < kK; ++k) {
      const double raw = 2.0 / kN * std::abs(acc[size_t(k)]);
      const double dm = 2.0 / kN * std::hypot(double(out[k].re), double(out[k].im));
      if (k == 2) {
        own = std::max(own, dm);
        continue;
      }
      const double lim = 2.0 / kN * std::hypot(bound[size_t(2 * k)], bound[size_t(2 * k + 1)]);
      leak_raw = std::max(leak_raw, raw);
      leak_demixed = std::max(leak_demixed, dm);
      worst_ratio = std::max(worst_ratio, dm / lim);
      ASSERT_LE(dm, lim) << "sample " << n << " carrier " << k;
    }
  });
  std::printf("lone 5 kHz tone, A = %.0f: largest leak into another carrier %.1f LSB raw, "
              "%.2f LSB demixed (worst / bound %.3f); own amplitude %.1f\n",
              amp, leak_raw, leak_demixed, worst_ratio, own);
  EXPECT_GT(leak_raw, 0.05 * amp);  // the problem exists without demixing
  EXPECT_NEAR(own, amp, 0.01 * amp);
}

// The limit of demixing: the model assumes the nominal frequencies, so an
// oscillator off by `drift` leaves a residual. Prints the drift table of
// docs/carrier_demix.md (fixed-point pipeline, lone tones of 1500 LSB on
// each carrier in turn). Asserted: no drift => the fixed-point bound above
// (< 1% here); the residual grows with drift; at 0.5% demixing still beats
// the plain sums by more than 4x.
TEST(CarrierDemix, OscillatorDriftLimitsTheGain) {
  const double amp = 1500;
  const double drifts[] = {0.0, 0.005, 0.015, 0.035};
  double prev = -1, raw_at[4] = {}, dm_at[4] = {};
  for (int d = 0; d < 4; ++d) {
    double leak_raw = 0, leak_dm = 0;
    for (int c = 0; c < kK; ++c) {
      std::vector<int32_t> xs;
      const double f = kThesis[size_t(c)] * (1 + drifts[d]);
      for (int n = 0; n < 400; ++n)
        xs.push_back(int32_t(std::lround(amp * std::cos(2 * kPi * f / kFs * n + 0.3 * c))));
      run_pipeline(kThesis, xs, [&](size_t n, const Bank::Token* sums, const Demix::Token* out) {
        if (n < kN) return;
        for (int k = 0; k < kK; ++k) {
          if (k == c) continue;
          leak_raw = std::max(leak_raw, 2.0 / kN * std::hypot(double(sums[k].re), double(sums[k].im)));
          leak_dm = std::max(leak_dm, 2.0 / kN * std::hypot(double(out[k].re), double(out[k].im)));
        }
      });
    }
    raw_at[d] = leak_raw / amp;
    dm_at[d] = leak_dm / amp;
    std::printf("drift %.1f%%: largest leak plain %.1f%%, demixed %.2f%%\n", 100 * drifts[d],
                100 * raw_at[d], 100 * dm_at[d]);
    EXPECT_GT(dm_at[d], prev);
    prev = dm_at[d];
  }
  EXPECT_LT(dm_at[0], 0.01);
  EXPECT_LT(4 * dm_at[1], raw_at[1]);
}

// ---- The 64-bit accumulation at the extreme ---------------------------------
// K = 128 carriers (the most CarrierDemix takes: a 64x64 skin), the largest
// token values, table entries and coefficients the number formats allow,
// against the same arithmetic evaluated here in __int128 from the header's
// formats (floor divisions, not the kernel's shifts or code).
//
// Bound. A carrier's token (re, im), |re|, |im| <= 2^(ACC_W-1), rotated by
// (c, s), |c|, |s| <= 2^(SW-1) (any SW-bit table entry), gives
//   |b_2k| + |b_2k+1| = max(|pr + pi|, |pr - pi|) / 2^(SW-1) + rounding
//                    <= 2^(ACC_W-1) (|c + s| + |c - s|) / 2^(SW-1) + 1
//                    <= 2^ACC_W + 1,
// and the DC sum |b_2K| <= 2^ACC_W; with |coef| <= 2^(CW-1):
//   |acc_i| <= 2^(CW-1) (K + 1) (2^ACC_W + 1),
// and 2^(CW-1) ((K + 1) 2^ACC_W - (2K + 1)) is reached (every sum at the
// end of its range, a row's coefficients all most negative): for K = 128 at the
// widest formats (ACC_W 32, CW 18) 129 2^49 ~ 2^56.01, a 58-bit signed sum,
// inside int64 (the header's coarser bound: 257 terms < 2^(ACC_W+CW) each,
// < 2^59). At DtmfChain<64x64, N 512>'s formats (ACC_W 22, CW 16):
// 129 2^37 ~ 2^44.01.
//
// The frames: two that drive every sum to the end of its range (all low,
// all high), then random extremes and random tokens. The rows: all most
// negative, all most positive, alternating, random extremes, random, and
// "boundary" rows whose last two coefficients (set_coef before each frame,
// against two small sums, 256 and 1) put the exact sum on a rounding
// boundary of the output (acc = 2^(CF-1) or 2^(CF-1) - 1 mod 2^CF), so an
// error of 1 anywhere in the sum changes the output.
// The test checks that it can fail: the same rows summed in 32 bits, in one
// bit fewer than the bound needs (wrapping), and (where the bound exceeds
// 2^53) in double give outputs that differ from the exact ones.
using I128 = __int128;

I128 floor_div_pow2(I128 a, int sh) {
  const I128 d = I128(1) << sh;
  I128 q = a / d;
  if (a % d != 0 && a < 0) --q;
  return q;
}

template <int K, int N, int ACC_W, int OUT_W, int TW, int SW, int CW, int CF>
void extreme_accumulation(uint32_t seed) {
  using D = CarrierDemix<K, N, ACC_W, OUT_W, TW, SW, CW, CF>;
  constexpr int dim = 2 * K + 1, Q = 1 << (TW - 2);
  static_assert(CF - 8 <= CW - 1, "boundary rows: (2^CF - 1) >> 8 must fit a coefficient");
  std::mt19937_64 rng(seed);
  const int64_t M = int64_t(1) << (SW - 1);
  const int64_t lo = -(int64_t(1) << (ACC_W - 1)), hi = (int64_t(1) << (ACC_W - 1)) - 1;
  const int64_t cmin = -(int64_t(1) << (CW - 1)), cmax = (int64_t(1) << (CW - 1)) - 1;
  const I128 ymax = (I128(1) << (OUT_W - 1)) - 1, ymin = -ymax - 1;
  const auto sat = [&](I128 v) { return v > ymax ? ymax : (v < ymin ? ymin : v); };
  const auto y_of = [&](I128 acc) { return sat(floor_div_pow2(acc + (I128(1) << (CF - 1)), CF)); };

  // Quadrant phases only: carrier k starts at quadrant k % 4 and advances
  // (k / 4) % 4 quadrants a frame. The quarter-wave table's two entries
  // those phases read are the most negative SW-bit value, so every rotation
  // product is as large as the format allows (the kernel takes any SW-bit
  // table; sin(m pi/2) = qsin[0], qsin[Q], -qsin[0], -qsin[Q] for m = 0..3).
  auto cfg = std::make_unique<typename D::Config>();
  cfg->carriers = K;
  for (int k = 0; k < K; ++k)
    cfg->phase0[k] = uint32_t(k % 4) << 30, cfg->inc[k] = uint32_t((k / 4) % 4) << 30;
  cfg->qsin[0] = int32_t(-M), cfg->qsin[Q] = int32_t(-M);
  const auto sin_q = [&](int m) -> int64_t {
    const int64_t t[4] = {cfg->qsin[0], cfg->qsin[Q], -int64_t(cfg->qsin[0]), -int64_t(cfg->qsin[Q])};
    return t[m & 3];
  };
  const auto rotate = [&](int64_t re, int64_t im, int m, I128& b0, I128& b1) {
    const I128 c = sin_q(m + 1), s = sin_q(m), half = I128(1) << (SW - 2);
    b0 = floor_div_pow2(I128(re) * c - I128(im) * s + half, SW - 1);
    b1 = -floor_div_pow2(I128(re) * s + I128(im) * c + half, SW - 1);
  };

  // The trim slots of the boundary rows: carriers K-2 (sums +-256) and K-1
  // (sums +-1) on every frame from frame 2.
  const int j1 = 2 * (K - 2), j2 = 2 * (K - 1);
  std::vector<int64_t> coef(size_t(dim) * dim);
  std::uniform_int_distribution<int64_t> any_coef(cmin, cmax);
  for (int i = 0; i < dim; ++i)
    for (int j = 0; j < dim; ++j) {
      int64_t& v = coef[size_t(i) * dim + j];
      switch (i % 6) {
        case 0: v = cmin; break;
        case 1: v = cmax; break;
        case 2: v = j % 2 ? cmax : cmin; break;
        case 4: v = any_coef(rng); break;
        default: v = rng() % 2 ? cmax : cmin; break;  // 3, and 5 (boundary)
      }
    }
  for (size_t n = 0; n < coef.size(); ++n) cfg->coef[n] = int32_t(coef[n]);
  auto dm = std::make_unique<D>();
  ASSERT_TRUE(dm->configure(*cfg));

  const int64_t extremes[] = {lo, hi, lo + 1, hi - 1, 0, -1, 1};
  std::uniform_int_distribution<int64_t> any_tok(lo, hi);
  const auto extreme = [&]() { return rng() % 8 == 7 ? any_tok(rng) : extremes[rng() % 7]; };
  const int frames = 10;
  I128 max_acc = 0;
  bool differs_32 = false, differs_wrap = false, differs_double = false;
  int saturated = 0, unsaturated_large = 0, boundary_rows = 0;
  const int wrap_bits = ACC_W + CW + 7;  // one bit fewer than the bound's sums need
  for (int f = 0; f < frames; ++f) {
    std::vector<int64_t> re(K + 1), im(K + 1);
    std::vector<I128> b(dim);
    for (int k = 0; k <= K; ++k) {
      const int m = k < K ? int((cfg->phase0[k] >> 30) + uint32_t(f) * (cfg->inc[k] >> 30)) & 3 : 0;
      if (f < 2) {  // every sum at the end of its range: frame 0 low, frame 1 high
        I128 best = 0;
        bool first = true;
        for (int64_t r : {lo, hi})
          for (int64_t q : {lo, hi}) {
            I128 b0, b1;
            rotate(r, q, m, b0, b1);
            const I128 v = k < K ? b0 + b1 : b0;
            if (first || (f == 0 ? v < best : v > best)) best = v, re[k] = r, im[k] = q, first = false;
          }
      } else if (k == K - 2 || k == K - 1) {
        re[k] = k == K - 2 ? 256 : 1, im[k] = 0;
      } else if (f < 8) {
        re[k] = extreme(), im[k] = extreme();
      } else {
        re[k] = any_tok(rng), im[k] = any_tok(rng);
      }
      I128 b0, b1;
      rotate(re[k], im[k], m, b0, b1);
      if (k < K) b[2 * k] = b0, b[2 * k + 1] = b1;
      else b[2 * K] = b0;
    }
    if (f >= 2) {  // the boundary rows' trims for this frame's sums
      ASSERT_TRUE((b[j1] == 256 || b[j1] == -256) && (b[j2] == 1 || b[j2] == -1)) << "frame " << f;
      for (int i = 5; i < dim; i += 6) {
        I128 rest = 0;
        for (int j = 0; j < dim; ++j)
          if (j != j1 && j != j2) rest += I128(coef[size_t(i) * dim + j]) * b[j];
        const I128 target = (I128(1) << (CF - 1)) - (i / 6) % 2, mod = I128(1) << CF;
        const I128 d = ((target - rest) % mod + mod) % mod;
        const int64_t c1 = int64_t(d >> 8) * (b[j1] > 0 ? 1 : -1);
        const int64_t c2 = int64_t(d & 255) * (b[j2] > 0 ? 1 : -1);
        coef[size_t(i) * dim + j1] = c1, coef[size_t(i) * dim + j2] = c2;
        ASSERT_TRUE(dm->set_coef(i * dim + j1, int32_t(c1)));
        ASSERT_TRUE(dm->set_coef(i * dim + j2, int32_t(c2)));
      }
    }
    // The exact outputs and those of the narrower sums.
    std::vector<I128> y(dim);
    for (int i = 0; i < dim; ++i) {
      I128 acc = 0;
      uint32_t acc32 = 0;
      double accd = 0;
      for (int j = 0; j < dim; ++j) {
        const I128 p = I128(coef[size_t(i) * dim + j]) * b[j];
        acc += p;
        acc32 += uint32_t(uint64_t(int64_t(p)));
        accd += double(int64_t(p));
      }
      y[i] = y_of(acc);
      max_acc = std::max(max_acc, acc < 0 ? -acc : acc);
      I128 wrapped = acc & ((I128(1) << wrap_bits) - 1);
      if (wrapped >= I128(1) << (wrap_bits - 1)) wrapped -= I128(1) << wrap_bits;
      differs_32 |= y_of(I128(int32_t(acc32))) != y[i];
      differs_wrap |= y_of(wrapped) != y[i];
      differs_double |= y_of(I128(int64_t(accd))) != y[i];
      if (y[i] == ymax || y[i] == ymin) ++saturated;
      else if ((acc < 0 ? -acc : acc) > (I128(1) << (ACC_W + CW + 3))) ++unsaturated_large;
      if (f >= 2 && i % 6 == 5) {
        ASSERT_EQ((acc % (I128(1) << CF) + (I128(1) << CF)) % (I128(1) << CF),
                  (I128(1) << (CF - 1)) - (i / 6) % 2);
        boundary_rows += y[i] != ymax && y[i] != ymin;
      }
    }
    // The kernel.
    typename D::Token out[K];
    for (int k = 0; k <= K; ++k) {
      const int n = dm->push(typename D::Token{uint8_t(k), int32_t(re[k]), int32_t(im[k]), k == K}, out);
      ASSERT_EQ(n, k == K ? K : 0) << "frame " << f << " token " << k;
    }
    for (int k = 0; k < K; ++k) {
      EXPECT_EQ(int(out[k].k), k) << "frame " << f;
      EXPECT_EQ(out[k].last, k == K - 1) << "frame " << f << " carrier " << k;
      EXPECT_EQ(int64_t(out[k].re), int64_t(y[2 * k])) << "frame " << f << " carrier " << k;
      EXPECT_EQ(int64_t(out[k].im), int64_t(sat(-y[2 * k + 1]))) << "frame " << f << " carrier " << k;
    }
    EXPECT_EQ(int64_t(dm->dc()), int64_t(y[2 * K])) << "frame " << f;
  }
  // The bound holds and the frames reach it (to within the rounding of
  // the sums at the ends of their ranges).
  const I128 bound = I128(-cmin) * (K + 1) * ((I128(1) << ACC_W) + 1);
  const I128 reached = I128(-cmin) * ((I128(K + 1) << ACC_W) - (2 * K + 1));
  EXPECT_LE(max_acc, bound);
  EXPECT_GE(max_acc, reached);
  EXPECT_GE(max_acc, I128(1) << (wrap_bits - 1)) << "a " << wrap_bits << "-bit sum would hold it";
  std::printf("K %d ACC_W %d CW %d: max |acc| = 2^%.4f (bound 2^%.4f), %d outputs saturated, "
              "%d unsaturated above 2^%d, %d boundary rows unsaturated\n",
              K, ACC_W, CW, std::log2(double(max_acc)), std::log2(double(bound)), saturated,
              unsaturated_large, ACC_W + CW + 3, boundary_rows);
  // The test tells the exact sum from narrower ones.
  EXPECT_TRUE(differs_32) << "no output tells a 32-bit sum from the exact one";
  EXPECT_TRUE(differs_wrap) << "no output tells a " << wrap_bits << "-bit sum from the exact one";
  if (double(bound) > std::ldexp(1.0, 53)) {
    EXPECT_TRUE(differs_double) << "no output tells a double sum from the exact one";
    EXPECT_GT(boundary_rows, 0);
  }
}

TEST(CarrierDemix, Exact64BitSumsAt128CarriersWidestFormats) {
  // ACC_W 32, OUT_W 32, TW 10, SW 18, CW 18, CF 25: each the largest the
  // kernel's static_asserts allow.
  extreme_accumulation<128, 512, 32, 32, 10, 18, 18, 25>(1);
}

TEST(CarrierDemix, Exact64BitSumsAt128CarriersDtmfChain64x64) {
  // The demix DtmfChain instantiates for the 64x64 skin (N 512).
  static_assert(std::is_same_v<eskin::hls::DtmfChain<eskin::hls::DtmfChainSizes<64, 64, 512>>::Demix,
                               CarrierDemix<128, 512, 22, 24, 10, 16, 16, 14>>);
  extreme_accumulation<128, 512, 22, 24, 10, 16, 16, 14>(2);
}

}  // namespace
