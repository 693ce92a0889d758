// `eskin calibrate` on a Hall scene: the calibration every decoding block
// of the scene needs: seed 002's 6x9 F/T matrix C by least squares
// (pseudo-inverse) from recorded presses or from simulated presses on the
// scene's skin; seed 001's Bz compensation and force polynomials; seed
// 003's force curves. Printed, and written as YAML.
#pragma once

#include <string>

#include "sim/scene.h"

namespace eskin::hall {

struct HallCalibrateOptions {
  std::string from;           // recorded presses (CSV: b1x..b3z uT, fx fy fz N, tx ty tz N*mm)
  std::string out;            // the calibration as YAML (empty: none)
  std::string write_presses;  // the simulated presses as a CSV recording (empty: none)
  int presses = 200;          // simulated presses for the F/T fit
};

// `scene` has a hall: section; `scene_file` names it in the YAML. Throws
// ConfigError when the scene asks for nothing to calibrate or --from does
// not fit it. Returns the process exit code.
int run_hall_calibrate(const sim::Scene& scene, const std::string& scene_file,
                       const HallCalibrateOptions& a);

}  // namespace eskin::hall
