// Izhikevich neurons (2003 presets, thesis RA) under the project's forward
// Euler scheme: characteristic firing patterns, clamps, weighted layer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "eskin/skin_config.h"
#include "host/golden/izhikevich_layer.h"

using namespace eskin::golden;
using eskin::IzhikevichParams;

namespace {

using Input = std::function<double(double t_ms)>;

// Spike times (ms) of one neuron driven by input(t) (before the gain).
std::vector<double> run(const IzhikevichParams& p, double dt, double t_end, const Input& in) {
  IzhikevichLayer layer(1, p, dt);
  std::vector<double> times;
  std::vector<int> spiked;
  const long steps = long(std::lround(t_end / dt));
  for (long k = 0; k < steps; ++k) {
    double x = in(double(k) * dt);
    spiked.clear();
    layer.step(&x, spiked);
    if (!spiked.empty()) times.push_back(layer.time_ms());
  }
  return times;
}

Input step_at(double t0, double amp) {
  return [=](double t) { return t >= t0 ? amp : 0.0; };
}

std::vector<double> isis(const std::vector<double>& t) {
  std::vector<double> d;
  for (size_t k = 1; k < t.size(); ++k) d.push_back(t[k] - t[k - 1]);
  return d;
}

double mean_last(const std::vector<double>& v, size_t n) {
  double s = 0;
  for (size_t k = v.size() - n; k < v.size(); ++k) s += v[k];
  return s / double(n);
}

size_t count_in(const std::vector<double>& t, double from, double to) {
  size_t n = 0;
  for (double x : t) n += x >= from && x < to;
  return n;
}

// The 2003 paper's protocol: dt 0.25 ms, rest until 50 ms, then a step of
// I = 10 held to 500 ms.
constexpr double kDt = 0.25, kT = 500.0, kOn = 50.0;

std::vector<double> paper_step(const std::string& preset) {
  return run(izhikevich_preset(preset), kDt, kT, step_at(kOn, 10.0));
}

}  // namespace

// Criteria below are the qualitative signatures of Izhikevich (2003) Fig. 2
// turned into ISI ratios; thresholds sit between the classes (e.g. a burst
// ISI is a few ms, a tonic ISI tens of ms at I = 10).

// RS: single spikes (no ISI < 10 ms), spike-frequency adaptation (last ISI
// >= 1.5x the first), then tonic (last three ISIs within 5%).
TEST(GoldenIzhikevichLayer, RegularSpikingAdapts) {
  auto t = paper_step("RS");
  auto d = isis(t);
  ASSERT_GE(t.size(), 5u);
  EXPECT_GE(t.front(), kOn);
  for (double x : d) EXPECT_GT(x, 10.0);
  EXPECT_GE(d.back(), 1.5 * d.front());
  const double m = mean_last(d, 3);
  for (size_t k = d.size() - 3; k < d.size(); ++k) EXPECT_NEAR(d[k], m, 0.05 * m);
}

// IB: an initial burst (first two ISIs < 6 ms, i.e. >= 3 spikes) then tonic
// single spikes (every later ISI > 20 ms).
TEST(GoldenIzhikevichLayer, IntrinsicallyBurstingBurstThenTonic) {
  auto d = isis(paper_step("IB"));
  ASSERT_GE(d.size(), 6u);
  EXPECT_LT(d[0], 6.0);
  EXPECT_LT(d[1], 6.0);
  for (size_t k = 2; k < d.size(); ++k) EXPECT_GT(d[k], 20.0) << "ISI " << k;
}

// CH: repeated bursts, i.e. a bimodal ISI: >= 4 pauses (ISI > 30 ms), at
// least twice as many intra-burst ISIs (< 6 ms) as pauses (>= 3 spikes per
// burst on average), and every pause is followed by a short ISI (a burst).
TEST(GoldenIzhikevichLayer, ChatteringRepeatedBursts) {
  auto d = isis(paper_step("CH"));
  size_t pauses = 0, shorts = 0;
  for (size_t k = 0; k < d.size(); ++k) {
    if (d[k] > 30.0) {
      ++pauses;
      if (k + 1 < d.size()) {
        EXPECT_LT(d[k + 1], 6.0) << "no burst after pause " << k;
      }
    }
    shorts += d[k] < 6.0;
  }
  EXPECT_GE(pauses, 4u);
  EXPECT_GE(shorts, 2 * pauses);
}

