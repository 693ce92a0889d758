// Shared configuration of the Izhikevich spiking layer (golden model, scene
// loader and CLI). The fixed-point kernel in hls/ has its own copy of the
// presets by design: the two implementations stay independent.
#pragma once

#include <string>

namespace eskin {

// v' = 0.04 v^2 + 5 v + 140 - u + I,  u' = a (b v - u),
// if v >= 30 mV: v <- c, u <- u + d.  Time in ms, v in mV.
struct IzhikevichParams {
  double a = 0.02, b = 0.2, c = -65.0, d = 8.0;
  double tau = 1.0;   // time scale: derivatives are multiplied by tau
  double gain = 1.0;  // K: input current I = K * input
};

// Which signal drives a taxel's neuron.
enum class NeuronInput {
  Level,           // the taxel value itself
  RectifiedChange  // max(0, d(taxel)/dt), per ms: responds to onsets
};

struct NeuronConfig {
  std::string preset = "RA";  // RS IB CH FS LTS TC RZ (Izhikevich 2003) or RA
  double dt_ms = 1.0 / 35.0;  // integration step (one ADC sample at 35 kHz)
  NeuronInput input = NeuronInput::Level;
  // Taxel value (calibrated, conductance fraction g in 0..1) -> input units
  // before the gain K: a firm press (g ~ 0.5) then drives I = K * 5.
  double input_scale = 10.0;
};

}  // namespace eskin
