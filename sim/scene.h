// A scene: a DTMF skin with its decoder and neuron settings, and/or a
// magnetic (Hall) skin (sim/hall_scene.h); the stimuli over time and the
// outputs wanted. Loaded from YAML (format: docs/scenes.md) and
// fully validated before anything runs: every error names the file, the
// line and column, the field path and what was expected.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "eskin/neuron_config.h"
#include "eskin/skin_config.h"
#include "sim/hall_scene.h"

namespace eskin::sim {

// One touch: pressure ramps linearly 0 -> pressure_kpa over ramp_s, holds for
// hold_s, ramps back to 0 over release_s. Either on one taxel (row, col), or
// a disk of uniform pressure centred at (x, y) whose pressure each taxel
// samples as the fraction of its 1x1-pitch cell that the disk covers.
struct Press {
  bool at_position = false;   // false: taxel (row, col); true: position (x, y)
  int row = 0, col = 0;
  double x = 0, y = 0;        // taxel-pitch units: x along columns, y along rows
  double radius = 0.5;        // contact disk radius (taxel pitches), positions only
  double pressure_kpa = 0;
  double t_start_s = 0, ramp_s = 0.005, hold_s = 0.02, release_s = 0.005;

  double end_s() const { return t_start_s + ramp_s + hold_s + release_s; }
  // Envelope 0..1 at time t (linear ramps; 0 outside the touch).
  double envelope(double t) const;
};

// A disk of uniform pressure moving at constant speed from (x0, y0) to
// (x1, y1) over duration_s, starting at t_start_s; its pressure ramps up over
// the first ramp_s and down over the last ramp_s of the duration.
struct Slide {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // taxel-pitch units (x: cols, y: rows)
  double radius = 0.5;
  double pressure_kpa = 0;
  double t_start_s = 0, duration_s = 0.1, ramp_s = 0.005;

  double end_s() const { return t_start_s + duration_s; }
  double envelope(double t) const;
  // Disk centre at time t (clamped to the start/end points outside the slide).
  void centre(double t, double& x, double& y) const;
};

struct Outputs {
  bool amplitudes = true, taxels = true, spikes = false;
};

struct Scene {
  std::string file;  // path it came from (for messages)
  std::string name;
  uint64_t seed = 1;
  double duration_s = 0;
  bool has_skin = true;   // false: a Hall-only scene (no skin: section)
  SkinConfig skin;        // carriers always resolved (also for `carriers: auto`)
  DecoderConfig decoder;
  NeuronConfig neuron;
  std::vector<Press> presses;
  std::vector<Slide> slides;
  Outputs outputs;
  bool has_hall = false;  // a hall: section (magnetic skin) was given
  HallScene hall;
};

// what(): "FILE:LINE:COL: FIELD: expected ..., got ...". line/col are 1-based
// (0 when unknown, e.g. the file could not be opened).
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, int line, int col, std::string field, const std::string& what);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  int col() const { return col_; }
  const std::string& field() const { return field_; }

 private:
  std::string file_;
  int line_, col_;
  std::string field_;
};

// Parse and validate; throws SceneError.
Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& yaml_text, const std::string& file_for_messages);

// The `skin:` section of a file (a skin file, or a scene file; other top-level
// keys are ignored, a top-level `decoder.window` is used for `carriers: auto`).
SkinConfig load_skin(const std::string& path);
SkinConfig parse_skin(const std::string& yaml_text, const std::string& file_for_messages);

// Mean pressure (kPa) over the unit cell of taxel (row, col) under a disk of
// uniform pressure p centred at (x, y): p times the covered fraction of the
// cell, computed by integrating over a fixed sub-grid of the cell.
double disk_cover_fraction(double x, double y, double radius, int row, int col);

}  // namespace eskin::sim
