// Golden SdftBank variants against FFTW, against each other over 10^6+
// samples, against closed-form leakage (geometric series), and at extremes.
// Every expected value is computed here from its own formula, never taken
// from the code under test. Amplitudes follow sdft_bank.h: scale 2/sum(h),
// phase of the carrier at the window's oldest sample.
#include <fftw3.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "host/golden/sdft_bank.h"

namespace eskin::golden {
namespace {

using cd = std::complex<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kFs = 35000.0;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};

DecoderConfig cfg(int n, bool hann = false, double r = 0.9999) {
  DecoderConfig c;
  c.window = n;
  c.hann = hann;
  c.damping = r;
  return c;
}

// Sum_{i=0}^{N-1} q^i in closed form (N when q == 1).
cd geometric(cd q, int n) {
  if (std::abs(q - 1.0) < 1e-15) return double(n);
  return (1.0 - std::pow(q, n)) / (1.0 - q);
}

// Rectangular-window amplitude at angular frequency wk of the tone
// A*cos(wt*m + phi), window oldest sample s: (1/N) [A e^{j(wt s+phi)} G(e^{j(wt-wk)})
// + A e^{-j(wt s+phi)} G(e^{-j(wt+wk)})], G = geometric series.
cd tone_at(double a, double wt, double phi, double wk, long s, int n) {
  const double ph = wt * double(s) + phi;
  return (a / n) * (std::polar(1.0, ph) * geometric(std::polar(1.0, wt - wk), n) +
                    std::polar(1.0, -ph) * geometric(std::polar(1.0, -wt - wk), n));
}

double w_of(double f) { return 2.0 * M_PI * f / kFs; }

// ---------------------------------------------------------------- FFTW ---
// Bound 1e-12 * max|x|: the direct sum of N terms has rounding error below
// about 2(N+2)*eps*max|x| after the 2/N scale (5.7e-14*max|x| at N = 256),
// FFTW's O(eps*log N); both are far inside 1e-12.
TEST(SdftBank, DirectMatchesFftwOnBinCentredTonesAllBins) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> amp(0.1, 500.0), phase(-M_PI, M_PI);
  for (int n : {32, 64, 256}) {
    for (bool hann : {false, true}) {
      std::vector<double> freqs;
      for (int b = 1; b < n / 2; ++b) freqs.push_back(b * kFs / n);
      auto bank = make_sdft_bank(DftVariant::Direct, freqs, kFs, cfg(n, hann));
      std::vector<double> a(freqs.size()), phi(freqs.size());
      for (size_t b = 0; b < freqs.size(); ++b) a[b] = amp(rng), phi[b] = phase(rng);
      const long total = n + 17;  // the window starts at s = 17
      std::vector<double> x(static_cast<size_t>(total));
      for (long m = 0; m < total; ++m) {
        for (size_t b = 0; b < freqs.size(); ++b)
          x[size_t(m)] += a[b] * std::cos(w_of(freqs[b]) * m + phi[b]);
        bank->push(x[size_t(m)]);
      }
      double max_x = 0.0;
      for (double v : x) max_x = std::max(max_x, std::fabs(v));

      std::vector<double> in(static_cast<size_t>(n));
      std::vector<double> h = window_weights(n, hann);
      double sum_h = 0.0;
      for (int i = 0; i < n; ++i) {
        in[size_t(i)] = h[size_t(i)] * x[size_t(total - n + i)];
        sum_h += h[size_t(i)];
      }
      std::vector<fftw_complex> out(size_t(n / 2 + 1));
      fftw_plan p = fftw_plan_dft_r2c_1d(n, in.data(), out.data(), FFTW_ESTIMATE);
      fftw_execute(p);
      fftw_destroy_plan(p);
      double worst = 0.0;
      for (int b = 1; b < n / 2; ++b) {
        cd ref = (2.0 / sum_h) * cd(out[size_t(b)][0], out[size_t(b)][1]);
        worst = std::max(worst, std::abs(bank->amplitude(b - 1) - ref));
        if (!hann) {  // bin-centred, rectangular: exactly the tone's phasor
          cd tone = std::polar(a[size_t(b - 1)], w_of(freqs[size_t(b - 1)]) * (total - n) +
                                                     phi[size_t(b - 1)]);
          EXPECT_LT(std::abs(bank->amplitude(b - 1) - tone), 1e-12 * max_x) << "bin " << b;
        }
      }
      EXPECT_LT(worst, 1e-12 * max_x) << "N=" << n << " hann=" << hann;
      std::cout << "N=" << n << (hann ? " hann" : " rect") << ": max |direct - fftw| / max|x| = "
                << worst / max_x << "\n";
    }
  }
}

