// `eskin locate` on a Hall scene: the seed-000 field table from a
// simulated calibration scan (the scene's locate: grid, Kriging-refined),
// then the contacts of every frame of the scene located: contacts.csv (t,
// contact index, x, y, force; truth alongside) and the mean error of the
// single-contact frames on stdout; table.csv (x, y, then 3 values per
// sensor) if asked.
#pragma once

#include <string>

#include "sim/scene.h"

namespace eskin::hall {

struct HallLocateOptions {
  std::string out = "eskin-out";  // output directory (created)
  int max_contacts = 4;           // contacts searched per frame
  bool table = false;             // also write the interpolated field table
};

// `scene` has a hall: section. Returns the process exit code.
int run_hall_locate(const sim::Scene& scene, const HallLocateOptions& a);

}  // namespace eskin::hall
