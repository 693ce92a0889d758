// The host side of a virtual board run (eskin simulate, DTMF and Hall): the
// board's pty read through the host streaming library as a host program
// reads a real board, until the board has put its last byte in the pty.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "host/stream/link_stream.h"
#include "sim/vboard/vboard_process.h"

namespace eskin::cli {

// Raw 8N1 at the board's rate; no reopening (the port exists until the
// board exits); packets to callbacks only.
inline stream::StreamOptions board_link_options(const std::string& pty, int baud) {
  stream::StreamOptions o;
  o.endpoint = stream::Endpoint::serial(pty, baud);
  o.reconnect = false;
  o.queue_capacity = 0;
  return o;
}

// Returns once the board is done and every byte it sent has been read (or
// the port is gone); `tick` runs every 50 ms meanwhile (a progress bar).
inline void read_until_board_done(vboard::VboardProcess& board, const stream::LinkStream& port,
                                  const std::function<void()>& tick) {
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    tick();
    const stream::StreamStats st = port.stats();
    if (board.poll_done() &&
        (st.link.bytes + st.sync_bytes >= board.done().at("bytes_to_host").get<uint64_t>() ||
         !port.connected()))
      return;
  }
}

}  // namespace eskin::cli
