#include "sim/wav_io.h"

#include <sndfile.h>

#include <stdexcept>

namespace eskin::sim {

void write_wav(const std::string& path, const std::vector<int>& codes, const AdcConfig& adc) {
  if (adc.bits > 16)
    throw std::runtime_error(path + ": a 16-bit WAV cannot hold " + std::to_string(adc.bits) +
                             "-bit ADC codes");
  SF_INFO info{};
  info.samplerate = int(adc.rate_hz + 0.5);
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!f) throw std::runtime_error(path + ": cannot write WAV: " + sf_strerror(nullptr));
  std::vector<short> buf;
  buf.reserve(codes.size());
  for (int c : codes) buf.push_back(short(wav_sample_from_code(c, adc.bits)));
  sf_count_t n = sf_write_short(f, buf.data(), sf_count_t(buf.size()));
  std::string err = n == sf_count_t(buf.size()) ? "" : sf_strerror(f);
  sf_close(f);
  if (!err.empty()) throw std::runtime_error(path + ": short WAV write: " + err);
}

}  // namespace eskin::sim
