#include "izhikevich_layer.h"

#include <algorithm>
#include <cmath>

#include "eskin/skin_config.h"

namespace eskin::golden {

const std::vector<std::string>& izhikevich_preset_names() {
  static const std::vector<std::string> names = {"RS", "IB", "CH", "FS", "LTS", "TC", "RZ", "RA"};
  return names;
}

IzhikevichParams izhikevich_preset(const std::string& name) {
  //                      a     b      c      d     tau   gain
  if (name == "RS") return {0.02, 0.2, -65.0, 8.0, 1.0, 1.0};    // regular spiking
  if (name == "IB") return {0.02, 0.2, -55.0, 4.0, 1.0, 1.0};    // intrinsically bursting
  if (name == "CH") return {0.02, 0.2, -50.0, 2.0, 1.0, 1.0};    // chattering
  if (name == "FS") return {0.1, 0.2, -65.0, 2.0, 1.0, 1.0};     // fast spiking
  if (name == "LTS") return {0.02, 0.25, -65.0, 2.0, 1.0, 1.0};  // low-threshold spiking
  if (name == "TC") return {0.02, 0.25, -65.0, 0.05, 1.0, 1.0};  // thalamo-cortical
  if (name == "RZ") return {0.1, 0.26, -65.0, 2.0, 1.0, 1.0};    // resonator
  if (name == "RA") return {0.02, 0.25, -55.0, 0.05, 0.97, 9.0}; // thesis rapidly adapting
  std::string list;
  for (const auto& n : izhikevich_preset_names()) list += (list.empty() ? "" : ", ") + n;
  throw ConfigError("neuron.preset", "expected one of " + list + "; got '" + name + "'");
}

bool IzhikevichState::step(const IzhikevichParams& p, double dt_ms, double current) {
  const double I = std::isnan(current) ? 0.0 : std::clamp(current, -kMaxCurrent, kMaxCurrent);
  const double dv = p.tau * dt_ms * (0.04 * v * v + 5.0 * v + 140.0 - u + I);
  const double du = p.tau * dt_ms * p.a * (p.b * v - u);
  v = std::clamp(v + dv, -kVClamp, kVClamp);
  u = std::clamp(u + du, -kUClamp, kUClamp);
  if (v < kVPeak) return false;
  v = p.c;
  u = std::clamp(u + p.d, -kUClamp, kUClamp);
  return true;
}

IzhikevichLayer::IzhikevichLayer(int neurons, IzhikevichParams p, double dt_ms)
    : p_(p), dt_ms_(dt_ms) {
  if (neurons < 1)
    throw ConfigError("neuron.count", "expected >= 1 neuron, got " + std::to_string(neurons));
  if (!(dt_ms > 0.0 && dt_ms <= 10.0))
    throw ConfigError("neuron.dt_ms", "expected 0 < dt <= 10 ms, got " + std::to_string(dt_ms));
  IzhikevichState s0;
  s0.v = kV0;
  s0.u = p.b * kV0;
  state_.assign(size_t(neurons), s0);
}

void IzhikevichLayer::step(const double* input, std::vector<int>& spiked) {
  for (size_t i = 0; i < state_.size(); ++i)
    if (state_[i].step(p_, dt_ms_, p_.gain * input[i])) spiked.push_back(int(i));
  ++steps_;
}

WeightedIzhikevichLayer::WeightedIzhikevichLayer(Eigen::MatrixXd weights, IzhikevichParams p,
                                                 double dt_ms)
    : w_(std::move(weights)), layer_(int(w_.rows()), p, dt_ms) {
  if (w_.cols() < 1) throw ConfigError("neuron.weights", "expected >= 1 input column");
  if (!w_.allFinite()) throw ConfigError("neuron.weights", "expected finite weights");
  s_ = Eigen::VectorXd::Zero(w_.cols());
}

void WeightedIzhikevichLayer::step(const std::vector<int>& pre_spiked, std::vector<int>& spiked) {
  s_.setZero();
  for (int j : pre_spiked) {
    if (j < 0 || j >= s_.size())
      throw ConfigError("neuron.pre_spiked", "expected indices 0.." +
                                                 std::to_string(s_.size() - 1) + ", got " +
                                                 std::to_string(j));
    s_[j] = 1.0;
  }
  drive_ = w_ * s_;
  layer_.step(drive_.data(), spiked);
}

void receptor_input(const NeuronConfig& cfg, const Eigen::MatrixXd& g,
                    const Eigen::MatrixXd& g_prev, double frame_ms, std::vector<double>& out) {
  if (!(frame_ms > 0.0))
    throw ConfigError("neuron.frame_ms", "expected > 0 ms, got " + std::to_string(frame_ms));
  const bool change = cfg.input == NeuronInput::RectifiedChange;
  if (change && (g_prev.rows() != g.rows() || g_prev.cols() != g.cols()))
    throw ConfigError("neuron.g_prev", "expected a " + std::to_string(g.rows()) + "x" +
                                           std::to_string(g.cols()) + " previous frame");
  out.resize(size_t(g.size()));
  size_t k = 0;
  for (Eigen::Index i = 0; i < g.rows(); ++i)
    for (Eigen::Index j = 0; j < g.cols(); ++j, ++k)
      out[k] = change ? cfg.input_scale * std::max(0.0, (g(i, j) - g_prev(i, j)) / frame_ms)
                      : cfg.input_scale * g(i, j);
}

SpikeStats spike_stats(const std::vector<double>& t) {
  SpikeStats s;
  s.count = t.size();
  if (t.size() < 2) return s;
  const double n = double(t.size() - 1);
  s.mean_isi_ms = (t.back() - t.front()) / n;
  if (t.size() < 3) return s;
  double ss = 0.0;
  for (size_t k = 1; k < t.size(); ++k) {
    double e = (t[k] - t[k - 1]) - s.mean_isi_ms;
    ss += e * e;
  }
  s.var_isi_ms2 = ss / (n - 1.0);
  return s;
}

}  // namespace eskin::golden