// ------------------------------------------------ long sliding runs ---
// Random multi-tone (the six thesis carriers, two off-carrier tones, a DC
// residual) + Gaussian noise, 1.1e6 samples. Errors vs Direct are the max
// over the 64 samples before each checkpoint and over the carriers.
struct LongRun {
  static constexpr int kN = 32;
  std::vector<long> checkpoints = {10000, 100000, 1000000};
  std::vector<double> err_recursive, err_damped_vs_direct, err_damped_vs_expwin, err_exact;
  double max_x = 0.0;
  double r = 0.9999;

  LongRun() {
    auto direct = make_sdft_bank(DftVariant::Direct, kThesis, kFs, cfg(kN));
    auto recursive = make_sdft_bank(DftVariant::Recursive, kThesis, kFs, cfg(kN));
    auto damped = make_sdft_bank(DftVariant::Damped, kThesis, kFs, cfg(kN, false, r));
    auto exact = make_sdft_bank(DftVariant::Exact, kThesis, kFs, cfg(kN));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> amp(20.0, 200.0), phase(-M_PI, M_PI);
    std::normal_distribution<double> noise(0.0, 3.0);
    std::vector<double> f = kThesis, a, phi;
    f.push_back(2600.0);
    f.push_back(12345.6);
    for (size_t i = 0; i < f.size(); ++i) a.push_back(amp(rng)), phi.push_back(phase(rng));
    std::vector<double> win(kN, 0.0);  // the test's own copy of the window
    size_t cp = 0;
    double e_rec = 0, e_dd = 0, e_de = 0, e_ex = 0;
    for (long m = 0; m < checkpoints.back(); ++m) {
      double x = 3.7 + noise(rng);
      for (size_t i = 0; i < f.size(); ++i) x += a[i] * std::cos(w_of(f[i]) * double(m) + phi[i]);
      max_x = std::max(max_x, std::fabs(x));
      direct->push(x);
      recursive->push(x);
      damped->push(x);
      exact->push(x);
      win.erase(win.begin());
      win.push_back(x);
      if (m + 1 > checkpoints[cp] - 64) {
        for (int k = 0; k < 6; ++k) {
          cd ref = direct->amplitude(k);
          cd expwin = 0.0;  // sum r^(N-1-i) x_i e^{-jwi} * 2/N
          for (int i = 0; i < kN; ++i)
            expwin += std::pow(r, kN - 1 - i) * win[size_t(i)] * std::polar(1.0, -w_of(f[size_t(k)]) * i);
          expwin *= 2.0 / kN;
          e_rec = std::max(e_rec, std::abs(recursive->amplitude(k) - ref));
          e_dd = std::max(e_dd, std::abs(damped->amplitude(k) - ref));
          e_de = std::max(e_de, std::abs(damped->amplitude(k) - expwin));
          e_ex = std::max(e_ex, std::abs(exact->amplitude(k) - ref));
        }
        if (m + 1 == checkpoints[cp]) {
          err_recursive.push_back(e_rec);
          err_damped_vs_direct.push_back(e_dd);
          err_damped_vs_expwin.push_back(e_de);
          err_exact.push_back(e_ex);
          e_rec = e_dd = e_de = e_ex = 0;
          ++cp;
        }
      }
    }
  }
};

const LongRun& long_run() {
  static LongRun run;
  return run;
}

TEST(SdftBank, LongRunReport) {
  const LongRun& run = long_run();
  std::printf("max|x| = %.1f LSB; errors vs Direct (LSB, max over carriers and 64 samples)\n",
              run.max_x);
  std::printf("%10s %14s %14s %14s %14s\n", "samples", "recursive", "damped-direct",
              "damped-expwin", "exact");
  for (size_t i = 0; i < run.checkpoints.size(); ++i) {
    std::printf("%10ld %14.3e %14.3e %14.3e %14.3e\n", run.checkpoints[i], run.err_recursive[i],
                run.err_damped_vs_direct[i], run.err_damped_vs_expwin[i], run.err_exact[i]);
    const std::string n = std::to_string(run.checkpoints[i]);
    RecordProperty("recursive_err_" + n, std::to_string(run.err_recursive[i]));
    RecordProperty("damped_err_" + n, std::to_string(run.err_damped_vs_direct[i]));
    RecordProperty("exact_err_" + n, std::to_string(run.err_exact[i]));
  }
  EXPECT_EQ(run.err_exact.size(), run.checkpoints.size());
}

