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
#include <random>
#include <vector>

#include "hls/carrier_demix_config.h"
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

}  // namespace
