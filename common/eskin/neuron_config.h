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

// The second (weighted) layer: one neuron per taxel, driven through a 3x3
// synaptic kernel by the receptors around its taxel that spiked this step:
// I = gain * (centre * s(i,j) + surround * sum of the 8 neighbours' s).
// Centre-surround (centre > 0 > surround) makes it fire for a contact's
// centre rather than its whole area.
struct Layer2Config {
  std::string preset = "RS";
  double centre = 20.0;
  double surround = -4.0;
};

struct NeuronConfig {
  std::string preset = "RA";  // RS IB CH FS LTS TC RZ (Izhikevich 2003) or RA
  double dt_ms = 1.0 / 35.0;  // integration step (one ADC sample at 35 kHz)
  NeuronInput input = NeuronInput::Level;
  // Taxel value (calibrated, conductance fraction g in 0..1) -> input units
  // before the gain K: a firm press (g ~ 0.5) then drives I = K * 5.
  double input_scale = 10.0;
  Layer2Config layer2;
};

}  // namespace eskin
