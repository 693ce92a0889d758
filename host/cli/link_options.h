// The link options shared by `eskin stream` and `eskin config`:
// --port DEV [--baud N] | --tcp HOST:PORT.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "host/stream/endpoint.h"

namespace eskin::cli {

struct LinkArgs {
  std::string port, tcp;
  int baud = eskin::stream::kBoardBaud;

  void add_to(CLI::App* sub) {
    auto* p = sub->add_option("--port", port, "serial device or pty of the board (e.g. /dev/ttyUSB1)");
    auto* t = sub->add_option("--tcp", tcp, "HOST:PORT of a board or bridge serving the link over TCP");
    sub->add_option("--baud", baud, "serial baud rate (any rate; the board runs at 3000000)")
        ->check(CLI::PositiveNumber);
    p->excludes(t);
    t->excludes(p);
  }
  // Throws std::runtime_error / LinkError with the option named.
  eskin::stream::Endpoint endpoint() const {
    if (!tcp.empty()) return eskin::stream::Endpoint::parse_tcp(tcp);
    if (port.empty()) throw std::runtime_error("one of --port DEV or --tcp HOST:PORT is required");
    return eskin::stream::Endpoint::serial(port, baud);
  }
};

}  // namespace eskin::cli
