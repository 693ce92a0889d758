// Taxel reconstruction from per-line amplitudes of a DTMF skin (thesis §3.2).
//
// Units. The decoder measures one magnitude per carrier in ADC LSB (peak).
// Dividing by SkinConfig::full_carrier_lsb() gives "line conductance" units:
// row i carries r_i = sum_j g_ij and column j carries c_j = sum_i g_ij, where
// g_ij = Conductance::g(p_ij) in 0..1 is the fraction of a carrier that taxel
// (i, j) passes to the common conductor. Double precision throughout.
#pragma once

#include <Eigen/Dense>

#include "eskin/skin_config.h"

namespace eskin::golden {

// The thesis reconstruction T_ij = r_i * c_j (any units; LSB^2 if the inputs
// are LSB). Every (row, col) crossing of active lines lights up, so k touches
// on distinct lines give k^2 non-zero taxels: k^2 - k of them are ghosts.
Eigen::MatrixXd taxel_product(const Eigen::VectorXd& row_amp, const Eigen::VectorXd& col_amp);

// Calibrated reconstruction: normalised line amplitudes -> pressure (kPa)
// per taxel, g_ij = sqrt(max(0, r_i) * max(0, c_j)), p_ij = c.inverse(g_ij).
// Exact for a single touch (then r_i = c_j = g); with several touches it
// carries the same ghosts as the product (see ghost_filter.h).
Eigen::MatrixXd taxel_pressure(const Eigen::VectorXd& row_g, const Eigen::VectorXd& col_g,
                               const Conductance& c);

// The g-matrix part of taxel_pressure: sqrt(max(0, r_i) * max(0, c_j)).
Eigen::MatrixXd taxel_g(const Eigen::VectorXd& row_g, const Eigen::VectorXd& col_g);

// Element-wise c.inverse(g): g-matrix -> pressure matrix (kPa).
Eigen::MatrixXd pressure_from_g(const Eigen::MatrixXd& g, const Conductance& c);

}  // namespace eskin::golden
