#include "host/stream/live_address.h"

#include <arpa/inet.h>

#include <cstdlib>
#include <stdexcept>

namespace eskin::stream {

namespace {

bool is_loopback(const std::string& a) {
  if (a == "localhost") return true;
  in_addr v4{};
  if (inet_pton(AF_INET, a.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  if (inet_pton(AF_INET6, a.c_str(), &v6) == 1) return IN6_IS_ADDR_LOOPBACK(&v6);
  return false;  // another host name: it may resolve to any interface
}

}  // namespace

LiveAddress parse_live_address(const std::string& s) {
  const size_t colon = s.rfind(':');
  std::string addr = colon == std::string::npos ? "" : s.substr(0, colon);
  const std::string port = colon == std::string::npos ? s : s.substr(colon + 1);
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end || p < 0 || p > 65535)
    throw std::invalid_argument("--live '" + s + "': expected [ADDR:]PORT with PORT 0..65535");
  if (addr.size() > 1 && addr.front() == '[' && addr.back() == ']')
    addr = addr.substr(1, addr.size() - 2);
  if (addr.empty()) addr = "127.0.0.1";
  return {addr, int(p), is_loopback(addr)};
}

}  // namespace eskin::stream
