// The golden decoding chain in double precision, one ADC code at a time:
// sliding per-carrier amplitudes -> normalised line amplitudes -> taxels
// (thesis product and calibrated pressure) -> ghost correction -> Izhikevich
// receptor layer. Built only from host/golden blocks; never from hls/.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "host/golden/ghost_filter.h"
#include "host/golden/izhikevich_layer.h"
#include "host/golden/sdft_bank.h"

namespace eskin::golden {

struct GoldenOptions {
  bool taxels = true;        // reconstruct taxels (needed for spikes too)
  bool ghost_correct = true; // pressure from the ghost filter's active sites
  bool spikes = false;       // run the receptor layer
};

// One decoded frame, emitted every `hop` samples once the window is full.
struct Frame {
  size_t sample = 0;            // index of the newest sample in the window
  Eigen::VectorXd amp_lsb;      // per-carrier magnitude, ADC LSB peak (rows, cols)
  Eigen::VectorXd line_g;       // amp_lsb / full_carrier_lsb: line conductance sums
  Eigen::MatrixXd product;      // thesis taxel product amp(row) * amp(col), LSB^2
  Eigen::MatrixXd pressure_raw; // calibrated pressure without ghost correction, kPa
  Eigen::MatrixXd pressure;     // calibrated, ghost-corrected pressure, kPa
  std::vector<int> spiked;      // taxels (row-major) whose neuron fired this frame
  std::vector<int> spiked2;     // same for the second (weighted) layer
};

class GoldenDecoder {
 public:
  GoldenDecoder(const SkinConfig& skin, const DecoderConfig& dec, const NeuronConfig& neuron,
                GoldenOptions opt);
  // Feeds one ADC code; true when a new frame is ready in frame().
  bool push(int code);
  const Frame& frame() const { return frame_; }
  // Spike times (ms since the first sample) per taxel, row-major.
  const std::vector<std::vector<double>>& spike_times_ms() const { return spike_times_; }
  // The second layer's spike times, per taxel.
  const std::vector<std::vector<double>>& spike_times2_ms() const { return spike_times2_; }
  double frame_period_ms() const { return frame_period_ms_; }

 private:
  void reconstruct();
  void run_neurons();

  SkinConfig skin_;
  DecoderConfig dec_;
  NeuronConfig neuron_cfg_;
  GoldenOptions opt_;
  std::unique_ptr<SdftBank> bank_;
  std::unique_ptr<GhostFilter> ghost_;
  std::unique_ptr<IzhikevichLayer> neurons_;
  std::unique_ptr<WeightedIzhikevichLayer> layer2_;
  int neuron_substeps_ = 1;
  double frame_period_ms_ = 0;
  double mid_code_ = 0;
  size_t seen_ = 0;
  Frame frame_;
  Eigen::VectorXd prev_taxel_g_;
  std::vector<double> neuron_input_;
  std::vector<std::vector<double>> spike_times_, spike_times2_;
};

// The second layer's weights (taxels x taxels, row-major): the 3x3 kernel
// of `l2` (centre on the diagonal, surround for the 8 grid neighbours).
Eigen::MatrixXd layer2_weights(int rows, int cols, const Layer2Config& l2);

}  // namespace eskin::golden
