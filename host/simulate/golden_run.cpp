#include "host/simulate/golden_run.h"

#include "host/golden/decode_score.h"
#include "host/golden/golden_decoder.h"
#include "sim/world_model.h"

namespace eskin::simulate {

report::GoldenRun run_golden(const sim::Scene& scene, int fpga_step) {
  report::GoldenRun g;
  golden::GoldenOptions opt;
  opt.taxels = true;
  opt.spikes = scene.outputs.spikes;
  golden::GoldenDecoder dec(scene.skin, scene.decoder, scene.neuron, opt);
  sim::WorldModel world(scene), truth(scene);
  golden::DecodeScorer scorer(scene.skin, scene.decoder,
                              [&truth](size_t n, std::vector<double>& p) { truth.pressure_at(n, p); });
  g.frames.resize(world.total_samples());
  int code = 0;
  for (size_t n = 0; world.next(code); ++n)
    if (dec.push(code)) {
      g.frames[n] = dec.frame();
      scorer.add(dec.frame());
    }
  g.score = scorer.score();
  if (scene.outputs.spikes) {
    for (const auto& v : dec.spike_times_ms()) g.scene_step_spikes += v.size();
    for (const auto& v : dec.spike_times2_ms()) g.scene_step_spikes2 += v.size();
    DecoderConfig d = scene.decoder;
    d.hop = fpga_step;
    NeuronConfig n = scene.neuron;
    n.dt_ms = 1000.0 * fpga_step / scene.skin.adc.rate_hz;
    golden::GoldenOptions so;
    so.taxels = so.spikes = true;
    golden::GoldenDecoder sd(scene.skin, d, n, so);
    sim::WorldModel w(scene);
    for (int c = 0; w.next(c);) sd.push(c);
    g.spikes_ms = sd.spike_times_ms();
    g.spikes2_ms = sd.spike_times2_ms();
  }
  return g;
}

}  // namespace eskin::simulate
