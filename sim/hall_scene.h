// The `hall:` section of a scene: a magnetic skin (eskin/hall_config.h) and
// its stimuli over time. Format: docs/scenes.md, "Hall skins".
#pragma once

#include <array>
#include <vector>

#include "eskin/hall_config.h"
#include "sim/hall_physics.h"

namespace eskin::sim {

// Trapezoid 0 -> 1 -> 0 starting at t0: ramp up over `ramp`, hold, ramp
// down over `release` (the DTMF presses use it too).
double trapezoid(double t, double t0, double ramp, double hold, double release);

// A trapezoid envelope of a Hall stimulus.
struct Envelope {
  double t_start_s = 0, ramp_s = 0.05, hold_s = 0.2, release_s = 0.05;
  double end_s() const { return t_start_s + ramp_s + hold_s + release_s; }
  double at(double t) const;
};

// A press at a point of the skin (mm) with a normal force (N, into the skin)
// and a shear force (N, along x and y), footprint standard deviation radius_mm.
struct HallPress {
  std::array<double, 2> at_mm{0, 0};
  double normal_n = 1.0;
  std::array<double, 2> shear_n{0, 0};
  double radius_mm = 2.0;
  int cell = -1;  // the cell it was given for (-1: by position)
  Envelope env;
};

// A ball rolled along a polyline at constant speed, pressing with normal_n and
// pushing with shear_n along its direction of motion; the force ramps up over
// ramp_s at the start and down over ramp_s at the end.
struct HallRoll {
  std::vector<std::array<double, 2>> path_mm;
  double speed_mm_s = 20.0;
  double normal_n = 1.0;
  double shear_n = 0.0;
  double radius_mm = 4.0;
  double t_start_s = 0, ramp_s = 0.05;

  double length_mm() const;
  double end_s() const { return t_start_s + length_mm() / speed_mm_s; }
  // Position and unit direction of motion at time t (clamped to the path).
  void at(double t, std::array<double, 2>& p, std::array<double, 2>& dir) const;
  double envelope(double t) const;
};

// A force and torque on the rigid plate (seed 002), about the plate origin.
struct HallWrench {
  Vec3 force_n{0, 0, 0};
  Vec3 torque_nmm{0, 0, 0};
  Envelope env;
};

struct HallScene {
  HallConfig config;
  std::vector<HallPress> presses;
  std::vector<HallRoll> rolls;
  std::vector<HallWrench> wrenches;

  // The loads acting at time t (superposed by the physics).
  void loads_at(double t, std::vector<ContactLoad>& contacts,
                std::vector<PlateWrench>& plate) const;
  // z of the skin surface (highest cell top): where contacts act.
  double surface_z_mm() const;
};

}  // namespace eskin::sim
