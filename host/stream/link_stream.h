// LinkStream: the host end of the FPGA link. Reads bytes from a serial
// device / pty or a TCP socket on its own thread, decodes them with
// link::LinkDecoder (COBS, CRC, sequence numbers; corrupt frames counted
// and skipped), and hands every packet to the caller twice over:
//   * callbacks (on_packet, on_type): called on the reader thread, in order;
//   * a bounded pull queue (pop): when full, the oldest packet is dropped
//     and counted, so a slow consumer never stalls the link.
// A link that drops (EOF, EIO, device removed, connection reset) is reported
// through on_event and reopened with exponential back-off, except a
// pseudo-terminal (the virtual board's pty) that hangs up: a board that
// closes its pty has ended (a new one gets a new pty), so the stream ends
// (LinkEvent::HungUp, ended()). A link on which bytes arrive but no packet
// decodes (framing errors only) is at the wrong baud rate: the stream
// probes the common rates, says which one decodes (LinkEvent::WrongBaud)
// and ends. A link open with no packet for idle_after_ms is reported idle,
// once, and again when packets resume. Every connection
// starts a fresh decoder; if the bytes up to its first 0x00 do not decode,
// they were the tail of a frame sent before we listened and count as
// sync_bytes, not as an error. The statistics add up over connections.
// Commands go out with command(), which waits for the FPGA's verdict
// (commands.h).
//
//   eskin::stream::LinkStream s({eskin::stream::Endpoint::serial("/dev/pts/3")});
//   s.on_type(eskin::link::kTaxelsDense, [](const eskin::link::Packet& p) { ... });
//   s.start();
//   auto r = s.command("set-mask", {"0x7"});
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "host/stream/commands.h"
#include "host/stream/endpoint.h"

namespace eskin::stream {

struct StreamOptions {
  Endpoint endpoint;
  bool reconnect = true;          // reopen a dropped link (else: stop)
  int backoff_min_ms = 50;        // first retry delay; doubles per failure
  int backoff_max_ms = 2000;
  size_t queue_capacity = 65536;  // pull queue bound; 0 = no queue (callbacks only)
  size_t max_payload = 65535;     // decoder's frame bound (larger: framing error)
  // A pty that hangs up ends the stream (false: reopen it like a serial
  // device, e.g. a pty standing in for a /dev/ttyUSB in a test).
  bool pty_hangup_ends = true;
  int idle_after_ms = 3000;       // report "idle" after this long without a packet (0: never)
  // A serial link whose bytes decode to nothing: after baud_check_ms from
  // its first byte, or baud_check_bytes bytes, with at least two link
  // errors and no packet, probe kProbeBauds (0 / false: never).
  bool detect_baud = true;
  int baud_check_ms = 1000;
  uint64_t baud_check_bytes = 3000;
  int probe_ms = 1000;            // per rate: listen this long for two good packets
};

// The rates probed at a wrong baud rate, most likely first (the board's
// own rate, then the common USB-serial ones).
inline const std::vector<int>& probe_bauds() {
  static const std::vector<int> v{3000000, 2000000, 1000000, 921600, 460800, 230400, 115200};
  return v;
}

struct LinkEvent {
  // HungUp: a pty's board closed it (the stream ends). Idle: no packet for
  // idle_after_ms on an open link; Resumed: packets again after Idle.
  // WrongBaud: bytes but no packet; the message names the rate that decodes
  // (the stream ends).
  enum class Kind { Opened, Lost, OpenFailed, HungUp, Idle, Resumed, WrongBaud };
  Kind kind;
  std::string message;  // names the endpoint and the cause
  int attempt = 0;      // OpenFailed: consecutive failures so far; WrongBaud: the rate that decodes (0: none)
};

// Why the reader stopped on its own (LinkStream::ended()).
enum class StreamEnd { Running, Lost, HungUp, WrongBaud };

struct StreamStats {
  link::DecoderStats link;        // summed over all connections
  uint64_t sync_bytes = 0;        // each connection's partial first frame (not errors)
  uint64_t connects = 0;          // successful opens
  uint64_t disconnects = 0;       // links lost
  uint64_t queue_dropped = 0;     // pull queue was full: oldest dropped
  std::map<uint8_t, uint64_t> packets_by_type;
  uint64_t corrupt() const { return link.crc_errors + link.framing_errors + link.payload_errors; }
};

struct CommandReply {
  Ack ack = Ack::Pending;         // Pending here means: no verdict before the timeout
  uint8_t type = 0, seq = 0;      // the command as sent
  link::StatusBlock status;       // the STATUS that decided it
  link::HallDecodeStatus hall_status;  // ... or the HALL_DECODE_STATUS (a hall-* command)
  std::string message;            // "accepted", "rejected: value out of range", ...
};

class LinkStream {
 public:
  using PacketFn = std::function<void(const link::Packet&)>;
  using EventFn = std::function<void(const LinkEvent&)>;

