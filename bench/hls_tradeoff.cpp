// Speed against accuracy of the carrier-amplitude kernels, one command:
//   build/bin/hls_tradeoff [samples]
// For each variant (exact sliding DFT hls/sdft_bank.h, block Goertzel
// hls/sdft_damped.h), coefficient width CW (with the table index width TW and
// term fraction bits FB, or the state fraction bits F, it is paired with) and
// window N = 16/32/64/128:
//   error of the amplitude (2/N)|sum| against the golden Direct DFT (double),
//   max and RMS, in % of full scale (2^(XW-1) = 4096 LSB, XW = 13);
//   multiplies and adds per input sample (K = 6 carriers);
//   outputs per input sample (1 = a new amplitude set every sample);
//   state memory in bits (window buffer, sums, phases, increments, ROM /
//   resonator state and coefficients);
//   cycles per sample of a one-multiplier datapath (exact: the RTL's
//   II = 6K + 2, asserted in tests/rtl/sdft_bank_test.cpp; Goertzel: an
//   estimate, one multiply per cycle, no RTL).
// Input: six tones at the carriers with random amplitudes (peak sum ~4000)
// and phases plus 5% uniform noise, 13-bit samples. Carriers: the thesis set
// 1.9/3.3/5/7.14/8.3/10 kHz at fs = 35 kHz for N >= 32; with N = 16 the bin
// (2.19 kHz) is wider than their spacing, so 2.5/4.8/7.1/9.4/11.7/14 kHz.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "hls/sdft_bank.h"
#include "hls/sdft_bank_config.h"
#include "hls/sdft_damped.h"
#include "host/golden/sdft_bank.h"

namespace {

using namespace eskin::hls;

constexpr double kFs = 35000;
constexpr int kXW = 13;
constexpr double kFullScale = 4096;
const std::vector<double> kThesis = {1900, 3300, 5000, 7140, 8300, 10000};
const std::vector<double> kWide = {2500, 4800, 7100, 9400, 11700, 14000};

std::vector<int32_t> g_xs;  // the input, shared by every row

struct Row {
  const char* variant;
  int n, cw, tw_or_f, acc_w, frac;
  double max_err = 0, rms_err = 0;
  double mults = 0, adds = 0, outputs = 0, cycles = 0;
  long state_bits = 0;
};

const std::vector<double>& carriers(int n) { return n >= 32 ? kThesis : kWide; }

// Accumulates |kernel - golden| over every output of one configuration.
struct ErrorStats {
  double max = 0, sum2 = 0;
  long count = 0;
  void add(double e) {
    max = std::max(max, e);
    sum2 += e * e;
    ++count;
  }
};

template <int N, int CW, int TW, int FB>
Row run_exact() {
  constexpr int ACC_W = sdft_min_acc_width(N, kXW, FB);
  using Bank = SdftBank<6, N, kXW, CW, TW, ACC_W, FB>;
  const auto& f = carriers(N);
  typename Bank::Config cfg;
  if (!make_sdft_bank_config<Bank>(f, kFs, cfg).ok()) std::abort();
  static Bank bank;
  bank.configure(cfg);
  eskin::DecoderConfig dec;
  dec.window = N;
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::Direct, f, kFs, dec);
  const double g = (std::ldexp(1.0, CW - 1) - 1) / std::ldexp(1.0, CW - 1) * (1 << FB);
  SdftBankToken out[6];
  ErrorStats st;
  for (size_t i = 0; i < g_xs.size(); ++i) {
    bank.push(g_xs[i], out);
    golden->push(g_xs[i]);
    if (i + 1 < size_t(N)) continue;
    for (int k = 0; k < 6; ++k)
      st.add(std::fabs(2.0 / N * std::hypot(out[k].re, out[k].im) / g - golden->magnitude(k)));
  }
  Row r{"exact", N, CW, TW, ACC_W, FB};
  r.max_err = st.max / kFullScale * 100;
  r.rms_err = std::sqrt(st.sum2 / double(st.count)) / kFullScale * 100;
  const int k = 6;
  r.mults = 4 * k;
  r.adds = 12 * k;  // 4 accumulate, 4 term rounding, 2 phase, 2 index rounding
  r.outputs = 1;
  r.cycles = 6 * k + 2;
  r.state_bits = long(N) * kXW + long(k) * (2 * ACC_W + 64) + long(Bank::Q) * (CW - 1);
  return r;
}

