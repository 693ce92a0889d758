#include "host/stream/stream_memory.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "eskin/process.h"
#include "host/link/link_encoder.h"

namespace eskin::stream {
namespace {

namespace fs = std::filesystem;
using clock_type = std::chrono::steady_clock;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// The board's end of a pseudo-terminal: the master, and the slave's path
// that `eskin stream --port` opens like /dev/ttyUSB0. Raw from the start,
// so nothing written before the stream sets the line up is translated.
class Pty {
 public:
  Pty() {
    // CLOEXEC: the child must not hold the board's end open.
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0)
      throw std::runtime_error(std::string("posix_openpt: ") + std::strerror(errno));
    slave_ = ptsname(master_);
    const int s = ::open(slave_.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (s < 0) throw std::runtime_error(slave_ + ": " + std::strerror(errno));
    termios t{};
    tcgetattr(s, &t);
    cfmakeraw(&t);
    tcsetattr(s, TCSANOW, &t);
    ::close(s);
    // Non-blocking: the writer polls, so a child that dies never hangs it.
    fcntl(master_, F_SETFL, fcntl(master_, F_GETFL) | O_NONBLOCK);
  }
  ~Pty() { close_master(); }
  Pty(const Pty&) = delete;
  Pty& operator=(const Pty&) = delete;
  int master() const { return master_; }
  const std::string& slave() const { return slave_; }
  void close_master() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
  }
  // Bytes written into the master that the slave's reader has not read yet.
  int unread() const {
    const int s = ::open(slave_.c_str(), O_RDONLY | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
    if (s < 0) return -1;
    int n = -1;
    if (::ioctl(s, FIONREAD, &n) != 0) n = -1;
    ::close(s);
    return n;
  }

 private:
  int master_ = -1;
  std::string slave_;
};

// VmRSS and VmHWM of `pid` in KiB (false when it is gone).
bool read_rss(pid_t pid, MemorySample& s) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  bool rss = false, hwm = false;
  for (std::string line; std::getline(f, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::sscanf(line.c_str() + 6, "%lu", &s.rss_kib) == 1;
    if (line.rfind("VmHWM:", 0) == 0) hwm = std::sscanf(line.c_str() + 6, "%lu", &s.hwm_kib) == 1;
  }
  return rss && hwm;
}

// Bytes `pid`'s threads have taken with read() and its kin so far
// (/proc/PID/io rchar), or -1 when it is gone.
int64_t read_rchar(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/io");
  for (std::string line; std::getline(f, line);)
    if (line.rfind("rchar:", 0) == 0) return std::stoll(line.substr(6));
  return -1;
}

// The packets of a DTMF board, one after the other (sizes: stream_memory.h):
// each frame's AMPLITUDES, TAXELS dense and SPIKES, and a STATUS after
// every 1000th frame.
class BoardMix {
 public:
  void append(std::vector<uint8_t>& out) {
    const uint32_t t = uint32_t(frame_ * kStep + kStep - 1);  // the frame's newest sample
    std::vector<uint8_t> w;
    if (slot_ == 0) {
      std::vector<uint16_t> amps(16);
      for (auto& a : amps) a = uint16_t(next() >> 20);  // 12-bit window sums
      w = enc_.amplitudes(t, amps);
    } else if (slot_ == 1) {
      std::vector<uint16_t> taxels(16);
      for (auto& v : taxels) v = uint16_t(next() >> 17);  // UQ1.15
      w = enc_.taxels_dense(t, 4, 4, taxels);
    } else if (slot_ == 2) {
      std::vector<link::SpikeEvent> ev(1 + next() % 3);
      for (auto& e : ev) e = {uint16_t(next() % kStep), uint8_t(next() % 2), uint16_t(next() % 16)};
      w = enc_.spikes(t, ev);
    } else {
      link::StatusBlock s;
      s.cmd_accepted = 3;
      s.output_mask = 7;
      s.samples = t + 1;
      w = enc_.status(t, s);
    }
    out.insert(out.end(), w.begin(), w.end());
    const bool status_next = slot_ == 2 && (frame_ + 1) % kStatusFrames == 0;
    if (slot_ == 2 && !status_next) slot_ = 0, ++frame_;
    else if (slot_ == 3) slot_ = 0, ++frame_;
    else ++slot_;
  }

