// The host side of a virtual board run (eskin simulate, DTMF and Hall): the
// board's pty read through the host streaming library as a host program
// reads a real board, until the board has put its last byte in the pty.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "host/stream/progress.h"
#include "host/link/link_decoder.h"
#include "host/stream/link_stream.h"
#include "sim/vboard/vboard_process.h"

namespace eskin::stream {

// The board executable's arguments: the scene, an FST trace if asked, and
// the size of the host's start-up `commands` (run_board sends them): the
// board holds its time at 0 until all of them are in, so they act from the
// first frame however late the host gets to send them on a busy machine.
// `extra`: more of the board's options (its line faults).
inline std::vector<std::string> board_args(const std::string& scene, const std::string& trace,
                                           const std::vector<std::vector<uint8_t>>& commands,
                                           const std::vector<std::string>& extra = {}) {
  std::vector<std::string> a{scene};
  a.insert(a.end(), extra.begin(), extra.end());
  if (!trace.empty()) a.insert(a.end(), {"--trace", trace});
  size_t bytes = 0;
  for (const auto& c : commands) bytes += c.size();
  if (bytes > 0) a.insert(a.end(), {"--hold-for-host-bytes", std::to_string(bytes)});
  return a;
}

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
  // With line faults: what the host delivered against what the FPGA sent
  // (host/simulate/line_report.h), as summary.json's "line" and the
  // report's rows {figure, value}; empty without.
  nlohmann::json line;
  std::vector<std::vector<std::string>> line_rows;
  // With board faults: the done line's board_faults (summary.json's
  // "board_faults"; their rows join line_rows).
  nlohmann::json board_faults;
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

// One run of a started board, as a host program would do it: its pty read
// through host/stream, `commands` (framed) sent once the reader is up,
// `alongside` run on another thread meanwhile (the golden model: the
// board process has the other core), a progress bar over `progress_total`
// fed by `progress_of` (a packet's position, or -1 for none) until every
// byte the board sent has been read.
inline BoardRun run_board(vboard::VboardProcess& board, int baud,
                          const std::vector<std::vector<uint8_t>>& commands, size_t progress_total,
                          const std::function<long(const link::Packet&)>& progress_of,
                          const std::function<void()>& alongside = {}) {
  stream::LinkStream port(board_link_options(board.pty(), baud));
  std::vector<link::Packet> rx;  // filled on the reader thread, read after port.stop()
  std::atomic<long> last{0};
  port.on_packet([&](const link::Packet& p) {
    rx.push_back(p);
    if (const long at = progress_of(p); at >= 0) last = at;
  });
  port.start();
  for (const auto& c : commands)
    if (!c.empty()) port.send(c);
  std::thread side;
  if (alongside) side = std::thread(alongside);
  Progress bar(progress_total);
  read_until_board_done(board, port, [&] { bar.update(size_t(last.load())); });
  bar.update(progress_total);
  if (side.joinable()) side.join();
  return finish_board_run(board, port, std::move(rx));
}

}  // namespace eskin::stream