// FS: high-rate tonic firing with little adaptation: steady ISI < 10 ms
// (> 100 Hz), at most 2x the first ISI, and >= 4x RS's steady rate.
TEST(GoldenIzhikevichLayer, FastSpikingHighRateLittleAdaptation) {
  auto d = isis(paper_step("FS"));
  auto rs = isis(paper_step("RS"));
  ASSERT_GE(d.size(), 10u);
  const double steady = mean_last(d, 5);
  EXPECT_LT(steady, 10.0);
  EXPECT_LE(steady, 2.0 * d.front());
  EXPECT_LE(4.0 * steady, mean_last(rs, 3));
}

// LTS: high-frequency start (first ISI < 5 ms), strong adaptation (steady ISI
// > 3x the first), then tonic (last five ISIs within 10% of their mean).
TEST(GoldenIzhikevichLayer, LowThresholdSpikingStartsFastThenAdapts) {
  auto d = isis(paper_step("LTS"));
  ASSERT_GE(d.size(), 10u);
  EXPECT_LT(d.front(), 5.0);
  const double steady = mean_last(d, 5);
  EXPECT_GT(steady, 3.0 * d.front());
  for (size_t k = d.size() - 5; k < d.size(); ++k) EXPECT_NEAR(d[k], steady, 0.1 * steady);
}

// TC: (a) tonic firing at positive current, regular (max ISI < 2x min ISI);
// (b) silent during a hyperpolarising step (I = -10, 100..300 ms) and a
// rebound burst on release: >= 2 spikes within 40 ms with first ISI < 15
// ms, then silence again (none after 350 ms).
TEST(GoldenIzhikevichLayer, ThalamoCorticalTonicAndReboundBurst) {
  auto d = isis(paper_step("TC"));
  ASSERT_GE(d.size(), 20u);
  EXPECT_LT(*std::max_element(d.begin(), d.end()), 2.0 * *std::min_element(d.begin(), d.end()));

  auto t = run(izhikevich_preset("TC"), kDt, 600.0,
               [](double t) { return t >= 100.0 && t < 300.0 ? -10.0 : 0.0; });
  EXPECT_EQ(count_in(t, 0.0, 300.0), 0u);
  EXPECT_GE(count_in(t, 300.0, 340.0), 2u);
  ASSERT_GE(t.size(), 2u);
  EXPECT_LT(t[1] - t[0], 15.0);
  EXPECT_EQ(count_in(t, 350.0, 600.0), 0u);
}

