// Scores decoded frames against a scene's ground truth: per-taxel pressure
// error over steady windows, ghost taxels with and without correction, and
// spike statistics. Knows nothing of the world model: ground truth comes in
// through a callback, so real captures with external truth work too.
#pragma once

#include <functional>
#include <vector>

#include "eskin/skin_config.h"
#include "host/golden/golden_decoder.h"

namespace eskin::golden {

// Ground-truth pressure (kPa, row-major) of every taxel at sample n.
using TruthFn = std::function<void(size_t n, std::vector<double>& kpa)>;

struct TaxelScore {
  size_t steady_frames = 0;   // frames whose window saw constant truth
  double rms_error_kpa = 0;   // over steady frames where truth or decode is lit
  double max_error_kpa = 0;
};

struct DecodeScore {
  size_t frames = 0;
  size_t steady_frames = 0;
  std::vector<TaxelScore> taxel;     // row-major
  // A taxel is lit when its conductance fraction exceeds decoder.ghost_threshold.
  size_t ghost_taxel_frames_raw = 0; // lit, truth unlit: product reconstruction
  size_t ghost_taxel_frames = 0;     // same after ghost correction
  size_t ghost_frames_raw = 0;       // steady frames with >= 1 ghost (raw)
  size_t ghost_frames = 0;           // steady frames with >= 1 ghost (corrected)
  size_t missed_taxel_frames = 0;    // truth lit, decode (corrected) unlit
  double worst_rms_error_kpa() const;
  double worst_max_error_kpa() const;
};

class DecodeScorer {
 public:
  DecodeScorer(const SkinConfig& skin, const DecoderConfig& dec, TruthFn truth);
  void add(const Frame& f);
  DecodeScore score() const;

 private:
  bool lit(double kpa) const;
  SkinConfig skin_;
  DecoderConfig dec_;
  TruthFn truth_;
  DecodeScore s_;
  std::vector<double> sq_sum_;
  std::vector<size_t> err_n_;
  std::vector<double> a_, b_, c_;
};

}  // namespace eskin::golden
