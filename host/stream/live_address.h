// Where `eskin stream --live [ADDR:]PORT` serves the live view, which shows
// the board's data and takes commands for it: loopback unless the user
// says otherwise (--live-public), since anyone who reaches the port can
// reconfigure the board.
#pragma once

#include <string>

namespace eskin::stream {

struct LiveAddress {
  std::string addr;  // "127.0.0.1" when none was given (":PORT", "PORT")
  int port = 0;      // 0: any free port
  bool loopback = true;
};

// "[ADDR:]PORT", ADDR an IPv4 or IPv6 address ("[::1]") or a host name;
// throws std::invalid_argument naming --live and what was expected.
LiveAddress parse_live_address(const std::string& s);

}  // namespace eskin::stream
