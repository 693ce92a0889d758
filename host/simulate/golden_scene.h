// `eskin golden` on a DTMF skin: the scene's world model through the
// double-precision golden decoder; amplitudes, taxels and spikes written as
// NDJSON and CSV, and a summary scored against the scene's ground truth on
// stdout.
#pragma once

#include <string>

#include "sim/scene.h"

namespace eskin::simulate {

// `scene`: the skin's scene with the command line's decoder overrides;
// decoder.variant auto resolves to the most accurate for the skin.
// `scene_file` names it in the summary; `out_dir` is created. Returns the
// process exit code.
int run_golden_scene(sim::Scene scene, const std::string& scene_file, const std::string& out_dir,
                     bool ghost_correct);

}  // namespace eskin::simulate
