// The host side of a virtual board run (eskin simulate, DTMF and Hall): the
// board's pty read through the host streaming library as a host program
// reads a real board, until the board has put its last byte in the pty.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "host/link/link_decoder.h"
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

// What a board run delivered: every packet in order with its arrival at the
// host, the board's done line and the link's counters.
struct BoardRun {
  std::vector<link::Packet> rx;
  std::vector<double> arrival_us;  // per packet; -1 each when !timed
  bool timed = false;  // packet k ended with the k-th frame delimiter: no link error
  nlohmann::json done;
  link::DecoderStats link;
};

// After read_until_board_done: stops the port (the board exits once its
// reader has closed it) and pairs each packet with its delimiter's arrival.
inline BoardRun finish_board_run(vboard::VboardProcess& board, stream::LinkStream& port,
                                 std::vector<link::Packet> rx) {
  BoardRun r;
  r.done = board.done();
  r.link = port.stats().link;
  port.stop();
  r.rx = std::move(rx);
  const auto& ends = r.done.at("frame_end_ns");
  r.timed = r.link.crc_errors + r.link.framing_errors + r.link.payload_errors == 0 &&
            ends.size() == r.rx.size();
  r.arrival_us.assign(r.rx.size(), -1.0);
  if (r.timed)
    for (size_t i = 0; i < r.rx.size(); ++i) r.arrival_us[i] = ends[i].get<double>() / 1000.0;
  return r;
}

}  // namespace eskin::cli
