// Izhikevich spiking neurons in double precision (Izhikevich 2003, "Simple
// model of spiking neurons"; thesis Table 4.1 for the RA receptor).
//
//   v' = tau (0.04 v^2 + 5 v + 140 - u + I),  u' = tau a (b v - u)   (v mV, t ms)
//   if v >= 30 mV: spike, v <- c, u <- u + d
//
// Integration scheme (fixed project-wide; the fixed-point kernel in hls/
// uses the same one, so spike times agree within one step): forward Euler
// with step dt (ms), both updates from the values at the start of the step:
//   dv = tau dt (0.04 v^2 + 5 v + 140 - u + I);  du = tau dt a (b v - u)
//   v += dv;  u += du;  clamp;  if v >= 30: spike at this step's END time
//   (step_index + 1) * dt, v = c, u += d.
// Initial state: v0 = -65 mV for every preset, u0 = b v0 (Izhikevich's own
// convention; a preset with c > -65 thus starts slightly below its reset).
//
// Clamps (so that no input, however large, gives NaN/inf or runaway):
//   * I = gain * input is clamped to [-kMaxCurrent, +kMaxCurrent] = +-1e4;
//     a NaN input counts as 0.
//   * v is clamped to [-kVClamp, +kVClamp] = +-1000 mV after the update and
//     before the threshold test (v overshoots far past 30 within one step
//     for large I; 0.04 * 1000^2 = 4e4 stays finite).
//   * u is clamped to [-kUClamp, +kUClamp] = +-1e6 after the update and after
//     the reset increment (u - b v can reach d / (tau dt a) when the neuron
//     fires every step; that is 4e5 for RS at dt = 1e-3 ms).
// Within these clamps every term is finite, so v and u stay in range.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "eskin/neuron_config.h"

namespace eskin::golden {

constexpr double kMaxCurrent = 1e4;  // |I| clamp
constexpr double kVClamp = 1000.0;   // |v| clamp, mV
constexpr double kUClamp = 1e6;      // |u| clamp
constexpr double kVPeak = 30.0;      // spike threshold, mV
constexpr double kV0 = -65.0;        // initial membrane potential, mV

// Presets: RS IB CH FS LTS TC RZ (Izhikevich 2003, tau = gain = 1) and RA
// (thesis Table 4.1: a 0.02, b 0.25, c -55, d 0.05, tau 0.97, gain K = 9).
// Throws eskin::ConfigError("neuron.preset", ...) listing the valid names.
IzhikevichParams izhikevich_preset(const std::string& name);
const std::vector<std::string>& izhikevich_preset_names();

// One neuron's state and the shared update (exposed so both layers and the
// tests use exactly one implementation of the scheme above).
struct IzhikevichState {
  double v = kV0, u = 0.0;
  // Advances one step with current I (already gain-scaled); true on a spike.
  bool step(const IzhikevichParams& p, double dt_ms, double current);
};

// Receptor layer: one neuron per input, I = gain * input[i].
class IzhikevichLayer {
 public:
  // Throws eskin::ConfigError for neurons < 1 or dt_ms not in (0, 10].
  IzhikevichLayer(int neurons, IzhikevichParams p, double dt_ms);
  // input has size() values; appends the indices that spiked this step.
  void step(const double* input, std::vector<int>& spiked);
  double v(int i) const { return state_[size_t(i)].v; }
  double u(int i) const { return state_[size_t(i)].u; }
  double time_ms() const { return double(steps_) * dt_ms_; }
  int size() const { return int(state_.size()); }
  const IzhikevichParams& params() const { return p_; }

 private:
  IzhikevichParams p_;
  double dt_ms_;
  long long steps_ = 0;
  std::vector<IzhikevichState> state_;
};

// Second layer: I = gain * (W s), W is n_out x n_in, s_j = 1 if presynaptic
// neuron j spiked this step (else 0); then the same neuron update.
class WeightedIzhikevichLayer {
 public:
  WeightedIzhikevichLayer(Eigen::MatrixXd weights, IzhikevichParams p, double dt_ms);
  // pre_spiked: indices (0..n_in-1) of presynaptic neurons that spiked.
  // Throws eskin::ConfigError for an index out of range.
  void step(const std::vector<int>& pre_spiked, std::vector<int>& spiked);
  double v(int i) const { return layer_.v(i); }
  double u(int i) const { return layer_.u(i); }
  double time_ms() const { return layer_.time_ms(); }
  int size() const { return layer_.size(); }
  const Eigen::MatrixXd& weights() const { return w_; }

 private:
  Eigen::MatrixXd w_;
  IzhikevichLayer layer_;
  Eigen::VectorXd s_, drive_;
};

// Receptor-layer input per taxel, row-major (rows * cols values), from the
// corrected taxel g-matrix of this frame and of the previous frame, as
// NeuronConfig::input says:
//   Level:           input = input_scale * g
//   RectifiedChange: input = input_scale * max(0, (g - g_prev) / frame_ms)
//                    (change per ms: responds to onsets, silent when held)
// Throws eskin::ConfigError if frame_ms <= 0 or the matrices differ in size.
void receptor_input(const NeuronConfig& cfg, const Eigen::MatrixXd& g,
                    const Eigen::MatrixXd& g_prev, double frame_ms, std::vector<double>& out);

// Spike-train features (thesis §4.3): count, mean inter-spike interval and
// its sample variance (n - 1 denominator, as MATLAB var). With fewer than 2
// spikes the mean is 0; with fewer than 3 the variance is 0.
struct SpikeStats {
  size_t count = 0;
  double mean_isi_ms = 0.0;
  double var_isi_ms2 = 0.0;
};
SpikeStats spike_stats(const std::vector<double>& spike_times_ms);

}  // namespace eskin::golden