// Naive recursive SDFT. Per sample it makes rounding errors of a few
// eps*|y| <= eps*N*max|x| (complex multiply, additions) plus the mismatch
// |z^N - c| <= (N+1)*eps between the rounded pole and the rounded leaving
// factor; with the pole on the unit circle none of it decays, so after n
// samples the error is below 12*n*eps*max|x| after the 2/N scale (6N eps
// per step, see sdft_bank.h). For tones AT the carrier the mismatch
// residue adds up coherently, so the error grows about linearly: we require
// at least 10x growth from 1e4 to 1e6 samples (linear would be 100x).
TEST(SdftBank, RecursiveDriftsAndGrows) {
  const LongRun& run = long_run();
  for (size_t i = 0; i < run.checkpoints.size(); ++i)
    EXPECT_LT(run.err_recursive[i], 12.0 * run.checkpoints[i] * kEps * run.max_x);
  EXPECT_GT(run.err_recursive[2], 10.0 * run.err_recursive[0]);
  EXPECT_GT(run.err_recursive[1], run.err_recursive[0]);
}

// Damped SDFT: it computes the DFT under the exponential window r^(N-1-i)
// with the rectangular scale 2/N, so vs Direct it differs by at most
// (2/N)*max|x|*sum_i (1 - r^(N-1-i)) (deterministic bias, ~1e-4 max|x| at
// r = 0.9999). Against the exponentially windowed sum computed here, only
// rounding remains, and it decays by r per sample: <= (2/N)*6N*eps*max|x| /
// (1 - r) = 12*eps*max|x|/(1 - r), at every checkpoint alike (no growth).
TEST(SdftBank, DampedBiasBoundedAndNoDrift) {
  const LongRun& run = long_run();
  const int n = LongRun::kN;
  double bias = 0.0;
  for (int i = 0; i < n; ++i) bias += 1.0 - std::pow(run.r, n - 1 - i);
  for (size_t i = 0; i < run.checkpoints.size(); ++i) {
    EXPECT_LT(run.err_damped_vs_direct[i], 2.0 / n * run.max_x * bias);
    EXPECT_LT(run.err_damped_vs_expwin[i], 12.0 * kEps * run.max_x / (1.0 - run.r));
  }
}

// Exact modulated SDFT: the only error is the rounding of the running sum,
// a random walk of steps <= 2*eps*N*max|x| (before the 2/N scale); after n
// samples about 2*eps*sqrt(n)*N*max|x|. We allow 10x that (a 10-sigma
// bound on the walk): <= 40*eps*sqrt(n)*max|x| after scaling, 8.9e-12*max|x|
// at 1e6 samples, where the recursive bound is already 2.7e-9*max|x|.
// (Typical |sum| is well below N*max|x|, so the measured error is smaller.)
TEST(SdftBank, ExactStaysAtRounding) {
  const LongRun& run = long_run();
  for (size_t i = 0; i < run.checkpoints.size(); ++i)
    EXPECT_LT(run.err_exact[i], 40.0 * kEps * std::sqrt(double(run.checkpoints[i])) * run.max_x)
        << run.checkpoints[i] << " samples";
}

// Hann on the sliding variants: the three-tap combination 0.5 R(w) -
// 0.25 R(w -/+ 2pi/N) must equal the directly Hann-windowed sum. Bounds as
// above over 2e4 samples, doubled because three sums of weight 0.5+0.25+0.25
// each carry their own error: Exact 80*eps*sqrt(n)*max|x|, Recursive
// 24*n*eps*max|x|. (Damped is biased by design, tested separately.)
TEST(SdftBank, HannSlidingMatchesDirect) {
  const int n = 32;
  auto direct = make_sdft_bank(DftVariant::Direct, kThesis, kFs, cfg(n, true));
  auto exact = make_sdft_bank(DftVariant::Exact, kThesis, kFs, cfg(n, true));
  auto recursive = make_sdft_bank(DftVariant::Recursive, kThesis, kFs, cfg(n, true));
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 100.0);
  double max_x = 0.0, e_ex = 0.0, e_rec = 0.0;
  const long total = 20000;
  for (long m = 0; m < total; ++m) {
    double x = noise(rng) + 150.0 * std::cos(w_of(5000) * m + 0.3);
    max_x = std::max(max_x, std::fabs(x));
    direct->push(x), exact->push(x), recursive->push(x);
    if (m >= n)
      for (int k = 0; k < 6; ++k) {
        e_ex = std::max(e_ex, std::abs(exact->amplitude(k) - direct->amplitude(k)));
        e_rec = std::max(e_rec, std::abs(recursive->amplitude(k) - direct->amplitude(k)));
      }
  }
  std::cout << "Hann, 2e4 samples: max |exact - direct| = " << e_ex
            << ", |recursive - direct| = " << e_rec << " (max|x| " << max_x << ")\n";
  EXPECT_LT(e_ex, 80.0 * kEps * std::sqrt(double(total)) * max_x);
  EXPECT_LT(e_rec, 2.0 * 12.0 * total * kEps * max_x);
}

