// FNV-1a, 64 bit: the one content hash behind the project's build keys (the
// virtual boards' FPGA builds, the latency bench's harness cache, the trade
// study's synthesis cache) and of the delivery check's packet keys. Not
// cryptographic: it names builds and tells payloads apart, it guards
// neither.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace eskin {

inline uint64_t fnv1a(const uint8_t* p, size_t n, uint64_t h = 1469598103934665603ull) {
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}
inline uint64_t fnv1a(const std::string& s, uint64_t h = 1469598103934665603ull) {
  return fnv1a(reinterpret_cast<const uint8_t*>(s.data()), s.size(), h);
}

}  // namespace eskin
