// Joint least-squares demixing (carrier_demix.h) and the LsDemix SdftBank
// variant: ground-truth recovery for the thesis carriers, identities with
// the DFT, DC removal, a 10^6-sample streaming run, and config errors.
// Expected values are built here from the signal's own parameters.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "host/golden/carrier_demix.h"
#include "host/golden/sdft_bank.h"

namespace eskin::golden {
namespace {

using cd = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kFs = 35000.0;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};

DecoderConfig cfg(int n, bool hann = false) {
  DecoderConfig c;
  c.window = n;
  c.hann = hann;
  return c;
}

double w_of(double f) { return 2.0 * M_PI * f / kFs; }

// The model is exact for a pure multi-tone at the carriers + DC, so LS
// returns it up to rounding: the windowed sums carry ~N*eps*max|x| and the
// normal inverse amplifies by at most kappa^2 (printed; ~10 here), i.e.
// ~1e-13 relative. 1e-6 relative is the required accuracy of the decoder;
// it also holds with amplitudes spread 30:1 (A >= 10, |x| up to ~1500).
TEST(CarrierDemix, RecoversThesisAmplitudesAndDc) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> amp(10.0, 300.0), phase(-M_PI, M_PI), dc(-50, 50);
  for (int n : {32, 64})
    for (bool hann : {false, true}) {
      CarrierDemix demix(kThesis, kFs, n, hann);
      std::printf("N=%d %s: condition number of the basis %.3f\n", n, hann ? "hann" : "rect",
                  demix.condition_number());
      for (int trial = 0; trial < 5; ++trial) {
        std::vector<double> a, phi;
        for (size_t k = 0; k < kThesis.size(); ++k) a.push_back(amp(rng)), phi.push_back(phase(rng));
        const double d = dc(rng);
        auto bank = make_sdft_bank(DftVariant::LsDemix, kThesis, kFs, cfg(n, hann));
        double worst = 0.0;
        for (long m = 0; m < 600; ++m) {
          double x = d;
          for (size_t k = 0; k < a.size(); ++k) x += a[k] * std::cos(w_of(kThesis[k]) * m + phi[k]);
          bank->push(x);
          if (!bank->full()) continue;
          const long s = m + 1 - n;  // oldest sample of the window
          for (int k = 0; k < 6; ++k) {
            cd want = std::polar(a[size_t(k)], w_of(kThesis[size_t(k)]) * s + phi[size_t(k)]);
            worst = std::max(worst, std::abs(bank->amplitude(k) - want) / a[size_t(k)]);
          }
          EXPECT_NEAR(bank->dc(), d, 1e-6 * 10.0);  // 1e-6 of the smallest amplitude
        }
        EXPECT_LT(worst, 1e-6) << "N=" << n << " hann=" << hann;
        if (trial == 0) std::printf("  max relative amplitude error %.3e\n", worst);
      }
    }
}

// Bin-centred carriers (plan_carriers) are orthogonal to each other and to
// DC over the window, so the LS fit IS the DFT: LsDemix equals Direct on any
// input (here noise) within O(N eps)*max|x| roundings: bound 1e-12*max|x|.
TEST(CarrierDemix, BinCentredCarriersReduceToTheDft) {
  const int n = 32;
  std::vector<double> f = plan_carriers(6, kFs, n);
  auto ls = make_sdft_bank(DftVariant::LsDemix, f, kFs, cfg(n));
  auto direct = make_sdft_bank(DftVariant::Direct, f, kFs, cfg(n));
  std::mt19937_64 rng(2);
  std::normal_distribution<double> noise(0.0, 200.0);
  double max_x = 0.0, worst = 0.0;
  for (int m = 0; m < 3000; ++m) {
    double x = noise(rng);
    max_x = std::max(max_x, std::fabs(x));
    ls->push(x), direct->push(x);
    if (m >= n)
      for (int k = 0; k < 6; ++k)
        worst = std::max(worst, std::abs(ls->amplitude(k) - direct->amplitude(k)));
  }
  EXPECT_LT(worst, 1e-12 * max_x);
}

// Constant input: the rectangular DFT at the off-bin thesis carriers leaks
// (2c/N)|sum_i e^{-jwi}| (tested in sdft_bank_test); the joint fit has a DC
// column and returns amplitudes ~0 and dc = c. Rounding: kappa^2*N*eps*c,
// bound 1e-12*c.
TEST(CarrierDemix, RemovesDcLeakage) {
  const double c = 400.0;
  for (bool hann : {false, true}) {
    auto ls = make_sdft_bank(DftVariant::LsDemix, kThesis, kFs, cfg(32, hann));
    auto direct = make_sdft_bank(DftVariant::Direct, kThesis, kFs, cfg(32, hann));
    for (int m = 0; m < 100; ++m) ls->push(c), direct->push(c);
    double leak = 0.0;
    for (int k = 0; k < 6; ++k) {
      EXPECT_LT(ls->magnitude(k), 1e-12 * c) << k;
      leak = std::max(leak, direct->magnitude(k) / c);
    }
    EXPECT_NEAR(ls->dc(), c, 1e-12 * c);
    std::printf("%s: DC leaks up to %.4f of c into the DFT, %.1e after demixing\n",
                hann ? "hann" : "rect", leak, ls->magnitude(0) / c);
    if (!hann) {
      EXPECT_GT(leak, 0.01);  // it really leaks without demixing
    }
  }
}

