#include "host/golden/hall_baseline.h"

namespace eskin::golden {

std::vector<Vec3> frame_ut(const HallFrame& f, const mlx90393::Config& c) {
  std::vector<Vec3> out;
  for (const auto& s : f) out.push_back(sample_ut(c, s));
  return out;
}

HallBaseline::HallBaseline(size_t sensors, int capture)
    : capture_(capture), sum_(sensors, Vec3{0, 0, 0}), mean_(sensors, Vec3{0, 0, 0}) {}

void HallBaseline::set(const std::vector<Vec3>& baseline) {
  mean_ = baseline;
  seen_ = capture_;
}

bool HallBaseline::push(const std::vector<Vec3>& frame, std::vector<Vec3>& delta) {
  if (capturing()) {
    for (size_t s = 0; s < frame.size(); ++s)
      for (size_t a = 0; a < 3; ++a) sum_[s][a] += frame[s][a];
    if (++seen_ == capture_)
      for (size_t s = 0; s < frame.size(); ++s)
        for (size_t a = 0; a < 3; ++a) mean_[s][a] = sum_[s][a] / capture_;
    return false;
  }
  delta.resize(frame.size());
  for (size_t s = 0; s < frame.size(); ++s)
    for (size_t a = 0; a < 3; ++a) delta[s][a] = frame[s][a] - mean_[s][a];
  return true;
}

}  // namespace eskin::golden
