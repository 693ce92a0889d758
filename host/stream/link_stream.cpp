#include "host/stream/link_stream.h"

#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace eskin::stream {

namespace {

constexpr size_t kRecentStatus = 64;

void add(link::DecoderStats& a, const link::DecoderStats& b) {
  a.bytes += b.bytes;
  a.frames_ok += b.frames_ok;
  a.crc_errors += b.crc_errors;
  a.framing_errors += b.framing_errors;
  a.payload_errors += b.payload_errors;
  a.seq_gaps += b.seq_gaps;
  a.lost_packets += b.lost_packets;
  a.restarts += b.restarts;
}

// A UNIX98 pty slave (char major 136-143, Documentation/admin-guide/
// devices.txt): the virtual board's port, or another program's pty. fstat
// on the open descriptor, so a symlink to it counts as what it points to.
bool is_pty_slave(int fd) {
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISCHR(st.st_mode)) return false;
  const unsigned m = major(st.st_rdev);
  return m >= 136 && m <= 143;
}

std::string seconds_text(double s) {
  char b[32];
  std::snprintf(b, sizeof b, s == double(long(s)) ? "%.0f" : "%.1f", s);
  return b;
}

// A connection's decoder statistics without the partial first frame.
link::DecoderStats connection_stats(link::DecoderStats s, const link::DecoderStats& excused) {
  s.crc_errors -= excused.crc_errors;
  s.framing_errors -= excused.framing_errors;
  return s;
}

}  // namespace

LinkStream::LinkStream(StreamOptions opt) : opt_(std::move(opt)) {}

LinkStream::~LinkStream() { stop(); }

void LinkStream::on_packet(PacketFn fn) { on_packet_ = std::move(fn); }
void LinkStream::on_type(uint8_t type, PacketFn fn) { on_type_[type] = std::move(fn); }
void LinkStream::on_event(EventFn fn) { on_event_ = std::move(fn); }

void LinkStream::start() {
  if (running_) return;
  stop_ = false;
  ended_ = StreamEnd::Running;
  if (!opt_.reconnect) {  // the first open must work: fail here, in the caller
    Channel ch(opt_.endpoint);
    std::lock_guard<std::mutex> lk(chan_mu_);
    channel_ = std::move(ch);
  }
  running_ = true;
  reader_ = std::thread([this] { run(); });
}

void LinkStream::stop() {
  stop_ = true;
  if (reader_.joinable()) reader_.join();
  running_ = false;
  std::lock_guard<std::mutex> lk(chan_mu_);
  channel_.close();
  connected_ = false;
}

bool LinkStream::open_with_backoff(int& failures) {
  int delay = opt_.backoff_min_ms;
  for (int i = 1; i < failures; ++i) delay = std::min(delay * 2, opt_.backoff_max_ms);
  while (!stop_) {
    try {
      Channel ch(opt_.endpoint);
      std::lock_guard<std::mutex> lk(chan_mu_);
      channel_ = std::move(ch);
      return true;
    } catch (const LinkError& e) {
      ++failures;
      if (on_event_) on_event_({LinkEvent::Kind::OpenFailed, e.what(), failures});
      if (!opt_.reconnect) return false;
    }
    // Sleep in small slices so stop() stays prompt.
    for (int waited = 0; waited < delay && !stop_; waited += 10)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    delay = std::min(delay * 2, opt_.backoff_max_ms);
  }
  return false;
}