// ----------------------------------------------------------- leakage ---
// A unit tone at each thesis carrier, 8 phases; every carrier's amplitude
// must equal the closed-form geometric-series prediction (tone_at) within
// 1e-12 (both are O(N eps) roundings of the same sum). The worst cross-talk
// over phase is tabulated; the closest pairs (1400-1700 Hz = 1.3-1.55 bins
// apart at fs/N = 1093.75 Hz) leak ~20% by the Dirichlet kernel
// |sin(N d/2) / (N sin(d/2))| (0.19-0.20); the image term (the tone's
// negative frequency) adds or subtracts up to D(w_src + w_k) depending on
// phase (measured worst 0.24, 1900 -> 3300). Both the kernel maximum and the
// worst measured cross-talk must fall in 0.15 .. 0.25.
TEST(SdftBank, ThesisCarrierLeakageMatchesDirichlet) {
  const int n = 32;
  double table[6][6] = {};
  for (int src = 0; src < 6; ++src) {
    for (int p = 0; p < 8; ++p) {
      const double phi = 2.0 * M_PI * p / 8 + 0.1;
      auto direct = make_sdft_bank(DftVariant::Direct, kThesis, kFs, cfg(n));
      auto exact = make_sdft_bank(DftVariant::Exact, kThesis, kFs, cfg(n));
      const long total = n + 5;
      for (long m = 0; m < total; ++m) {
        double x = std::cos(w_of(kThesis[size_t(src)]) * m + phi);
        direct->push(x), exact->push(x);
      }
      for (int k = 0; k < 6; ++k) {
        cd want = tone_at(1.0, w_of(kThesis[size_t(src)]), phi, w_of(kThesis[size_t(k)]),
                          total - n, n);
        EXPECT_LT(std::abs(direct->amplitude(k) - want), 1e-12) << src << "->" << k;
        EXPECT_LT(std::abs(exact->amplitude(k) - want), 1e-12) << src << "->" << k;
        table[src][k] = std::max(table[src][k], std::abs(want));
      }
    }
  }
  // The two geometric series have moduli D(w_src - w_k) (the leak) and
  // D(w_src + w_k) (the image), D(d) = |sin(N d/2) / (N sin(d/2))| (Dirichlet
  // kernel), so over phase |amp| lies in [D(-) - D(+), D(-) + D(+)].
  auto dirichlet = [n](double d) {
    return std::fabs(std::sin(n * d / 2) / (n * std::sin(d / 2)));
  };
  std::printf("Dirichlet kernel D(w_tone - w_k) alone (no image term), N=32\n%7s", "");
  for (double f : kThesis) std::printf("%8.0f", f);
  std::printf("\n");
  double worst_kernel = 0.0;
  for (int src = 0; src < 6; ++src) {
    std::printf("%7.0f", kThesis[size_t(src)]);
    for (int k = 0; k < 6; ++k) {
      const double ws = w_of(kThesis[size_t(src)]), wk = w_of(kThesis[size_t(k)]);
      const double leak = k == src ? 1.0 : dirichlet(ws - wk), image = dirichlet(ws + wk);
      std::printf("%8.4f", leak);
      if (k != src) worst_kernel = std::max(worst_kernel, leak);
      EXPECT_LE(table[src][k], leak + image + 1e-12) << src << "->" << k;
      EXPECT_GE(table[src][k], leak - image - 1e-12) << src << "->" << k;
    }
    std::printf("\n");
  }
  double worst = 0.0;
  std::printf("cross-talk |amp(k)| / A, worst over phase, rectangular N=32 (rows: tone)\n%7s",
              "");
  for (double f : kThesis) std::printf("%8.0f", f);
  std::printf("\n");
  for (int src = 0; src < 6; ++src) {
    std::printf("%7.0f", kThesis[size_t(src)]);
    for (int k = 0; k < 6; ++k) {
      std::printf("%8.4f", table[src][k]);
      if (k != src) worst = std::max(worst, table[src][k]);
    }
    std::printf("\n");
  }
  RecordProperty("max_crosstalk", std::to_string(worst));
  EXPECT_GT(worst, 0.15);
  EXPECT_LT(worst, 0.25);
  EXPECT_GT(worst_kernel, 0.15);
  EXPECT_LT(worst_kernel, 0.25);
}

