// The Hall golden chain (eskin golden/calibrate/locate/simulate): simulated
// calibration of each decoding block on the scene's own skin (the sampler's
// device-quantised, noisy frames), then the scene's frames through baseline
// and decoding, scored against the world's ground truth.
#pragma once

#include <string>
#include <vector>

#include "host/golden/contact_locate.h"
#include "host/golden/ft_calibrate.h"
#include "host/golden/hall_decouple.h"
#include "sim/hall_sampler.h"
#include "sim/hall_world.h"

namespace eskin::hall {

// Sets OSR / DIG_FILT (-1: keep) and rescales the sensors' noise to it
// (scaled_noise_ut); throws ConfigError for an illegal pair.
void apply_speed(HallConfig& h, int osr, int dig_filt);

// Mean field (uT per sensor) of `frames` noisy quantised frames under a load.
std::vector<Vec3> mean_field(const sim::HallWorld& w, sim::HallSampler& s,
                             const std::vector<sim::ContactLoad>& contacts,
                             const std::vector<sim::PlateWrench>& plate, int frames);

// Seed 001: presses over a normal x shear grid at the single cell.
struct DecoupleCalibration {
  DecoupleParams params;
  Vec3 rest_film_ut{0, 0, 1};  // unloaded film field (geomagnetic removed)
  double shear_fs_n = 1, normal_fs_n = 1;
};
DecoupleCalibration calibrate_decouple(const sim::HallWorld& w, uint64_t seed);

// Seed 002: random wrenches within the stated ranges on the plate.
struct WrenchCalibration {
  golden::FtMatrix c = golden::FtMatrix::Zero();
  golden::Vec6 full_scale = golden::Vec6::Ones();  // per axis, the calibration range
  int presses = 0;
};
struct WrenchPresses {
  std::vector<golden::Vec9> db_ut;    // baseline-removed fields
  std::vector<golden::Vec6> wrench;   // Fx Fy Fz (N) Tx Ty Tz (N*mm)
};
// The calibration ranges (the scene's stimuli stay inside them).
golden::Vec6 wrench_calibration_range();
WrenchPresses simulate_wrench_presses(const sim::HallWorld& w, uint64_t seed, int presses);
WrenchCalibration calibrate_wrench(const sim::HallWorld& w, uint64_t seed, int presses = 200);
// Recorded presses: CSV lines of b1x..b3z (uT, baseline removed), fx fy fz tx ty tz.
WrenchCalibration calibrate_wrench_csv(const std::string& path);

// Seed 003: a force sweep on every Stack cell.
std::vector<ForceCurve> calibrate_force_curves(const sim::HallWorld& w, uint64_t seed,
                                               int per_range = 4);

// Seed 000: the calibration scan and its Kriging table.
golden::ContactLocator calibrate_locator(const sim::HallWorld& w, uint64_t seed);

// Stimuli active at t (count), and whether all of them are at full force
// (the frames scored against the truth are these steady ones).
int active_stimuli(const sim::HallScene& s, double t, bool& steady);

// Runs the scene's frames through the golden chain; prints figures, writes
// per-frame outputs (NDJSON) to out_dir.
int run_hall_golden(const sim::HallWorld& w, double duration_s, uint64_t seed, const std::string& out_dir);

}  // namespace eskin::hall