template <int N, int CW, int F>
Row run_goertzel() {
  constexpr int SW = goertzel_min_state_width(N, kXW, F);
  using Bank = GoertzelBlockBank<6, N, kXW, CW, F, SW>;
  const auto& f = carriers(N);
  typename Bank::Config cfg;
  if (!make_goertzel_config<Bank>(f, kFs, cfg).ok()) std::abort();
  Bank bank;
  bank.configure(cfg);
  eskin::DecoderConfig dec;
  dec.window = N;
  auto golden = eskin::golden::make_sdft_bank(eskin::DftVariant::Direct, f, kFs, dec);
  GoertzelToken out[6];
  ErrorStats st;
  for (size_t i = 0; i < g_xs.size(); ++i) {
    golden->push(g_xs[i]);
    const int got = bank.push(g_xs[i], out);
    for (int k = 0; k < got; ++k)
      st.add(std::fabs(2.0 / N * std::hypot(out[k].re, out[k].im) - golden->magnitude(k)));
  }
  Row r{"goertzel", N, CW, F, SW, F};
  r.max_err = st.max / kFullScale * 100;
  r.rms_err = std::sqrt(st.sum2 / double(st.count)) / kFullScale * 100;
  const int k = 6;
  r.mults = k + 2.0 * k / N;
  r.adds = 3 * k + 3.0 * k / N;  // per sample: +x, -s2, rounding; per block: 3
  r.outputs = 1.0 / N;
  r.cycles = k + 2.0 * k / N;
  r.state_bits = long(k) * (2 * SW + 2 * CW) + sdft_ceil_log2(N);
  return r;
}

template <int N>
void rows_for(std::vector<Row>& rows) {
  rows.push_back(run_exact<N, 12, 8, 0>());
  rows.push_back(run_exact<N, 16, 10, 0>());
  rows.push_back(run_exact<N, 16, 12, 4>());
  rows.push_back(run_exact<N, 18, 12, 4>());
  rows.push_back(run_exact<N, 24, 14, 8>());
  rows.push_back(run_goertzel<N, 12, 0>());
  rows.push_back(run_goertzel<N, 16, 4>());
  rows.push_back(run_goertzel<N, 18, 6>());
  rows.push_back(run_goertzel<N, 24, 8>());
}

}  // namespace

int main(int argc, char** argv) {
  const size_t samples = argc > 1 ? size_t(std::atol(argv[1])) : 65536;
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0, 1);
  double amp[6], ph[6];
  for (int k = 0; k < 6; ++k) amp[k] = 4000.0 / 6 * (0.3 + 0.7 * u(rng)), ph[k] = 6.283 * u(rng);
  std::vector<double> v(samples);
  // Tones at the thesis carriers for N >= 32 and at the wide set for N = 16
  // would need two inputs; the sum of both keeps one input for every row
  // (each bank sees the other set as interference, as real skins do).
  for (size_t n = 0; n < samples; ++n) {
    double x = 200 * (u(rng) - 0.5);
    for (int k = 0; k < 6; ++k) {
      x += 0.5 * amp[k] * std::cos(2 * M_PI * kThesis[k] / kFs * double(n) + ph[k]);
      x += 0.5 * amp[k] * std::cos(2 * M_PI * kWide[k] / kFs * double(n) + ph[5 - k]);
    }
    g_xs.push_back(int32_t(std::lround(std::clamp(x, -4096.0, 4095.0))));
  }
  std::vector<Row> rows;
  rows_for<16>(rows);
  rows_for<32>(rows);
  rows_for<64>(rows);
  rows_for<128>(rows);
  std::printf("hls_tradeoff: K = 6 carriers, fs = 35 kHz, XW = 13, %zu samples; error of (2/N)|sum|\n"
              "vs golden Direct DFT in %% of full scale (4096 LSB)\n\n", samples);
  std::printf("%-9s %4s %3s %3s %3s %4s %10s %10s %7s %7s %8s %8s %11s\n", "variant", "N",
              "CW", "TW", "frac", "acc", "max err %", "RMS err %", "mul/smp", "add/smp",
              "out/smp", "cyc/smp", "state bits");
  for (const Row& r : rows) {
    char tw[8];
    std::snprintf(tw, sizeof tw, "%d", r.tw_or_f);
    std::printf("%-9s %4d %3d %3s %4d %4d %10.4f %10.4f %7.2f %7.2f %8.4f %8.2f %11ld\n",
                r.variant, r.n, r.cw, r.variant[0] == 'e' ? tw : "-", r.frac, r.acc_w, r.max_err,
                r.rms_err, r.mults, r.adds, r.outputs, r.cycles, r.state_bits);
  }
  std::printf("\nfrac: fraction bits below the sample LSB (exact: FB of each rounded term;\n"
              "Goertzel: F of the resonator state). acc: accumulator width, the narrowest legal\n"
              "(exact: XW + 1 + FB + ceil(log2 N); Goertzel: XW + F + 2 + ceil(log2(N(N+1)/2))).\n"
              "cyc/smp: exact = RTL II 6K + 2 (tests/rtl/sdft_bank_test.cpp); goertzel = estimate,\n"
              "1 multiply/cycle. exact state bits include the quarter-sine ROM 2^(TW-2) x (CW-1).\n");
  return 0;
}
