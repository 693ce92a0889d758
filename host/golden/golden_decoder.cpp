#include "host/golden/golden_decoder.h"

#include <algorithm>
#include <cmath>

#include "host/golden/taxel_reconstruct.h"

namespace eskin::golden {

GoldenDecoder::GoldenDecoder(const SkinConfig& skin, const DecoderConfig& dec,
                             const NeuronConfig& neuron, GoldenOptions opt)
    : skin_(skin), dec_(dec), neuron_cfg_(neuron), opt_(opt) {
  validate(skin_);
  validate(dec_, skin_);
  const double fs = skin_.adc.rate_hz;
  bank_ = make_sdft_bank(dec_.variant, skin_.carrier_freqs_hz(), fs, dec_);
  mid_code_ = skin_.adc.mid_code();
  frame_period_ms_ = 1000.0 * dec_.hop / fs;
  const int taxels = skin_.rows * skin_.cols;
  if (opt_.spikes) opt_.taxels = true;
  if (opt_.taxels && opt_.ghost_correct) {
    GhostFilterConfig g;
    g.onset = dec_.ghost_onset;
    g.release = dec_.ghost_threshold;
    g.lookback = std::max(1, dec_.window / dec_.hop);
    ghost_ = std::make_unique<GhostFilter>(skin_.rows, skin_.cols, g);
  }
  if (opt_.spikes) {
    // The neuron step divides the frame period into whole sub-steps.
    double dt = neuron_cfg_.dt_ms > 0 ? neuron_cfg_.dt_ms : frame_period_ms_;
    neuron_substeps_ = std::max(1, int(std::lround(frame_period_ms_ / dt)));
    dt = frame_period_ms_ / neuron_substeps_;
    neurons_ = std::make_unique<IzhikevichLayer>(taxels, izhikevich_preset(neuron_cfg_.preset), dt);
    layer2_ = std::make_unique<WeightedIzhikevichLayer>(
        layer2_weights(skin_.rows, skin_.cols, neuron_cfg_.layer2),
        izhikevich_preset(neuron_cfg_.layer2.preset), dt);
    neuron_input_.assign(size_t(taxels), 0.0);
    spike_times_.assign(size_t(taxels), {});
    spike_times2_.assign(size_t(taxels), {});
    prev_taxel_g_ = Eigen::VectorXd::Zero(taxels);
  }
  frame_.amp_lsb = Eigen::VectorXd::Zero(skin_.carriers());
}

bool GoldenDecoder::push(int code) {
  bank_->push(double(code) - mid_code_);
  const size_t n = seen_++;
  if (!bank_->full() || (n + 1 - size_t(dec_.window)) % size_t(dec_.hop) != 0) return false;
  frame_.sample = n;
  for (int k = 0; k < skin_.carriers(); ++k) frame_.amp_lsb[k] = bank_->magnitude(k);
  frame_.line_g = frame_.amp_lsb / skin_.full_carrier_lsb();
  frame_.spiked.clear();
  if (opt_.taxels) reconstruct();
  if (opt_.spikes) run_neurons();
  return true;
}

void GoldenDecoder::reconstruct() {
  const Eigen::VectorXd rows = frame_.amp_lsb.head(skin_.rows);
  const Eigen::VectorXd cols = frame_.amp_lsb.tail(skin_.cols);
  frame_.product = taxel_product(rows, cols);
  const Eigen::VectorXd row_g = frame_.line_g.head(skin_.rows);
  const Eigen::VectorXd col_g = frame_.line_g.tail(skin_.cols);
  frame_.pressure_raw = taxel_pressure(row_g, col_g, skin_.conductance);
  if (!ghost_) {
    frame_.pressure = frame_.pressure_raw;
    return;
  }
  const Eigen::MatrixXd& g = ghost_->update(row_g, col_g);
  frame_.pressure = g.unaryExpr([this](double v) { return skin_.conductance.inverse(v); });
}

void GoldenDecoder::run_neurons() {
  // Neuron input: the taxel's conductance fraction (ghost-corrected when the
  // filter runs), or its rectified rate of change per ms.
  const int taxels = skin_.rows * skin_.cols;
  Eigen::VectorXd g(taxels);
  for (int i = 0; i < skin_.rows; ++i)
    for (int j = 0; j < skin_.cols; ++j)
      g[i * skin_.cols + j] = skin_.conductance.g(frame_.pressure(i, j));
  for (int t = 0; t < taxels; ++t) {
    double x = g[t];
    if (neuron_cfg_.input == NeuronInput::RectifiedChange)
      x = std::max(0.0, (g[t] - prev_taxel_g_[t]) / frame_period_ms_);
    neuron_input_[size_t(t)] = neuron_cfg_.input_scale * x;
  }
  prev_taxel_g_ = g;
  std::vector<int> fired, fired2;
  frame_.spiked2.clear();
  const auto record = [](std::vector<double>& times, std::vector<int>& frame_list, int t,
                         double t_ms) {
    times.push_back(t_ms);
    if (std::find(frame_list.begin(), frame_list.end(), t) == frame_list.end())
      frame_list.push_back(t);
  };
  for (int s = 0; s < neuron_substeps_; ++s) {
    fired.clear();
    fired2.clear();
    neurons_->step(neuron_input_.data(), fired);
    layer2_->step(fired, fired2);
    // Sub-step s of this frame ends (substeps - 1 - s) steps before the
    // frame's newest sample.
    const double t_ms = 1000.0 * double(frame_.sample + 1) / skin_.adc.rate_hz -
                        double(neuron_substeps_ - 1 - s) * frame_period_ms_ / neuron_substeps_;
    for (int t : fired) record(spike_times_[size_t(t)], frame_.spiked, t, t_ms);
    for (int t : fired2) record(spike_times2_[size_t(t)], frame_.spiked2, t, t_ms);
  }
}

Eigen::MatrixXd layer2_weights(int rows, int cols, const Layer2Config& l2) {
  const int n = rows * cols;
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const int r = i + di, c = j + dj;
          if (r < 0 || r >= rows || c < 0 || c >= cols) continue;
          w(i * cols + j, r * cols + c) = (di == 0 && dj == 0) ? l2.centre : l2.surround;
        }
  return w;
}

}  // namespace eskin::golden
