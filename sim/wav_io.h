// ADC streams as WAV files: mono, 16-bit PCM at adc.rate_hz. A code c of a
// B-bit ADC is stored as the signed sample (c - 2^(B-1)) << (16 - B), so the
// ADC's mid-scale is 0 and full scale fills the 16-bit range (B <= 16).
#pragma once

#include <string>
#include <vector>

#include "eskin/skin_config.h"

namespace eskin::sim {

// Throws std::runtime_error naming the path on failure or if adc.bits > 16.
void write_wav(const std::string& path, const std::vector<int>& codes, const AdcConfig& adc);

// The 16-bit sample that code c becomes (exposed for tests and readers).
inline int wav_sample_from_code(int code, int bits) {
  return (code - (1 << (bits - 1))) * (1 << (16 - bits));
}

}  // namespace eskin::sim