// Damped bias on a bin-centred tone: the output is (1/N) sum_i r^(N-1-i)
// * (A e^{j ph} + A e^{-j ph} e^{-2jwi}) whose closed form is a geometric
// series in r^-1 e^{-2jw}; both are O(N eps) roundings: bound 1e-12.
// The relative bias of the main term is 1 - (1 - r^N)/(N (1 - r))
// ~ (N-1)(1-r)/2 = 1.55e-3 at N = 32, r = 0.9999.
TEST(SdftBank, DampedBiasMatchesExponentialWindow) {
  const int n = 32;
  const double r = 0.9999, f = 5 * kFs / n, w = w_of(f), phi = 0.7;
  auto damped = make_sdft_bank(DftVariant::Damped, {f}, kFs, cfg(n, false, r));
  const long total = 3000;
  for (long m = 0; m < total; ++m) damped->push(std::cos(w * m + phi));
  const double ph = w * (total - n) + phi;
  const cd main = std::pow(r, n - 1) * geometric(1.0 / r, n) / double(n);
  const cd image = std::pow(r, n - 1) * geometric(std::polar(1.0 / r, -2.0 * w), n) / double(n);
  const cd want = std::polar(1.0, ph) * main + std::polar(1.0, -ph) * image;
  EXPECT_LT(std::abs(damped->amplitude(0) - want), 1e-12);
  const double bias = 1.0 - (1.0 - std::pow(r, n)) / (n * (1.0 - r));
  EXPECT_NEAR(1.0 - main.real(), bias, 1e-12);
  std::printf("damped r=%.4f N=%d: relative bias %.4e (approx (N-1)(1-r)/2 = %.4e), |image| %.2e\n",
              r, n, bias, (n - 1) * (1 - r) / 2, std::abs(image));
}

// ---------------------------------------------------------- extremes ---
const DftVariant kAll[] = {DftVariant::Direct, DftVariant::Recursive, DftVariant::Damped,
                           DftVariant::Exact, DftVariant::LsDemix};

// Zero in, zero out: every operation on exact zeros yields exact zeros.
TEST(SdftBank, ZeroInputGivesExactlyZero) {
  for (bool hann : {false, true})
    for (DftVariant v : kAll) {
      auto bank = make_sdft_bank(v, kThesis, kFs, cfg(32, hann));
      EXPECT_FALSE(bank->full());
      for (int m = 0; m < 1000; ++m) bank->push(0.0);
      EXPECT_TRUE(bank->full());
      for (int k = 0; k < 6; ++k) EXPECT_EQ(bank->amplitude(k), cd(0.0)) << to_string(v);
      EXPECT_EQ(bank->dc(), 0.0);
    }
}

// Full-scale alternating +-1 (Nyquist). Predicted amplitude at w:
// (2/N) (-1)^s sum_i (-e^{-jw})^i (geometric series). Direct and Exact
// after 1e5 samples: 4e-12 (Exact's random-walk bound 40 eps sqrt(n) max|x|
// is 2.8e-12; Direct is O(N eps)). With bin-centred carriers and even N,
// Nyquist is bin N/2, orthogonal to every carrier: |amp| < 1e-13 (O(N eps)
// rounding; the recursive one too: its rounding scales with |y| ~ 0 here
// and its pole/leave mismatch residue sum_m x[m] z^(n-m) stays bounded by
// ~1/|1 + z| since the input has nothing at the carrier to add up).
TEST(SdftBank, NyquistAlternatingInput) {
  const int n = 32;
  const long total = 100001;  // odd: the oldest sample s = total - N is odd
  for (DftVariant v : {DftVariant::Direct, DftVariant::Exact}) {
    auto bank = make_sdft_bank(v, kThesis, kFs, cfg(n));
    for (long m = 0; m < total; ++m) bank->push(m % 2 ? -1.0 : 1.0);
    for (int k = 0; k < 6; ++k) {
      cd want = (2.0 / n) * -1.0 * geometric(-std::polar(1.0, -w_of(kThesis[size_t(k)])), n);
      EXPECT_LT(std::abs(bank->amplitude(k) - want), 4e-12) << to_string(v) << " " << k;
      EXPECT_TRUE(std::isfinite(bank->magnitude(k)));
    }
  }
  std::vector<double> planned = plan_carriers(6, kFs, n);
  // (Damped is left out: its exponential window is not orthogonal to Nyquist.)
  for (DftVariant v : {DftVariant::Direct, DftVariant::Recursive, DftVariant::Exact,
                       DftVariant::LsDemix}) {
    auto bank = make_sdft_bank(v, planned, kFs, cfg(n));
    for (long m = 0; m < 5000; ++m) bank->push(m % 2 ? -1.0 : 1.0);
    for (int k = 0; k < 6; ++k) EXPECT_LT(bank->magnitude(k), 1e-13) << to_string(v) << " " << k;
  }
}

