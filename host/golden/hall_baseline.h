// Golden Hall baseline (seeds 001, 002): the field a sensor sees with no load
// (geomagnetic field, plus the magnets' rest field where the magnets are in
// place) is averaged over the first `capture` frames and subtracted from every
// later frame, leaving the change the contact causes. Double precision.
#pragma once

#include <vector>

#include "eskin/hall_sample.h"

namespace eskin::golden {

// Field (uT) of every sample of a frame under the sensors' setting.
std::vector<Vec3> frame_ut(const HallFrame& f, const mlx90393::Config& c);

class HallBaseline {
 public:
  HallBaseline(size_t sensors, int capture);
  // Feeds one frame (uT per sensor). While capturing returns false; after,
  // writes frame - baseline to `delta` and returns true.
  bool push(const std::vector<Vec3>& frame, std::vector<Vec3>& delta);
  bool capturing() const { return seen_ < capture_; }
  const std::vector<Vec3>& baseline() const { return mean_; }
  void set(const std::vector<Vec3>& baseline);

 private:
  int capture_;
  int seen_ = 0;
  std::vector<Vec3> sum_, mean_;
};

}  // namespace eskin::golden