void LinkStream::run() {
  using clock = std::chrono::steady_clock;
  std::vector<uint8_t> buf(1 << 16);
  int failures = 0;
  bool first = true;
  while (!stop_) {
    bool have = false;
    {
      std::lock_guard<std::mutex> lk(chan_mu_);
      have = channel_.is_open();
    }
    if (!have && !(first || opt_.reconnect)) break;
    if (!have && !open_with_backoff(failures)) break;
    first = false;
    failures = 0;
    {
      std::lock_guard<std::mutex> lk(mu_);
      ++stats_.connects;
    }
    const bool serial = opt_.endpoint.kind == Endpoint::Kind::Serial;
    const bool on_pty = serial && is_pty_slave(channel_.fd());
    connected_ = true;
    if (on_event_) on_event_({LinkEvent::Kind::Opened, opt_.endpoint.describe(), 0});

    link::LinkDecoder dec(opt_.max_payload);
    dec.on_packet([this](const link::Packet& p) { deliver(p); });
    last_packet_at_ = clock::now();
    idle_reported_ = false;
    std::optional<clock::time_point> first_byte_at;
    // A connection may start inside a frame: if the bytes up to its first
    // 0x00 do not decode, they are a partial frame (sync_bytes), not an error.
    bool synced = false;
    link::DecoderStats excused;
    std::string why;
    bool wrong_baud = false;
    while (!stop_) {
      size_t got = 0;
      const ReadStatus st = channel_.read(buf.data(), buf.size(), got, 50, &why);
      const auto now = clock::now();
      check_idle(now);
      if (st == ReadStatus::Timeout) continue;
      if (st == ReadStatus::Closed) break;
      if (!first_byte_at) first_byte_at = now;
      size_t from = 0;
      if (!synced) {
        const auto* z = std::find(buf.data(), buf.data() + got, uint8_t(0));
        from = size_t(z - buf.data()) + (z < buf.data() + got ? 1 : 0);
        const link::DecoderStats before = dec.stats();
        dec.feed(buf.data(), from);
        synced = from > 0 && buf[from - 1] == 0;
        if (synced && dec.stats().frames_ok == before.frames_ok) {
          excused.bytes = from + before.bytes;  // bytes before the first good frame
          excused.crc_errors = dec.stats().crc_errors;
          excused.framing_errors = dec.stats().framing_errors;
        }
      }
      dec.feed(buf.data() + from, got - from);
      {
        std::lock_guard<std::mutex> lk(mu_);
        stats_.link = closed_links_;
        add(stats_.link, connection_stats(dec.stats(), excused));
        stats_.sync_bytes = sync_closed_ + excused.bytes;
      }
      // Bytes, link errors and not one packet: the line runs at another
      // rate than ours (a real UART then reads garbage with framing errors).
      const link::DecoderStats& d = dec.stats();
      if (serial && opt_.detect_baud && d.frames_ok == 0 &&
          d.crc_errors + d.framing_errors + d.payload_errors >= 2 &&
          (d.bytes >= opt_.baud_check_bytes ||
           now - *first_byte_at >= std::chrono::milliseconds(opt_.baud_check_ms))) {
        wrong_baud = true;
        break;
      }
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      add(closed_links_, connection_stats(dec.stats(), excused));
      sync_closed_ += excused.bytes;
      stats_.sync_bytes = sync_closed_;
      stats_.link = closed_links_;
      if (!stop_ && !wrong_baud) ++stats_.disconnects;
    }
    {
      std::lock_guard<std::mutex> lk(chan_mu_);
      channel_.close();
    }
    connected_ = false;
    if (wrong_baud) {
      const link::DecoderStats d = dec.stats();
      const int found = probe_rates();
      if (stop_) break;
      ended_ = StreamEnd::WrongBaud;
      if (on_event_) on_event_({LinkEvent::Kind::WrongBaud, wrong_baud_message(d, found), found});
      break;
    }
    if (stop_) break;
    // A pty's master closed: that board is gone for good (a board started
    // again gets a new pty; the old /dev/pts/N no longer exists).
    if (on_pty && opt_.pty_hangup_ends) {
      ended_ = StreamEnd::HungUp;
      if (on_event_)
        on_event_({LinkEvent::Kind::HungUp,
                   opt_.endpoint.path + ": the board hung up (the virtual board's scene is over)",
                   0});
      break;
    }
    if (on_event_) on_event_({LinkEvent::Kind::Lost, why, 0});
    if (!opt_.reconnect) {
      ended_ = StreamEnd::Lost;
      break;
    }
  }
  connected_ = false;
  cv_.notify_all();
}

// On the reader thread, at every read: an open link without a packet for
// idle_after_ms is reported once (deliver() reports the packets' return).
void LinkStream::check_idle(std::chrono::steady_clock::time_point now) {
  if (opt_.idle_after_ms <= 0 || idle_reported_ ||
      now - last_packet_at_ < std::chrono::milliseconds(opt_.idle_after_ms))
    return;
  idle_reported_ = true;
  if (on_event_)
    on_event_({LinkEvent::Kind::Idle,
               "no packets for " + seconds_text(opt_.idle_after_ms / 1000.0) +
                   " s: the board is idle",
               0});
}

// Reopens the port at each of probe_bauds() (not the rate that failed) for
// up to probe_ms; returns the first at which two packets decode (0: none).
// A board (and the virtual board, which follows its reader's rate) sends
// at its own rate whatever ours is, so the right rate decodes at once.
int LinkStream::probe_rates() {
  using clock = std::chrono::steady_clock;
  std::vector<uint8_t> buf(1 << 16);
  for (int baud : probe_bauds()) {
    if (baud == opt_.endpoint.baud) continue;
    Endpoint ep = opt_.endpoint;
    ep.baud = baud;
    Channel ch;
    try {
      ch = Channel(ep);
    } catch (const LinkError&) {
      continue;  // the driver refuses the rate: it cannot be the line's
    }
    link::LinkDecoder dec(opt_.max_payload);
    const auto end = clock::now() + std::chrono::milliseconds(opt_.probe_ms);
    while (!stop_ && clock::now() < end && dec.stats().frames_ok < 2) {
      size_t got = 0;
      const ReadStatus st = ch.read(buf.data(), buf.size(), got, 20, nullptr);
      if (st == ReadStatus::Closed) break;
      dec.feed(buf.data(), got);
    }
    if (stop_) return 0;
    if (dec.stats().frames_ok >= 2) return baud;
  }
  return 0;
}