// Constant input c: leaks into an off-bin carrier by (2c/N) G(e^{-jw})
// (geometric series; zero for bin-centred carriers). Bound 1e-12*c: O(N eps)
// for Direct/Exact, and 200 samples keep the recursive worst case
// 12*n*eps*c = 5.3e-13*c below it.
TEST(SdftBank, ConstantInputLeaksAsPredicted) {
  const int n = 32;
  const double c = 400.0;
  for (DftVariant v : {DftVariant::Direct, DftVariant::Exact, DftVariant::Recursive}) {
    auto bank = make_sdft_bank(v, kThesis, kFs, cfg(n));
    for (int m = 0; m < 200; ++m) bank->push(c);
    for (int k = 0; k < 6; ++k) {
      cd want = (2.0 * c / n) * geometric(std::polar(1.0, -w_of(kThesis[size_t(k)])), n);
      EXPECT_LT(std::abs(bank->amplitude(k) - want), 1e-12 * c) << to_string(v) << " " << k;
    }
    EXPECT_NEAR(bank->dc(), c, 1e-12 * c);
  }
}

// Bin-centred multi-tone under Hann: the Hann kernel is zero except at bin
// offsets 0 and +-1, the planned carriers are >= 2 bins apart and their
// images (sums of bins) avoid 0 and N +- 1: amplitudes are exact to O(eps).
TEST(SdftBank, HannBinCentredAmplitudeExact) {
  const int n = 32;
  std::vector<double> f = plan_carriers(6, kFs, n);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> amp(1.0, 100.0), phase(-M_PI, M_PI);
  std::vector<double> a, phi;
  for (size_t i = 0; i < f.size(); ++i) a.push_back(amp(rng)), phi.push_back(phase(rng));
  for (DftVariant v : {DftVariant::Direct, DftVariant::Exact, DftVariant::Recursive,
                       DftVariant::LsDemix}) {
    auto bank = make_sdft_bank(v, f, kFs, cfg(n, true));
    const long total = 1000;
    for (long m = 0; m < total; ++m) {
      double x = 0.0;
      for (size_t i = 0; i < f.size(); ++i) x += a[i] * std::cos(w_of(f[i]) * m + phi[i]);
      bank->push(x);
    }
    for (int k = 0; k < 6; ++k) {
      cd want = std::polar(a[size_t(k)], w_of(f[size_t(k)]) * (total - n) + phi[size_t(k)]);
      EXPECT_LT(std::abs(bank->amplitude(k) - want), 1e-11 * 100.0) << to_string(v) << " " << k;
    }
  }
}

TEST(SdftBank, BadConfigNamesTheField) {
  auto field_of = [](auto&& f) {
    try {
      f();
    } catch (const ConfigError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of([] { make_sdft_bank(DftVariant::Exact, {1000, 20000}, kFs, cfg(32)); }),
            "carriers[1]");
  EXPECT_EQ(field_of([] { make_sdft_bank(DftVariant::Exact, {1000}, kFs, cfg(1)); }),
            "decoder.window");
  EXPECT_EQ(field_of([] { make_sdft_bank(DftVariant::Damped, {1000}, kFs, cfg(32, false, 1.0)); }),
            "decoder.damping");
  EXPECT_EQ(field_of([] { make_sdft_bank(DftVariant::LsDemix, kThesis, kFs, cfg(12)); }),
            "decoder.window");
  EXPECT_EQ(field_of([] { make_sdft_bank(DftVariant::Direct, {}, kFs, cfg(32)); }), "carriers");
}

}  // namespace
}  // namespace eskin::golden