// RZ. Linearised at its rest point v* = -62.5, u* = b v* (I = 0: roots of
// 0.04 v^2 + (5 - b) v + 140), the Jacobian [[0.08 v* + 5, -1], [a b, -a]] =
// [[0, -1], [0.026, -0.1]] has eigenvalues -0.05 +- 0.1533i: a damped
// oscillation of period T = 2 pi / 0.1533 = 41.0 ms. (RS at its rest -70
// has real eigenvalues -0.59, -0.027: no oscillation.) Signatures asserted:
// (a) after a small pulse v crosses v* >= 3 times (subthreshold oscillation)
//     while RS crosses its rest at most once (a sum of two real exponentials
//     changes sign at most once);
// (b) resonance: with A* the single 1 ms pulse threshold (found by
//     bisection), a doublet of 0.95 A* pulses fires when they are one period
//     apart (41 ms: in phase) but not half a period apart (20.5 ms);
// (c) a small step (I = 0.1 < saddle-node rheobase (5-b)^2/0.16 - 140 =
//     0.42) gives no spike, a large one (I = 10) tonic firing.
// With v0 = -65, u0 = b v0 (the project's initial state) RZ starts off its
// rest and fires once near 21 ms before settling, so every protocol starts
// after 300 ms of rest (the oscillation decays as exp(-0.05 t)).
TEST(GoldenIzhikevichLayer, ResonatorOscillatesAndResonates) {
  const auto rz = izhikevich_preset("RZ");
  auto crossings = [](const IzhikevichParams& p, double v_rest, double amp) {
    IzhikevichLayer layer(1, p, kDt);
    std::vector<int> s;
    int n = 0;
    double prev = 0;
    for (long k = 0; k < long(800 / kDt); ++k) {
      double t = k * kDt, x = (t >= 300.0 && t < 301.0) ? amp : 0.0;
      layer.step(&x, s);
      double dev = layer.v(0) - v_rest;
      if (t > 300.0 && std::fabs(dev) > 1e-6) {
        if (prev != 0 && (dev > 0) != (prev > 0)) ++n;
        prev = dev;
      }
    }
    EXPECT_TRUE(s.size() <= 1u);  // at most RZ's settling spike: subthreshold
    return n;
  };
  const int rz_cross = crossings(rz, -62.5, 1.0), rs_cross = crossings(izhikevich_preset("RS"), -70.0, 1.0);
  std::printf("[resonator] rest crossings after a small pulse: RZ %d, RS %d\n", rz_cross, rs_cross);
  EXPECT_GE(rz_cross, 3);
  EXPECT_LE(rs_cross, 1);

  auto pulses = [&](double amp, double gap) {
    return count_in(run(rz, kDt, 700.0,
                        [=](double t) {
                          bool on = (t >= 300.0 && t < 301.0) ||
                                    (gap > 0 && t >= 300.0 + gap && t < 301.0 + gap);
                          return on ? amp : 0.0;
                        }),
                    300.0, 700.0);
  };
  double lo = 0.0, hi = 20.0;
  ASSERT_EQ(pulses(lo, 0), 0u);
  ASSERT_GT(pulses(hi, 0), 0u);
  for (int it = 0; it < 30; ++it) {
    double mid = 0.5 * (lo + hi);
    (pulses(mid, 0) ? hi : lo) = mid;
  }
  const double a = 0.95 * lo;
  std::printf("[resonator] single 1 ms pulse threshold A* = %.4f\n", lo);
  EXPECT_EQ(pulses(a, 0), 0u);
  EXPECT_GT(pulses(a, 41.0), 0u);
  EXPECT_EQ(pulses(a, 20.5), 0u);

  EXPECT_EQ(count_in(run(rz, kDt, 800.0, step_at(300.0, 0.1)), 300.0, 800.0), 0u);
  EXPECT_GE(count_in(run(rz, kDt, 800.0, step_at(300.0, 10.0)), 300.0, 800.0), 20u);
}

// RA (thesis Table 4.1: tau 0.97, K 9): a held input of 0.5 (I = K * 0.5 =
// 4.5) makes it fire (>= 10 spikes) and adapt (mean of the last three ISIs
// >= 1.3x the first ISI); nothing before the step.
TEST(GoldenIzhikevichLayer, RapidlyAdaptingFiresAndAdapts) {
  const auto ra = izhikevich_preset("RA");
  EXPECT_EQ(ra.tau, 0.97);
  EXPECT_EQ(ra.gain, 9.0);
  auto t = run(ra, kDt, kT, step_at(kOn, 0.5));
  auto d = isis(t);
  ASSERT_GE(t.size(), 10u);
  EXPECT_GE(t.front(), kOn);
  EXPECT_GE(mean_last(d, 3), 1.3 * d.front());
}