// Streaming (Exact sums -> G^{-1}) vs batch (pseudo-inverse on the raw
// window) over 1e6 samples of multi-tone + off-carrier tone + noise. The
// sums' error is at most 40*eps*sqrt(n)*N*max|x| each (random-walk bound of
// the exact SDFT, sdft_bank_test) and G^{-1} amplifies a vector of 2K+1 of
// them by ||G^{-1}||_2 = 1/sigma_min^2, computed here from our own basis.
TEST(CarrierDemix, StreamingMatchesBatchFitOver1e6Samples) {
  const int n = 32, k = 6;
  CarrierDemix demix(kThesis, kFs, n, false);
  auto ls = make_sdft_bank(DftVariant::LsDemix, kThesis, kFs, cfg(n));
  Eigen::MatrixXd b(n, 2 * k + 1);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < k; ++c) {
      b(i, 2 * c) = std::cos(w_of(kThesis[size_t(c)]) * i);
      b(i, 2 * c + 1) = std::sin(w_of(kThesis[size_t(c)]) * i);
    }
    b(i, 2 * k) = 1.0;
  }
  const double sigma_min = Eigen::JacobiSVD<Eigen::MatrixXd>(b).singularValues()(2 * k);
  std::mt19937_64 rng(4);
  std::normal_distribution<double> noise(0.0, 5.0);
  std::vector<double> win(n, 0.0), checkpoints = {1e4, 1e5, 1e6};
  double max_x = 0.0;
  size_t cp = 0;
  for (long m = 0; m < long(checkpoints.back()); ++m) {
    double x = 2.0 + noise(rng) + 300 * std::cos(w_of(3300) * m + 1) +
               120 * std::cos(w_of(8300) * m) + 80 * std::cos(w_of(6000) * m + 2);
    max_x = std::max(max_x, std::fabs(x));
    ls->push(x);
    win.erase(win.begin());
    win.push_back(x);
    if (m + 1 != long(checkpoints[cp])) continue;
    std::vector<cd> batch;
    double batch_dc = 0.0;
    demix.fit(win, batch, batch_dc);
    double worst = std::fabs(ls->dc() - batch_dc);
    for (int c = 0; c < k; ++c) worst = std::max(worst, std::abs(ls->amplitude(c) - batch[size_t(c)]));
    const double bound = std::sqrt(2.0 * k + 1) / (sigma_min * sigma_min) * 40.0 * kEps *
                         std::sqrt(checkpoints[cp]) * n * max_x;
    std::printf("%8.0e samples: |streaming - batch| = %.3e (bound %.3e)\n", checkpoints[cp],
                worst, bound);
    EXPECT_LT(worst, bound);
    ++cp;
  }
}

// Carriers closer than the window resolves make the basis nearly singular:
// 5000 and 5050 Hz are 0.046 bin apart at N = 32, kappa ~ 1.2/0.046 = 26 >
// the default limit 10; the same pair is accepted with a 1024-sample window
// (1.5 bins apart) and the thesis set is well conditioned (kappa < 3).
TEST(CarrierDemix, TooCloseCarriersThrowNamingThem) {
  EXPECT_LT(CarrierDemix(kThesis, kFs, 32, false).condition_number(), 3.0);
  EXPECT_LT(CarrierDemix({1900, 5000, 5050}, kFs, 1024, false).condition_number(), 3.0);
  try {
    CarrierDemix demix({1900, 5000, 5050}, kFs, 32, false);
    FAIL() << "expected ConfigError, condition number " << demix.condition_number();
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.field(), "decoder.window");
    EXPECT_NE(std::string(e.what()).find("5000 and 5050"), std::string::npos) << e.what();
  }
  // 6 carriers + DC = 13 unknowns: 12 samples cannot hold them; Hann's zero
  // weight at i = 0 leaves 12 of 13.
  EXPECT_THROW(CarrierDemix(kThesis, kFs, 12, false), ConfigError);
  EXPECT_THROW(CarrierDemix(kThesis, kFs, 13, true), ConfigError);
}

}  // namespace
}  // namespace eskin::golden
