#include "host/stream/link_stream.h"

#include <algorithm>
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
    connected_ = true;
    if (on_event_) on_event_({LinkEvent::Kind::Opened, opt_.endpoint.describe(), 0});

    link::LinkDecoder dec(opt_.max_payload);
    dec.on_packet([this](const link::Packet& p) { deliver(p); });
    // A connection may start inside a frame: if the bytes up to its first
    // 0x00 do not decode, they are a partial frame (sync_bytes), not an error.
    bool synced = false;
    link::DecoderStats excused;
    std::string why;
    while (!stop_) {
      size_t got = 0;
      const ReadStatus st = channel_.read(buf.data(), buf.size(), got, 50, &why);
      if (st == ReadStatus::Timeout) continue;
      if (st == ReadStatus::Closed) break;
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
      std::lock_guard<std::mutex> lk(mu_);
      stats_.link = closed_links_;
      add(stats_.link, connection_stats(dec.stats(), excused));
      stats_.sync_bytes = sync_closed_ + excused.bytes;
    }
    {
      std::lock_guard<std::mutex> lk(mu_);
      add(closed_links_, connection_stats(dec.stats(), excused));
      sync_closed_ += excused.bytes;
      stats_.sync_bytes = sync_closed_;
      stats_.link = closed_links_;
      if (!stop_) ++stats_.disconnects;
    }
    {
      std::lock_guard<std::mutex> lk(chan_mu_);
      channel_.close();
    }
    connected_ = false;
    if (!stop_ && on_event_) on_event_({LinkEvent::Kind::Lost, why, 0});
    if (!opt_.reconnect) break;
  }
  connected_ = false;
  cv_.notify_all();
}

void LinkStream::deliver(const link::Packet& p) {
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
                  "," + kv("sync_bytes", s.sync_bytes) + "," + kv("connects", s.connects) + "," +
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