// Clamps: for every preset, at dt 0.25 ms and 1/35 ms, 1e5 steps of input 0,
// +1e12, -1e12 and alternating +-1e12 (times the gain) keep v in [-1000,
// 1000] and u in [-1e6, 1e6] (the documented clamps), finite; +1e12 fires
// (I saturates at +1e4, and dv >= dt * (1e4 - ...) crosses 30 mV quickly).
TEST(GoldenIzhikevichLayer, ExtremeInputsStayFiniteAndInRange) {
  const double dts[] = {0.25, 1.0 / 35.0};
  for (const std::string& name : izhikevich_preset_names()) {
    for (double dt : dts) {
      for (int mode = 0; mode < 4; ++mode) {
        IzhikevichLayer layer(1, izhikevich_preset(name), dt);
        std::vector<int> s;
        size_t spikes = 0;
        for (long k = 0; k < 100000; ++k) {
          double x = mode == 0 ? 0.0 : mode == 1 ? 1e12 : mode == 2 ? -1e12
                                                  : (k % 2 ? 1e12 : -1e12);
          s.clear();
          layer.step(&x, s);
          spikes += s.size();
          const double v = layer.v(0), u = layer.u(0);
          ASSERT_TRUE(std::isfinite(v) && std::isfinite(u)) << name << " mode " << mode;
          ASSERT_LE(std::fabs(v), kVClamp) << name << " mode " << mode << " step " << k;
          ASSERT_LE(std::fabs(u), kUClamp) << name << " mode " << mode << " step " << k;
        }
        if (mode == 1) {
          EXPECT_GT(spikes, 1000u) << name;
        }
      }
    }
  }
  // A NaN input is treated as 0: same trajectory as a zero input.
  IzhikevichLayer a(1, izhikevich_preset("RS"), 0.25), b(1, izhikevich_preset("RS"), 0.25);
  std::vector<int> s;
  const double nan = std::numeric_limits<double>::quiet_NaN(), zero = 0.0;
  for (int k = 0; k < 1000; ++k) a.step(&nan, s), b.step(&zero, s);
  EXPECT_EQ(a.v(0), b.v(0));
  EXPECT_EQ(a.u(0), b.u(0));
}

// Forward Euler, both updates from the start-of-step values: two steps by
// hand. RS, v0 = -65, u0 = -13, I = 10, dt = 0.5:
//   dv = 0.5 (169 - 325 + 140 + 13 + 10) = 3.5  -> v = -61.5
//   du = 0.5 * 0.02 (0.2 * -65 + 13) = 0      -> u = -13
//   dv = 0.5 (0.04 * 3782.25 - 307.5 + 140 + 13 + 10) = 3.395 -> v = -58.105
//   du = 0.5 * 0.02 (0.2 * -61.5 + 13) = 0.007 -> u = -12.993
// Bound 1e-12: a handful of roundings of numbers ~100.
TEST(GoldenIzhikevichLayer, EulerStepByHand) {
  IzhikevichLayer layer(1, izhikevich_preset("RS"), 0.5);
  std::vector<int> s;
  double x = 10.0;
  layer.step(&x, s);
  EXPECT_NEAR(layer.v(0), -61.5, 1e-12);
  EXPECT_NEAR(layer.u(0), -13.0, 1e-12);
  layer.step(&x, s);
  EXPECT_NEAR(layer.v(0), -58.105, 1e-12);
  EXPECT_NEAR(layer.u(0), -12.993, 1e-12);
  EXPECT_TRUE(s.empty());
  EXPECT_EQ(layer.time_ms(), 1.0);
}

