// eskin decode --skin SKIN.yaml INPUT.wav: decodes a recorded mono 16-bit PCM
// WAV of a skin's summed signal with the golden decoder (or, --engine fpga,
// the FPGA's fixed-point chain: host/engine/decode_fpga.h); NDJSON to stdout, one
// line per frame.
#include <fmt/format.h>
#include <sndfile.h>
#include <yaml-cpp/yaml.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "cli/command.h"
#include "host/engine/decode_fpga.h"
#include "host/golden/golden_decoder.h"
#include "host/golden/sdft_bank.h"
#include "host/report/csv_fields.h"
#include "sim/scene.h"

namespace eskin::cli {
namespace {

struct DecodeArgs {
  std::string skin, wav, variant, engine = "golden";
  int window = 0, hop = 0, threads = 1;
  bool taxels = false, spikes = false, no_ghost = false, rate_from_wav = false;
};

struct SndCloser {
  void operator()(SNDFILE* f) const { sf_close(f); }
};

uint32_t le32(const unsigned char* b) {
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

// libsndfile quietly shortens a data chunk that runs past the end of the
// file; a capture cut short must not decode silently, so walk the RIFF
// chunks and compare the declared sample bytes with what the file holds.
void check_data_chunk(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  const uint64_t size = std::filesystem::file_size(path);
  unsigned char h[12];
  if (!f.read(reinterpret_cast<char*>(h), 12) || std::memcmp(h, "RIFF", 4) ||
      std::memcmp(h + 8, "WAVE", 4))
    throw std::runtime_error(path + ": byte 0: expected a RIFF/WAVE header");
  uint64_t at = 12;
  unsigned char c[8];
  while (f.read(reinterpret_cast<char*>(c), 8)) {
    const uint64_t len = le32(c + 4);
    if (!std::memcmp(c, "data", 4)) {
      if (at + 8 + len > size)
        throw std::runtime_error(fmt::format(
            "{}: truncated: the data chunk at byte {} declares {} bytes of samples, the file "
            "holds {}",
            path, at, len, size - at - 8));
      return;
    }
    at += 8 + len + (len & 1);  // chunks are padded to even sizes
    f.seekg(std::streamoff(at));
  }
  throw std::runtime_error(path + ": no data chunk before the end of the file");
}

// Reads the whole file as 16-bit samples after checking everything a real
// capture can get wrong; errors name the file and what was expected.
std::vector<short> read_wav(const std::string& path, double& rate) {
  SF_INFO info{};
  std::unique_ptr<SNDFILE, SndCloser> f(sf_open(path.c_str(), SFM_READ, &info));
  if (!f)
    throw std::runtime_error(path + ": not a readable WAV file (" + sf_strerror(nullptr) + ")");
  if ((info.format & SF_FORMAT_TYPEMASK) != SF_FORMAT_WAV)
    throw std::runtime_error(path + ": expected a WAV (RIFF/WAVE) file, got another container");
  if ((info.format & SF_FORMAT_SUBMASK) != SF_FORMAT_PCM_16)
    throw std::runtime_error(path + ": expected 16-bit PCM samples");
  if (info.channels != 1)
    throw std::runtime_error(path + ": expected mono (1 channel), got " +
                             std::to_string(info.channels) + " channels");
  check_data_chunk(path);
  std::vector<short> s(size_t(info.frames));
  if (sf_readf_short(f.get(), s.data(), info.frames) != info.frames)
    throw std::runtime_error(path + ": truncated: could not read " + std::to_string(info.frames) +
                             " samples");
  rate = info.samplerate;
  return s;
}

int run_decode(const DecodeArgs& a) {
  SkinConfig skin = sim::load_skin(a.skin);
  // A scene file (it has a duration) also carries decoder and neuron
  // settings: use them, and let a broken scene fail loudly rather than fall
  // back to defaults.
  DecoderConfig dec;
  NeuronConfig neuron;
  if (YAML::LoadFile(a.skin)["duration_s"]) {
    const sim::Scene scene = sim::load_scene(a.skin);
    dec = scene.decoder;
    neuron = scene.neuron;
  }
  if (!a.variant.empty()) dec.variant = dft_variant_from_string(a.variant);
  if (a.window > 0) dec.window = a.window;
  if (a.hop > 0) dec.hop = a.hop;
  double rate = 0;
  const std::vector<short> pcm = read_wav(a.wav, rate);
  if (rate != skin.adc.rate_hz) {
    if (!a.rate_from_wav)
      throw std::runtime_error(fmt::format(
          "{}: sample rate {} Hz does not match skin.adc.rate_hz {} Hz of {} (pass "
          "--rate-from-wav to decode at the file's rate)",
          a.wav, rate, skin.adc.rate_hz, a.skin));
    skin.adc.rate_hz = rate;
  }
  validate(skin);
  validate(dec, skin);
  const int shift = 16 - skin.adc.bits;
  const int half = 1 << (skin.adc.bits - 1);
  if (a.engine == "fpga") {
    std::vector<int> codes(pcm.size());
    for (size_t i = 0; i < pcm.size(); ++i)
      codes[i] = (shift >= 0 ? (int(pcm[i]) >> shift) : (int(pcm[i]) << -shift)) + half;
    return engine::decode_fpga(skin, dec, neuron, codes,
                               {a.taxels || a.spikes, a.spikes, !a.no_ghost, a.threads, a.hop});
  }
  dec.variant = golden::resolve_variant(dec.variant, skin.carrier_freqs_hz(), skin.adc.rate_hz, dec);

  if (a.threads != 1) throw ConfigError("--threads", "only --engine fpga runs on several threads");
  golden::GoldenOptions opt;
  opt.taxels = a.taxels || a.spikes;
  opt.spikes = a.spikes;
  opt.ghost_correct = !a.no_ghost;
  golden::GoldenDecoder d(skin, dec, neuron, opt);
  std::string line;
  for (short s : pcm) {
    const int code = (shift >= 0 ? (int(s) >> shift) : (int(s) << -shift)) + half;
    if (!d.push(code)) continue;
    const golden::Frame& f = d.frame();
    line = fmt::format("{{\"sample\":{},\"t_ms\":{:.4f},\"amp_lsb\":[", f.sample,
                       1000.0 * double(f.sample) / rate);
    line += report::join(f.amp_lsb);
    line += "]";
    if (opt.taxels) {
      line += ",\"pressure_kpa\":[";
      line += report::join(f.pressure);
      line += "]";
    }
    if (opt.spikes) {
      line += ",\"spikes\":[";
      for (size_t i = 0; i < f.spiked.size(); ++i) line += fmt::format("{}{}", i ? "," : "", f.spiked[i]);
      line += "]";
    }
    line += "}\n";
    std::fwrite(line.data(), 1, line.size(), stdout);
  }
  return 0;
}

std::function<int()> setup(CLI::App& app) {
  auto a = std::make_shared<DecodeArgs>();
  CLI::App* sub = app.add_subcommand(
      "decode", "Decode a recorded mono 16-bit PCM WAV of a skin's summed signal (NDJSON)");
  sub->add_option("--skin", a->skin, "skin file or scene file (its skin: section is used)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("input", a->wav, "WAV file: mono, 16-bit PCM, the skin's ADC rate")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--variant", a->variant,
                  "auto (default: the most accurate for the skin)|direct|recursive|damped|exact|ls");
  sub->add_option("--window", a->window, "samples in the sliding window");
  sub->add_option("--hop", a->hop, "emit a frame every HOP samples");
  sub->add_flag("--taxels", a->taxels, "add calibrated, ghost-corrected taxel pressures");
  sub->add_flag("--spikes", a->spikes, "add receptor-layer spikes (implies --taxels)");
  sub->add_flag("--no-ghost", a->no_ghost, "taxels without ghost correction");
  sub->add_option("--engine", a->engine,
                  "golden (double-precision model) or fpga (the FPGA's integers, host/engine)")
      ->check(CLI::IsMember({"golden", "fpga"}));
  sub->add_option("--threads", a->threads, "fpga engine: threads for a long recording")
      ->check(CLI::Range(1, 256));
  sub->add_flag("--rate-from-wav", a->rate_from_wav,
                "decode at the WAV's rate instead of requiring skin.adc.rate_hz");
  return [a] { return run_decode(*a); };
}

ESKIN_COMMAND("decode", setup);

}  // namespace
}  // namespace eskin::cli