std::string LinkStream::wrong_baud_message(const link::DecoderStats& d, int found) const {
  std::string errors = std::to_string(d.framing_errors) + " framing errors";
  if (d.crc_errors) errors += ", " + std::to_string(d.crc_errors) + " CRC errors";
  if (d.payload_errors) errors += ", " + std::to_string(d.payload_errors) + " payload errors";
  std::string m = opt_.endpoint.path + ": no packet decoded at " +
                  std::to_string(opt_.endpoint.baud) + " baud (" + errors + " in " +
                  std::to_string(d.bytes) + " bytes); ";
  if (found > 0)
    return m + "the line decodes at " + std::to_string(found) + " baud: use --baud " +
           std::to_string(found);
  std::string rates;
  for (int b : probe_bauds())
    if (b != opt_.endpoint.baud) rates += (rates.empty() ? "" : ", ") + std::to_string(b);
  return m + "no packet decoded at " + rates + " either: is it the board's link?";
}

void LinkStream::deliver(const link::Packet& p) {
  const auto now = std::chrono::steady_clock::now();
  if (idle_reported_) {
    idle_reported_ = false;
    if (on_event_)
      on_event_({LinkEvent::Kind::Resumed,
                 "packets again after " +
                     seconds_text(std::chrono::duration<double>(now - last_packet_at_).count()) +
                     " s",
                 0});
  }
  last_packet_at_ = now;
  if (on_packet_) on_packet_(p);
  const auto it = on_type_.find(p.type);
  if (it != on_type_.end()) it->second(p);
  {
    std::lock_guard<std::mutex> lk(mu_);
    ++stats_.packets_by_type[p.type];
    if (p.type == link::kStatus) {
      last_status_ = p.status;
      recent_status_.push_back({++status_count_, p.status});
      if (recent_status_.size() > kRecentStatus) recent_status_.pop_front();
    }
    if (p.type == link::kHallDecodeStatus) {
      recent_hall_status_.push_back({++hall_status_count_, p.hall.status});
      if (recent_hall_status_.size() > kRecentStatus) recent_hall_status_.pop_front();
    }
    if (opt_.queue_capacity > 0) {
      if (queue_.size() >= opt_.queue_capacity) {
        queue_.pop_front();
        ++stats_.queue_dropped;
      }
      queue_.push_back(p);
    }
  }
  cv_.notify_all();
}

bool LinkStream::pop(link::Packet& out, std::chrono::milliseconds wait) {
  std::unique_lock<std::mutex> lk(mu_);
  if (!cv_.wait_for(lk, wait, [this] { return !queue_.empty(); })) return false;
  out = std::move(queue_.front());
  queue_.pop_front();
  return true;
}

StreamStats LinkStream::stats() const {
  std::lock_guard<std::mutex> lk(mu_);
  return stats_;
}

std::optional<link::StatusBlock> LinkStream::last_status() const {
  std::lock_guard<std::mutex> lk(mu_);
  return last_status_;
}

uint64_t LinkStream::status_count() const {
  std::lock_guard<std::mutex> lk(mu_);
  return status_count_;
}

bool LinkStream::wait_status_count(uint64_t n, std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lk(mu_);
  return cv_.wait_for(lk, timeout, [&] { return status_count_ >= n; });
}

void LinkStream::send(const std::vector<uint8_t>& wire) {
  std::lock_guard<std::mutex> lk(chan_mu_);
  if (!channel_.is_open())
    throw LinkError(opt_.endpoint.describe() + ": cannot send: link is not open");
  channel_.write_all(wire.data(), wire.size());
}

CommandReply LinkStream::command(const std::string& name, const std::vector<std::string>& args,
                                 std::chrono::milliseconds timeout) {
  const CommandSpec* spec = find_command(name);
  if (!spec) {
    std::string known;
    for (const CommandSpec& c : command_specs()) known += std::string(" ") + c.name;
    throw std::invalid_argument("unknown command '" + name + "'; expected one of:" + known);
  }
  return command(*spec, parse_command_args(*spec, args), timeout);
}