// Weighted layer, 2 -> 1, neuron a 0.02, b 0, c -65, d 2 (b = 0 decouples u:
// u0 = b v0 = 0 and u' = -a u stays 0 until a spike). Then v' = 0.04 v^2 +
// 5 v + 140 + I has equilibria iff 25 - 0.16 (140 + I) >= 0, i.e. the
// rheobase is I* = 25 / 0.16 - 140 = 16.25, and the Euler map has the same
// fixed points. Below it (I = 15.75: roots -67.5 and -57.5) v0 = -65 lies
// between them where v' < 0, so v decays to -67.5 and never fires. Above it
// (I = 16.75) v' = 0.04 (v + 62.5)^2 + (I - 16.25) >= 0.5, so v gains
// >= 0.125 mV per 0.25 ms step and must reach 30 within 190 ms.
// Presynaptic spikes held on every step make the current W s constant.
TEST(GoldenIzhikevichLayer, WeightedLayerFiresIffAboveRheobase) {
  IzhikevichParams p;
  p.a = 0.02, p.b = 0.0, p.c = -65.0, p.d = 2.0, p.tau = 1.0, p.gain = 1.0;
  auto fires = [&](double w0, double w1, std::vector<int> pre) {
    Eigen::MatrixXd w(1, 2);
    w << w0, w1;
    WeightedIzhikevichLayer layer(w, p, 0.25);
    std::vector<int> s;
    for (int k = 0; k < 1600; ++k) layer.step(pre, s);  // 400 ms
    return !s.empty();
  };
  EXPECT_TRUE(fires(10.0, 6.75, {0, 1}));   // 16.75 > 16.25
  EXPECT_FALSE(fires(10.0, 5.75, {0, 1}));  // 15.75 < 16.25
  EXPECT_FALSE(fires(10.0, 6.75, {0}));     // 10 alone
  EXPECT_FALSE(fires(10.0, 6.75, {1}));     // 6.75 alone
  EXPECT_TRUE(fires(16.75, 0.0, {0}));
  EXPECT_FALSE(fires(10.0, 6.75, {}));

  WeightedIzhikevichLayer layer(Eigen::MatrixXd::Ones(1, 2), p, 0.25);
  std::vector<int> s;
  EXPECT_THROW(layer.step({2}, s), eskin::ConfigError);
}

// ISI features by hand: times 0, 10, 30, 60 -> ISIs 10, 20, 30, mean 20,
// sample variance (100 + 0 + 100) / 2 = 100. Exact in double.
TEST(GoldenIzhikevichLayer, SpikeStats) {
  SpikeStats s = spike_stats({0.0, 10.0, 30.0, 60.0});
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(s.mean_isi_ms, 20.0);
  EXPECT_EQ(s.var_isi_ms2, 100.0);
  s = spike_stats({5.0});
  EXPECT_EQ(s.count, 1u);
  EXPECT_EQ(s.mean_isi_ms, 0.0);
  EXPECT_EQ(s.var_isi_ms2, 0.0);
}

// Receptor input by hand (input_scale 10, frame 0.5 ms), row-major:
// Level -> 10 g; RectifiedChange -> 10 max(0, dg) / 0.5 ms = 20 max(0, dg).
// Values are exact binary fractions, so equality is exact.
TEST(GoldenIzhikevichLayer, ReceptorInputModes) {
  Eigen::MatrixXd g(2, 2), prev(2, 2);
  g << 0.5, 0.25, 0.0, 1.0;
  prev << 0.25, 0.5, 0.0, 0.75;
  eskin::NeuronConfig cfg;
  cfg.input_scale = 10.0;
  std::vector<double> out;
  cfg.input = eskin::NeuronInput::Level;
  receptor_input(cfg, g, prev, 0.5, out);
  EXPECT_EQ(out, (std::vector<double>{5.0, 2.5, 0.0, 10.0}));
  cfg.input = eskin::NeuronInput::RectifiedChange;
  receptor_input(cfg, g, prev, 0.5, out);
  EXPECT_EQ(out, (std::vector<double>{5.0, 0.0, 0.0, 5.0}));
  EXPECT_THROW(receptor_input(cfg, g, prev, 0.0, out), eskin::ConfigError);
}

TEST(GoldenIzhikevichLayer, UnknownPresetListsValidNames) {
  try {
    izhikevich_preset("XX");
    FAIL() << "XX accepted";
  } catch (const eskin::ConfigError& e) {
    EXPECT_EQ(e.field(), "neuron.preset");
    for (const char* n : {"RS", "IB", "CH", "FS", "LTS", "TC", "RZ", "RA"})
      EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << n;
  }
  EXPECT_THROW(IzhikevichLayer(1, izhikevich_preset("RS"), 0.0), eskin::ConfigError);
}
