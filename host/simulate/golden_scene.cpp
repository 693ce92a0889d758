#include "host/simulate/golden_scene.h"

#include <fmt/format.h>
#include <fmt/os.h>

#include <cmath>
#include <filesystem>

#include "host/golden/decode_score.h"
#include "host/golden/golden_decoder.h"
#include "host/golden/izhikevich_layer.h"
#include "host/golden/sdft_bank.h"
#include "host/report/csv_fields.h"
#include "sim/world_model.h"

namespace eskin::simulate {
namespace {

// The run's output files, their headers written.
struct GoldenFiles {
  fmt::ostream amp_nd, amp_csv, tax_nd, tax_csv, spk_nd, spk_csv;
};

GoldenFiles open_files(const SkinConfig& skin, const std::string& out_dir) {
  namespace fs = std::filesystem;
  fs::create_directories(out_dir);
  auto open = [&](const char* name) { return fmt::output_file((fs::path(out_dir) / name).string()); };
  GoldenFiles f{open("amplitudes.ndjson"), open("amplitudes.csv"), open("taxels.ndjson"),
                open("taxels.csv"),        open("spikes.ndjson"),    open("spikes.csv")};
  f.amp_csv.print("sample,t_ms");
  for (double fr : skin.carrier_freqs_hz()) f.amp_csv.print(",amp_{}hz", fr);
  f.amp_csv.print("\n");
  f.tax_csv.print("sample,t_ms");
  for (int i = 0; i < skin.rows; ++i)
    for (int j = 0; j < skin.cols; ++j) f.tax_csv.print(",r{}c{}_kpa", i, j);
  f.tax_csv.print("\n");
  f.spk_csv.print("t_ms,taxel,row,col\n");
  return f;
}

// Every frame of the scene through the decoder: amplitudes and taxels as
// the scene's outputs ask, the taxels scored against the truth.
void decode_frames(const sim::Scene& scene, bool score, sim::WorldModel& world,
                   golden::GoldenDecoder& dec, golden::DecodeScorer& scorer, GoldenFiles& out) {
  const double fs = scene.skin.adc.rate_hz;
  int code = 0;
  while (world.next(code)) {
    if (!dec.push(code)) continue;
    const golden::Frame& f = dec.frame();
    const double t_ms = 1000.0 * double(f.sample) / fs;
    if (score) scorer.add(f);
    if (scene.outputs.amplitudes) {
      out.amp_nd.print("{{\"sample\":{},\"t_ms\":{:.4f},\"amp_lsb\":[{}]}}\n", f.sample, t_ms, report::join(f.amp_lsb));
      out.amp_csv.print("{},{:.4f},{}\n", f.sample, t_ms, report::join(f.amp_lsb));
    }
    if (scene.outputs.taxels) {
      out.tax_nd.print("{{\"sample\":{},\"t_ms\":{:.4f},\"pressure_kpa\":[{}]}}\n", f.sample, t_ms,
                       report::join(f.pressure));
      out.tax_csv.print("{},{:.4f},{}\n", f.sample, t_ms, report::join(f.pressure));
    }
  }
}

// The receptors' spikes, per taxel in time order; returns their count.
size_t write_spikes(const SkinConfig& skin, const std::vector<std::vector<double>>& spikes,
                    GoldenFiles& out) {
  size_t written = 0;
  for (size_t t = 0; t < spikes.size(); ++t)
    for (double ts : spikes[t]) {
      const int r = int(t) / skin.cols, c = int(t) % skin.cols;
      out.spk_nd.print("{{\"t_ms\":{:.4f},\"taxel\":{},\"row\":{},\"col\":{}}}\n", ts, t, r, c);
      out.spk_csv.print("{:.4f},{},{},{}\n", ts, t, r, c);
      ++written;
    }
  return written;
}

// The skin and decoder, and a note when carriers off DFT bin centres leak
// into each other.
void print_setup(const sim::Scene& scene, const std::string& scene_file,
                 const sim::WorldModel& world) {
  const SkinConfig& skin = scene.skin;
  const double fs = skin.adc.rate_hz;
  fmt::print("scene {} ({}): {}x{} skin, {} carriers, {} samples at {} Hz, window {}, variant {}\n",
             scene.name, scene_file, skin.rows, skin.cols, skin.carriers(), world.total_samples(), fs,
             scene.decoder.window, to_string(scene.decoder.variant));
  fmt::print("adc: {} samples clipped\n", world.clipped());
  // Off-bin carriers leak into each other under a rectangular window (up to
  // ~24% for the thesis set at N = 32); only the LS variant removes that.
  int off_bin = 0;
  for (double f : skin.carrier_freqs_hz()) {
    const double bin = f * scene.decoder.window / fs;
    off_bin += std::fabs(bin - std::round(bin)) > 1e-9;
  }
  if (off_bin && scene.decoder.variant != DftVariant::LsDemix && !scene.decoder.hann)
    fmt::print("note: {} of {} carriers are off DFT bin centres and leak into each other; "
               "--variant ls demixes them\n",
               off_bin, skin.carriers());
}

// Per taxel: the error against the truth and the spike statistics; the
// ghosts, raw and corrected.
void print_scores(const SkinConfig& skin, const golden::DecodeScore& s, bool spiking,
                  const std::vector<std::vector<double>>& spikes) {
  fmt::print("frames: {} ({} steady windows scored against ground truth)\n", s.frames,
             s.steady_frames);
  fmt::print("taxel   rms_err_kpa  max_err_kpa  spikes  mean_isi_ms  var_isi_ms2\n");
  for (size_t t = 0; t < s.taxel.size(); ++t) {
    golden::SpikeStats st{};
    if (spiking) st = golden::spike_stats(spikes[t]);
    fmt::print("r{}c{}    {:11.3f}  {:11.3f}  {:6}  {:11.3f}  {:11.3f}\n", int(t) / skin.cols,
               int(t) % skin.cols, s.taxel[t].rms_error_kpa, s.taxel[t].max_error_kpa, st.count,
               st.mean_isi_ms, st.var_isi_ms2);
  }
  fmt::print("ghosts (lit taxel, truth unlit, steady windows): product {} taxel-frames in {} "
             "frames; corrected {} taxel-frames in {} frames; missed {}\n",
             s.ghost_taxel_frames_raw, s.ghost_frames_raw, s.ghost_taxel_frames, s.ghost_frames,
             s.missed_taxel_frames);
}

}  // namespace

int run_golden_scene(sim::Scene scene, const std::string& scene_file, const std::string& out_dir,
                     bool ghost_correct) {
  validate(scene.decoder, scene.skin);
  scene.decoder.variant = golden::resolve_variant(
      scene.decoder.variant, scene.skin.carrier_freqs_hz(), scene.skin.adc.rate_hz, scene.decoder);
  const SkinConfig& skin = scene.skin;

  golden::GoldenOptions opt;
  opt.taxels = scene.outputs.taxels || scene.outputs.spikes;
  opt.spikes = scene.outputs.spikes;
  opt.ghost_correct = ghost_correct;
  golden::GoldenDecoder dec(skin, scene.decoder, scene.neuron, opt);
  sim::WorldModel world(scene);
  golden::DecodeScorer scorer(skin, scene.decoder,
                              [&world](size_t n, std::vector<double>& p) { world.pressure_at(n, p); });
  GoldenFiles out = open_files(skin, out_dir);
  decode_frames(scene, opt.taxels, world, dec, scorer, out);
  const auto& spikes = dec.spike_times_ms();
  const size_t spikes_written = write_spikes(skin, spikes, out);

  const golden::DecodeScore s = scorer.score();
  print_setup(scene, scene_file, world);
  if (opt.taxels) print_scores(skin, s, opt.spikes, spikes);
  if (opt.spikes) fmt::print("spikes: {}\n", spikes_written);
  fmt::print("outputs written to {}/\n", out_dir);
  return 0;
}

}  // namespace eskin::simulate