CommandReply LinkStream::command(const CommandSpec& spec, const std::vector<int64_t>& args,
                                 std::chrono::milliseconds timeout) {
  std::lock_guard<std::mutex> cmd_lock(cmd_mu_);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  CommandReply r;
  r.type = spec.type;
  // Right after start() the reader may still be opening the link.
  while (!connected_ && running_ && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (spec.hall) return hall_command(spec, args, deadline);
  if (!last_status()) {  // no baseline yet: ask for one
    const uint64_t n = status_count();
    send(encoder_.request_status());
    if (!wait_status_count(n + 1, timeout)) {
      r.message = "no STATUS packet from the board (is status output masked or the link down?)";
      return r;
    }
  }
  link::StatusBlock base;
  uint64_t seen;
  {
    std::lock_guard<std::mutex> lk(mu_);
    base = *last_status_;
    seen = status_count_;
  }
  r.seq = encoder_.next_seq();
  std::vector<uint8_t> wire = spec.build(encoder_, args);
  const std::vector<uint8_t> req = encoder_.request_status();
  wire.insert(wire.end(), req.begin(), req.end());
  send(wire);

  std::unique_lock<std::mutex> lk(mu_);
  while (true) {
    for (const auto& [index, st] : recent_status_) {
      if (index <= seen) continue;
      seen = index;
      r.ack = judge_reply(spec.type, r.seq, base, st);
      if (r.ack == Ack::Pending) continue;
      r.status = st;
      if (r.ack == Ack::Accepted) r.message = "accepted";
      if (r.ack == Ack::Rejected)
        r.message = "rejected: " + reject_reason_text(st.last_reject_reason);
      if (r.ack == Ack::Unknown)
        r.message = "unknown: the FPGA's command counters are saturated (send 'clear')";
      return r;
    }
    if (cv_.wait_until(lk, deadline) == std::cv_status::timeout) {
      r.message = "no verdict: no STATUS packet decided it in time";
      return r;
    }
  }
}

}  // namespace eskin::stream

namespace eskin::stream {

std::string stats_json(const StreamStats& s) {
  const auto kv = [](const char* k, uint64_t v) {
    return std::string("\"") + k + "\":" + std::to_string(v);
  };
  std::string j = "{" + kv("bytes", s.link.bytes) + "," + kv("frames_ok", s.link.frames_ok) + "," +
                  kv("crc_errors", s.link.crc_errors) + "," +
                  kv("framing_errors", s.link.framing_errors) + "," +
                  kv("payload_errors", s.link.payload_errors) + "," +
                  kv("seq_gaps", s.link.seq_gaps) + "," + kv("lost_packets", s.link.lost_packets) +
                  "," + kv("restarts", s.link.restarts) + "," + kv("sync_bytes", s.sync_bytes) + "," + kv("connects", s.connects) + "," +
                  kv("disconnects", s.disconnects) + "," + kv("queue_dropped", s.queue_dropped) +
                  "}";
  return j;
}

// A Hall command: the HALL_DECODE_STATUS before it is the base (waited for
// when none has come yet: the top sends one every STATUS_EVERY frames), the
// ones after it are judged.
CommandReply LinkStream::hall_command(const CommandSpec& spec, const std::vector<int64_t>& args,
                                      std::chrono::steady_clock::time_point deadline) {
  CommandReply r;
  r.type = spec.type;
  std::unique_lock<std::mutex> lk(mu_);
  if (!cv_.wait_until(lk, deadline, [this] { return !recent_hall_status_.empty(); })) {
    r.message = "no HALL_DECODE_STATUS packet from the board (is it a Hall top with DELTAS, "
                "and the link up?)";
    return r;
  }
  const link::HallDecodeStatus base = recent_hall_status_.back().second;
  uint64_t seen = recent_hall_status_.back().first;
  r.seq = encoder_.next_seq();
  const std::vector<uint8_t> wire = spec.build(encoder_, args);
  lk.unlock();
  send(wire);
  lk.lock();
  while (true) {
    for (const auto& [index, st] : recent_hall_status_) {
      if (index <= seen) continue;
      seen = index;
      r.ack = judge_hall_reply(spec.type, r.seq, base, st);
      if (r.ack == Ack::Pending) continue;
      r.hall_status = st;
      r.message = r.ack == Ack::Accepted   ? "accepted"
                  : r.ack == Ack::Rejected ? "rejected: " + reject_reason_text(st.last_reject_reason)
                                           : "unknown: the Hall top's command counters are saturated";
      return r;
    }
    if (cv_.wait_until(lk, deadline) == std::cv_status::timeout) {
      r.message = "no verdict: no HALL_DECODE_STATUS decided it in time";
      return r;
    }
  }
}

}  // namespace eskin::stream
