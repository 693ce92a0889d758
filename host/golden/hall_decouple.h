// Golden seed-001 3D force decoupling. From the film's field (geomagnetic
// baseline removed) the decoupling parameters
//   Rx = atan( 2 Bx Bz' / (Bz'^2 + By^2 - Bx^2) )
//   Ry = atan( 2 By Bz' / (Bz'^2 + Bx^2 - By^2) )
//   Sz = ln sqrt( ((Bz''^2 - By^2 + Bx^2) / (2 Bz''))^2 + By^2 )
// with Bz' = k1 Bz + c1, Bz'' = k2 Bz + c2 (the seed's eq. 1, written without
// its nested fractions: Bz' - (Bz'^2 -+ (By^2 - Bx^2)) / (2 Bz') is the
// denominator above over 2 Bz'). Rx follows the film's x shift only, Ry its y
// shift, Sz its distance; each maps to a force through a polynomial fitted to
// calibration presses. Out-of-range inputs (Bz' or Bz'' <= 0, a denominator
// <= 0: the film outside the working range) give valid = false.
#pragma once

#include <array>
#include <vector>

#include "eskin/hall_config.h"

namespace eskin::golden {

struct Decoupled {
  double rx = 0, ry = 0, sz = 0;
  bool valid = false;
};

Decoupled hall_decouple(const Vec3& b_ut, const DecoupleParams& p);

// Force (Fx, Fy, normal) from the change of (Rx, Ry, Sz) since the unloaded
// state `rest`, through the fitted polynomials.
Vec3 decoupled_force(const Decoupled& d, const Decoupled& rest, const DecoupleParams& p);

// One calibration press: the film field and the force that caused it.
struct DecoupleSample {
  Vec3 b_ut;
  Vec3 force;  // Fx, Fy, normal (N)
};

// Fits k1/c1, k2/c2 and cubic force polynomials to calibration presses (least
// squares; c1 and c2 by golden-section search on the fit residual).
// `rest_b_ut` is the unloaded film field.
DecoupleParams fit_decouple(const std::vector<DecoupleSample>& cal, const Vec3& rest_b_ut);

}  // namespace eskin::golden