  explicit LinkStream(StreamOptions opt);
  ~LinkStream();
  LinkStream(const LinkStream&) = delete;
  LinkStream& operator=(const LinkStream&) = delete;

  // Register before start().
  void on_packet(PacketFn fn);                // every packet
  void on_type(uint8_t type, PacketFn fn);    // packets of one type
  void on_event(EventFn fn);

  // Opens the link and starts the reader thread. Throws LinkError when the
  // first open fails and options.reconnect is false.
  void start();
  void stop();  // joins the reader; idempotent
  bool running() const { return running_; }
  bool connected() const { return connected_; }
  // Running until the reader stops on its own: a lost link without
  // reconnect, a pty that hung up, a wrong baud rate.
  StreamEnd ended() const { return ended_; }

  // Pull API: waits up to `wait` for a packet.
  bool pop(link::Packet& out, std::chrono::milliseconds wait = std::chrono::milliseconds(0));

  StreamStats stats() const;
  std::optional<link::StatusBlock> last_status() const;
  // Waits until `n` STATUS packets in total have arrived.
  bool wait_status_count(uint64_t n, std::chrono::milliseconds timeout);
  uint64_t status_count() const;

  // Sends one wire frame as is (throws LinkError when not connected).
  void send(const std::vector<uint8_t>& wire);
  // Sends a named command (commands.h) and waits for the FPGA's verdict:
  // waits for the link to open (within the timeout), requests a baseline
  // STATUS if none was seen, then sends the command and REQUEST_STATUS and
  // judges the STATUS packets that follow. Throws LinkError if the link is
  // not open by then. Never call it from a packet callback: the verdict
  // arrives through the reader thread that runs the callback. Any other
  // thread may call it while packets are delivered (a stream takes
  // commands through its control socket as it records: control_server.h);
  // commands go out one at a time.
  // Throws std::invalid_argument for an unknown name or bad arguments.
  CommandReply command(const std::string& name, const std::vector<std::string>& args,
                       std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));
  CommandReply command(const CommandSpec& spec, const std::vector<int64_t>& args,
                       std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));

 private:
  void run();
  bool open_with_backoff(int& failures);
  void deliver(const link::Packet& p);
  void check_idle(std::chrono::steady_clock::time_point now);
  int probe_rates();
  std::string wrong_baud_message(const link::DecoderStats& d, int found) const;

  StreamOptions opt_;
  PacketFn on_packet_;
  std::map<uint8_t, PacketFn> on_type_;
  EventFn on_event_;

  std::thread reader_;
  std::atomic<bool> running_{false};
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  std::atomic<StreamEnd> ended_{StreamEnd::Running};
  // Reader thread only: the last packet's arrival (or the link's opening),
  // and whether the idle time was reported.
  std::chrono::steady_clock::time_point last_packet_at_;
  bool idle_reported_ = false;

  mutable std::mutex chan_mu_;  // channel_ (reader reopens, command() writes)
  Channel channel_;

  mutable std::mutex mu_;       // queue_, stats_, statuses
  std::condition_variable cv_;
  std::deque<link::Packet> queue_;
  StreamStats stats_;
  link::DecoderStats closed_links_;  // decoder stats of finished connections
  uint64_t sync_closed_ = 0;         // their sync_bytes
  std::optional<link::StatusBlock> last_status_;
  uint64_t status_count_ = 0;
  // The latest STATUS packets with their arrival number (1-based), for command().
  std::deque<std::pair<uint64_t, link::StatusBlock>> recent_status_;
  // The latest HALL_DECODE_STATUS packets, numbered the same way.
  std::deque<std::pair<uint64_t, link::HallDecodeStatus>> recent_hall_status_;
  uint64_t hall_status_count_ = 0;
  CommandReply hall_command(const CommandSpec& spec, const std::vector<int64_t>& args,
                            std::chrono::steady_clock::time_point deadline);

  std::mutex cmd_mu_;           // one command at a time
  link::LinkEncoder encoder_;
};

}  // namespace eskin::stream

namespace eskin::stream {
// The statistics as one JSON object (NDJSON summaries, the live view).
std::string stats_json(const StreamStats& s);
}  // namespace eskin::stream
