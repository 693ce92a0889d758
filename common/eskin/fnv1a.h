// FNV-1a, 64 bit: the one content hash behind the project's build keys (the
// virtual boards' FPGA builds, the latency bench's harness cache, the trade
// study's synthesis cache). Not cryptographic: it names builds, it does not
// guard them.
#pragma once

#include <cstdint>
#include <string>

namespace eskin {

inline uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

}  // namespace eskin
