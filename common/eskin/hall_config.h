// Shared configuration of a magnetic (Hall) skin: the magnets or magnetised
// films, the elastic structure that carries them (cells), the MLX90393
// sensors with their bus placement, and the decoding settings (baseline,
// calibration matrix, force-curve ranges, localisation grid). The scene
// loader (sim/), the world model, the golden model (host/golden/) and the CLI
// all use these types. hls/ does not include this file.
//
// Units: lengths in mm, forces in N, torques in N*mm, fields in uT, angles
// in rad. Coordinates: x, y across the skin surface, z up (out of the skin);
// sensors sit below the magnets (smaller z).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "eskin/mlx90393_config.h"
#include "eskin/skin_config.h"  // ConfigError

namespace eskin {

using Vec3 = std::array<double, 3>;


// How a magnet's field is modelled (sim/hall_physics.h says why each):
//  Box       uniformly magnetised along body z (magnetised film, block);
//  Cylinder  axially magnetised disc or rod;
//  CentripetalSquare  square film magnetised in plane from its four sides
//            towards its centre (seed 001), zero net dipole moment.
enum class MagnetShape { Box, Cylinder, CentripetalSquare };

struct HallMagnet {
  std::string name;
  MagnetShape shape = MagnetShape::Box;
  // Box: x, y, z extents; Cylinder: diameter, (unused), height;
  // CentripetalSquare: side, side, thickness.
  Vec3 size_mm{1, 1, 1};
  Vec3 centre_mm{0, 0, 0};   // at rest, in world coordinates
  // Remanence Br (T); signed along body z for Box/Cylinder (negative =
  // magnetised downwards); for CentripetalSquare the in-plane magnitude
  // (negative = magnetised outwards).
  double remanence_t = 1.0;
  int cell = 0;              // index of the cell whose motion carries it
};

// The elastic structure under a contact:
//  Film    rigid film on a linear elastic layer (seeds 000, 001): moves by
//          normal/shear force over stiffness and tilts by moment over the
//          tilt stiffness of a uniform foundation (k_normal * a^2 / 12);
//          loaded by the part of each contact's footprint over `footprint_mm`.
//  Pillar  flexure-guided pillar (seed 002): moves along z by its normal
//          force / k_normal; shear force at the top (height pillar_mm above the
//          pivot) tilts it by (pillar_mm * F) / k_tilt; the magnet sits
//          magnet_below_pivot_mm under the pivot. Pillars under a rigid plate
//          share a contact like springs in parallel.
//  Stack   metamaterial block (seed 003): layers in series, softest first;
//          layer i compresses F / k_i until its travel is used up (locks).
enum class CellKind { Film, Pillar, Stack };

struct HallCell {
  std::string name;
  CellKind kind = CellKind::Film;
  Vec3 centre_mm{0, 0, 0};            // top centre (contact point) at rest
  std::array<double, 2> footprint_mm{10, 10};  // Film: loaded area (x, y)
  double k_normal_n_per_mm = 1.0;     // Film, Pillar
  double k_shear_n_per_mm = 1.0;      // Film
  double k_tilt_nmm_per_rad = 0.0;    // Pillar
  double pillar_mm = 0.0;             // Pillar: pivot to top
  double magnet_below_pivot_mm = 0.0; // Pillar: pivot to magnet centre
  std::vector<double> layer_k_n_per_mm;  // Stack, softest first
  std::vector<double> layer_travel_mm;   // Stack, travel before locking

  // Stack: total compression (mm) under normal force f >= 0 (N).
  double stack_compression_mm(double f) const;
  // Stack: force at which layer i locks (N); the last is the full scale.
  std::vector<double> stack_lock_forces_n() const;
};

struct HallSensor {
  std::string name;
  Vec3 position_mm{0, 0, 0};  // Hall plate centre
  int bus = 0;                // I2C bus index on the FPGA
  int mux_address = -1;       // TCA9548A 7-bit address, -1 when none
  int mux_channel = 0;        // 0..7 when behind a mux
  int i2c_address = 0x0C;     // MLX90393 7-bit address
};

// What the FPGA and golden chain decode from the samples.
enum class HallDecode { Baseline, Decouple, Wrench, ForceCurve, Locate };

// Seed 001 decoupling coefficients (Rx, Ry use Bz' = k1*Bz + c1; Sz uses
// Bz'' = k2*Bz + c2), plus per-axis polynomial force curves
// F = sum_j poly[j] * delta^(j+1) of the change from the unloaded value.
struct DecoupleParams {
  double k1 = 1.0, c1_ut = 0.0, k2 = 1.0, c2_ut = 0.0;
  std::array<std::vector<double>, 3> poly;  // Fx(dRx), Fy(dRy), Fn(dSz)
};

// Seed 003 piecewise-linear force curve of one cell: breakpoints of the
// field change |B - B0| (uT, ascending) and force (N).
struct ForceCurve {
  std::vector<double> db_ut;
  std::vector<double> force_n;
};

struct HallConfig {
  std::vector<HallMagnet> magnets;
  std::vector<HallCell> cells;
  std::vector<HallSensor> sensors;
  bool rigid_plate = false;           // Pillar cells share one rigid plate
  Vec3 geomagnetic_ut{20.0, 0.0, -45.0};
  mlx90393::Config mlx;               // one setting for every sensor
  // White noise each sensor adds (uT RMS per axis) at the `mlx` setting.
  Vec3 noise_rms_ut{1.0, 1.0, 1.6};
  std::vector<HallDecode> decode;     // blocks the scene asks for
  // Calibration results carried by the scene (optional; eskin calibrate
  // writes them): 6x9 row-major C (N, N*mm per uT), decoupling, curves.
  std::vector<double> wrench_matrix;
  DecoupleParams decouple;
  std::vector<ForceCurve> force_curves;   // one per Stack cell
  // Localisation (seed 000): the calibration scan's grid pitch and force,
  // and the interpolated table's subdivision of that pitch.
  double scan_pitch_mm = 4.4;
  double scan_normal_n = 2.0;
  int table_subdivision = 10;
  std::array<double, 4> area_mm{-110, -110, 110, 110};  // x0, y0, x1, y1

  bool wants(HallDecode d) const;
  int bus_count() const;
};

// The noise at another OSR/DIG_FILT: white noise averaged over the
// 2^OSR * (2 + 2^DIG_FILT) conversions the datasheet's timing formula counts,
// so RMS scales with 1/sqrt of that count (an assumption of the model).
Vec3 scaled_noise_ut(const Vec3& noise, const mlx90393::Config& from, const mlx90393::Config& to);

const char* to_string(MagnetShape s);
const char* to_string(CellKind k);
const char* to_string(HallDecode d);

// Throws ConfigError naming the first offending field (prefixed, e.g.
// "hall.sensors[3].i2c_address").
void validate(const HallConfig& h, const std::string& prefix = "hall");

}  // namespace eskin