 private:
  static constexpr uint64_t kStep = 64;          // ADC samples per frame
  static constexpr uint64_t kStatusFrames = 1000;  // STATUS decimation at reset
  uint32_t next() { return state_ = state_ * 1664525u + 1013904223u; }
  link::LinkEncoder enc_;
  uint32_t state_ = 1;
  uint64_t frame_ = 0;
  int slot_ = 0;  // 0 AMPLITUDES, 1 TAXELS, 2 SPIKES, 3 STATUS
};

// Writes all of `buf` into the non-blocking master, polling while the pty
// is full. False (with *why) when the child ended or nothing moved for
// stall_s.
bool write_all(Pty& pty, ChildProcess& child, const std::vector<uint8_t>& buf, double stall_s,
               std::string* why) {
  size_t off = 0;
  auto last_progress = clock_type::now();
  while (off < buf.size()) {
    const ssize_t w = ::write(pty.master(), buf.data() + off, buf.size() - off);
    if (w > 0) {
      off += size_t(w);
      last_progress = clock_type::now();
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EINTR) {
      *why = std::string("writing the pty master: ") + std::strerror(errno);
      return false;
    }
    pollfd q{pty.master(), POLLOUT, 0};
    ::poll(&q, 1, 100);
    if (child.poll_exit() >= 0) {
      *why = "eskin stream ended while packets were being written";
      return false;
    }
    if (clock_type::now() - last_progress > std::chrono::duration<double>(stall_s)) {
      *why = "eskin stream read nothing for " + std::to_string(int(stall_s)) + " s";
      return false;
    }
  }
  return true;
}

// "eskin stream: N packets; link {...}" in its stderr.
void parse_final_line(MemoryResult& r) {
  const std::string key = "eskin stream: ";
  std::istringstream in(r.child_stderr);
  for (std::string line; std::getline(in, line);) {
    const size_t at = line.find(" packets; link {");
    if (line.rfind(key, 0) != 0 || at == std::string::npos) continue;
    try {
      const uint64_t n = std::stoull(line.substr(key.size(), at - key.size()));
      const auto j = nlohmann::json::parse(line.substr(line.find('{', at)));
      r.packets_counted = n;
      r.frames_ok = j.at("frames_ok").get<uint64_t>();
      r.lost_packets = j.at("lost_packets").get<uint64_t>();
      r.corrupt_frames = j.at("crc_errors").get<uint64_t>() +
                         j.at("framing_errors").get<uint64_t>() +
                         j.at("payload_errors").get<uint64_t>();
      r.counted = true;
    } catch (const std::exception&) {
      r.counted = false;
    }
  }
}

std::string kib_text(uint64_t k) { return std::to_string(k) + " KiB"; }

}  // namespace

const MemorySample& MemoryResult::warm() const {
  for (const MemorySample& s : samples)
    if (s.packets >= sample_every && s.packets > 0) return s;
  return samples.back();
}

bool MemoryResult::delivered_all() const {
  return error.empty() && exit_code == 0 && counted && packets_counted == packets_written &&
         frames_ok == packets_written && lost_packets == 0 && corrupt_frames == 0 &&
         samples.size() >= 2;
}

MemoryResult measure_stream_memory(const MemoryOptions& o) {
  if (o.packets == 0) throw std::invalid_argument("--packets: must be at least 1");
  MemoryResult r;
  r.sample_every = o.sample_every ? o.sample_every
                                  : std::max<uint64_t>(1, std::min<uint64_t>(1000000, o.packets / 10));
  // A private directory for the child's output and the recording.
  std::string tmpl = (fs::temp_directory_path() / "eskin-stream-memory-XXXXXX").string();
  if (!::mkdtemp(tmpl.data()))
    throw std::runtime_error("cannot create a directory under " +
                             fs::temp_directory_path().string() + ": " + std::strerror(errno));
  const fs::path dir = tmpl;
  struct Cleanup {
    fs::path d;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
  } cleanup{dir};

  Pty pty;
  // No --count: the stream ends when the master hangs up after the last
  // byte was read, so its count is every packet it took, not a cap on it.
  r.argv = {o.eskin_bin, "stream", "--port", pty.slave(), "--baud", std::to_string(o.baud), "-q"};
  const fs::path h5 = dir / "stream.h5";
  r.hdf5 = o.hdf5;
  if (o.hdf5) {
    r.argv.push_back("--hdf5");
    r.argv.push_back(h5.string());
  }
  ChildProcess child(r.argv, (dir / "stdout.txt").string(), (dir / "stderr.txt").string());
  if (!child.started())
    throw std::runtime_error(r.argv[0] + ": cannot start: " + std::strerror(child.start_error()));

  // Bytes written before the stream has the port open and set up could be
  // flushed by its set-up: wait for "link open".
  const auto open_by = clock_type::now() + std::chrono::seconds(20);
  while (slurp(dir / "stderr.txt").find("link open") == std::string::npos) {
    if (child.poll_exit() >= 0 || clock_type::now() > open_by) {
      r.error = child.poll_exit() >= 0 ? "eskin stream ended before the link opened"
                                       : "eskin stream did not open the link within 20 s";
      child.signal(SIGKILL);
      r.exit_code = child.wait_exit(std::chrono::seconds(10));
      r.child_stderr = slurp(dir / "stderr.txt");
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const auto t0 = clock_type::now();
  // Everything the stream reads from here on is the pty's (and, recording,
  // the HDF5 file's own metadata, which only makes the count larger).
  const int64_t rchar_at_open = read_rchar(child.pid());
  const auto sample = [&](uint64_t written) {
    MemorySample s;
    s.packets = written;
    s.seconds = std::chrono::duration<double>(clock_type::now() - t0).count();
    if (!read_rss(child.pid(), s)) return false;
    r.samples.push_back(s);
    return true;
  };
  if (!sample(0)) r.error = "cannot read /proc/" + std::to_string(child.pid()) + "/status";

  BoardMix mix;
  std::vector<uint8_t> buf;
  buf.reserve(1 << 17);
  for (uint64_t i = 0; i < o.packets && r.error.empty(); ++i) {
    mix.append(buf);
    ++r.packets_written;
    const bool at_sample = r.packets_written % r.sample_every == 0 && r.packets_written < o.packets;
    if (buf.size() >= (1 << 16) || at_sample || r.packets_written == o.packets) {
      if (!write_all(pty, child, buf, o.stall_s, &r.error)) break;
      r.wire_bytes += buf.size();
      buf.clear();
    }
    if (at_sample && !sample(r.packets_written))
      r.error = "eskin stream ended at packet " + std::to_string(r.packets_written);
  }
  // Every byte read by the stream before the last sample and the hang-up:
  // the slave's FIONREAD misses bytes still in the tty's flip buffer (the
  // kernel moves them to the line discipline from a worker), and a hang-up
  // flushes them, so the stream's own read count must cover every byte
  // written and nothing may wait in the line discipline.
  const auto taken = [&] {
    const int64_t now = read_rchar(child.pid());
    return rchar_at_open >= 0 && now >= 0 && uint64_t(now - rchar_at_open) >= r.wire_bytes;
  };
  if (r.error.empty()) {
    const auto drained_by = clock_type::now() + std::chrono::duration<double>(o.stall_s);
    while ((pty.unread() != 0 || !taken()) && r.error.empty()) {
      if (child.poll_exit() >= 0) r.error = "eskin stream ended before reading every byte";
      else if (clock_type::now() > drained_by)
        r.error = "eskin stream left " + std::to_string(pty.unread()) +
                  " bytes unread in the pty and read " +
                  std::to_string(read_rchar(child.pid()) - rchar_at_open) + " of " +
                  std::to_string(r.wire_bytes) + " bytes written";
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  if (r.error.empty() && !sample(r.packets_written))
    r.error = "eskin stream ended before the last sample";
  pty.close_master();
  r.exit_code = child.wait_exit(std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::duration<double>(o.stall_s)));
  if (r.exit_code < 0) {
    if (r.error.empty()) r.error = "eskin stream did not end after the pty hung up";
    child.signal(SIGKILL);
    r.exit_code = child.wait_exit(std::chrono::seconds(10));
  }
  r.wall_s = std::chrono::duration<double>(clock_type::now() - t0).count();
  r.child_stderr = slurp(dir / "stderr.txt");
  parse_final_line(r);
  std::error_code ec;
  if (o.hdf5) r.hdf5_bytes = fs::file_size(h5, ec);
  return r;
}

std::string memory_text(const MemoryResult& r) {
  std::ostringstream s;
  s << "stream memory: " << r.packets_written << " packets (" << r.wire_bytes
    << " bytes) into a pty read by `eskin stream`; VmRSS every " << r.sample_every
    << " packets\n\n";
  char line[160];
  std::snprintf(line, sizeof line, "%12s %12s %12s %10s\n", "packets", "VmRSS KiB", "VmHWM KiB",
                "seconds");
  s << line;
  for (const MemorySample& m : r.samples) {
    std::snprintf(line, sizeof line, "%12lu %12lu %12lu %10.2f\n", (unsigned long)m.packets,
                  (unsigned long)m.rss_kib, (unsigned long)m.hwm_kib, m.seconds);
    s << line;
  }
  s << "\n";
  if (!r.samples.empty()) {
    s << "RSS growth from " << r.warm().packets << " to " << r.last().packets
      << " packets: " << r.growth_kib() << " KiB; VmHWM " << kib_text(r.last().hwm_kib) << "\n";
  }
  s << "eskin stream: exit " << r.exit_code << ", " << r.packets_counted << " packets counted, "
    << r.lost_packets << " lost, " << r.corrupt_frames << " corrupt frames";
  if (r.hdf5) s << "; HDF5 recording " << r.hdf5_bytes << " bytes";
  std::snprintf(line, sizeof line, "; %.1f s wall, %.0f packets/s\n", r.wall_s,
                r.wall_s > 0 ? double(r.packets_written) / r.wall_s : 0.0);
  s << line;
  if (!r.error.empty()) s << "error: " << r.error << "\n";
  return s.str();
}

std::string memory_csv(const MemoryResult& r, const std::string& command) {
  const std::string src = "\"" + command + "\"";
  std::ostringstream s;
  s << "# The streaming path's memory (docs/bench.md, \"Memory under a long stream\"), written by\n"
       "# `eskin bench memory --csv` (host/stream/stream_memory.h); cited as <!--fig:"
    << (r.hdf5 ? "stream_memory_hdf5" : "stream_memory")
    << "/NAME-->.\n# VmRSS of `eskin stream` every " << r.sample_every
    << " packets written into its pty (rss_kib_at_N).\nname,value,unit,source\n";
  const auto row = [&](const std::string& name, const std::string& v, const char* unit) {
    s << name << "," << v << "," << unit << "," << src << "\n";
  };
  const auto num = [](double v, int decimals) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    return std::string(b);
  };
  row("packets_written", std::to_string(r.packets_written), "packets");
  row("packets_counted", std::to_string(r.packets_counted), "packets");
  row("packets_lost", std::to_string(r.lost_packets), "packets");
  row("corrupt_frames", std::to_string(r.corrupt_frames), "frames");
  row("exit_code", std::to_string(r.exit_code), "code");
  row("wire_bytes", std::to_string(r.wire_bytes), "bytes");
  for (const MemorySample& m : r.samples)
    row("rss_kib_at_" + std::to_string(m.packets), std::to_string(m.rss_kib), "KiB");
  if (!r.samples.empty()) {
    row("rss_warm_kib", std::to_string(r.warm().rss_kib), "KiB");
    row("rss_end_kib", std::to_string(r.last().rss_kib), "KiB");
    row("rss_growth_kib", std::to_string(r.growth_kib()), "KiB");
    row("hwm_kib", std::to_string(r.last().hwm_kib), "KiB");
  }
  if (r.hdf5) row("hdf5_bytes", std::to_string(r.hdf5_bytes), "bytes");
  row("wall_s", num(r.wall_s, 1), "s");
  row("packets_per_s", num(r.wall_s > 0 ? double(r.packets_written) / r.wall_s : 0, 0),
      "packets/s");
  return s.str();
}

}  // namespace eskin::stream
