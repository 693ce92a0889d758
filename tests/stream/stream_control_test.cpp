// Stream and command at once: `eskin stream` owns the board's port and
// `eskin config` on the same port goes through it (host/stream/port_lock.h,
// control_server.h). The board is a real pty whose other end this test
// plays: it streams data packets without pause and answers commands as
// docs/protocol.md §5 says (a STATUS after REQUEST_STATUS and after a
// rejection), every frame through one encoder, so the recording must hold
// exactly the packets it sent, with no sequence gap and no framing error.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "host/stream/control_server.h"
#include "host/stream/link_stream.h"
#include "host/stream/port_lock.h"
#include "tests/stream/process.h"
#include "tests/stream/pty_pair.h"
#include "tests/stream/recording.h"

namespace fs = std::filesystem;
using namespace eskin::testing;
using namespace std::chrono_literals;
using nlohmann::json;

namespace {

// A fresh directory per test, and a fresh runtime directory for the eskin
// processes it starts (XDG_RUNTIME_DIR, inherited), kept short: the
// control socket's path must fit a sockaddr_un.
struct TestDirs {
  fs::path dir, runtime;
  TestDirs() {
    static int n = 0;
    const std::string tag = std::to_string(getpid()) + "_" + std::to_string(++n);
    dir = fs::temp_directory_path() / ("eskin_ctl_" + tag);
    runtime = fs::temp_directory_path() / ("ekr" + tag);
    fs::remove_all(dir);
    fs::remove_all(runtime);
    fs::create_directories(dir);
    fs::create_directory(runtime);
    fs::permissions(runtime, fs::perms::owner_all);
    setenv("XDG_RUNTIME_DIR", runtime.c_str(), 1);
  }
  ~TestDirs() {
    fs::remove_all(dir);
    fs::remove_all(runtime);
  }
};

// The board: data packets (amplitudes and dense 3x3 taxels, alternately)
// paced by a 1 ms wait for commands, until finish(); commands answered as
// the FPGA does. Every frame it sends is kept (sent()) as the test's truth.
class StreamingBoard {
 public:
  explicit StreamingBoard(int master) : fd_(master) {
    // Non-blocking: with no reader on the pty (config done) a write would
    // wait forever; the board gives up a frame when told to finish.
    ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) | O_NONBLOCK);
    st_.output_mask = 0xF;
    thread_ = std::thread([this] { run(); });
  }
  ~StreamingBoard() {
    finish();
    if (thread_.joinable()) thread_.join();
  }
  void finish() { stop_ = true; }
  void join() {
    if (thread_.joinable()) thread_.join();
  }
  std::vector<Sent> sent() {
    std::lock_guard<std::mutex> lk(mu_);
    return sent_;
  }
  size_t commands_heard() const { return heard_; }

 private:
  void run() {
    eskin::link::LinkDecoder dec;
    uint32_t i = 0;
    while (!stop_) {
      dec.feed(read_some(fd_, 1));
      eskin::link::Packet c;
      while (dec.pop(c)) apply(c);
      const uint32_t t = 175 * i;
      if (i % 2 == 0) {
        send(enc_.amplitudes(t, {uint16_t(i), uint16_t(7 * i), 300, uint16_t(i ^ 0x5A5A), 5,
                                 uint16_t(65535 - i)}));
      } else {
        std::vector<uint16_t> v(9);
        for (size_t k = 0; k < v.size(); ++k) v[k] = uint16_t(i * 3 + k);
        send(enc_.taxels_dense(t, 3, 3, v));
      }
      samples_ = std::max(samples_, t + 1);
      ++i;
    }
  }
  void send(const std::vector<uint8_t>& frame) {
    eskin::link::LinkDecoder d;  // the frame's fields, read back from its bytes
    d.feed(frame);
    eskin::link::Packet p;
    d.pop(p);
    size_t off = 0;
    while (off < frame.size()) {
      const ssize_t w = ::write(fd_, frame.data() + off, frame.size() - off);
      if (w > 0) {
        off += size_t(w);
        continue;
      }
      if (stop_ || (w < 0 && errno != EAGAIN && errno != EINTR)) return;  // not sent
      pollfd q{fd_, POLLOUT, 0};
      ::poll(&q, 1, 10);
    }
    std::lock_guard<std::mutex> lk(mu_);
    sent_.push_back({p.type, p.seq, p.t, p.payload});
  }
  // Each STATUS its own sample count, so a verdict names one of them.
  void send_status() {
    st_.samples = ++samples_;
    send(enc_.status(samples_ - 1, st_));
  }
  void apply(const eskin::link::Packet& c) {
    using namespace eskin::link;
    ++heard_;
    if (c.type == kCmdSetOutputMask && (c.cmd_value & 0xE0)) {
      ++st_.cmd_rejected;
      st_.last_reject_type = c.type;
      st_.last_reject_reason = kRejectReservedBits;
      st_.last_reject_seq = c.seq;
      return send_status();
    }
    if (c.type == kCmdSetOutputMask) st_.output_mask = uint8_t(c.cmd_value);
    ++st_.cmd_accepted;
    if (c.type == kCmdRequestStatus) send_status();
  }

  int fd_;
  std::atomic<bool> stop_{false};
  std::atomic<size_t> heard_{0};
  std::mutex mu_;
  std::vector<Sent> sent_;
  eskin::link::LinkEncoder enc_;
  eskin::link::StatusBlock st_;
  uint32_t samples_ = 1;
  std::thread thread_;
};

struct CliRun {
  int rc;
  std::string out, err;
};

CliRun run(const fs::path& dir, const std::string& name, std::vector<std::string> args) {
  args.insert(args.begin(), ESKIN_BIN);
  Process p(args, (dir / (name + ".out")).string(), (dir / (name + ".err")).string());
  const int rc = p.wait_exit(30s);
  return {rc, p.out(), p.err()};
}

const auto has = [](const std::string& what) {
  return [what](const std::string& t) { return t.find(what) != std::string::npos; };
};

// A variable-length string dataset of an HDF5 file.
std::vector<std::string> read_strings(hid_t file, const std::string& name) {
  std::vector<std::string> out;
  const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  if (d < 0) return out;
  const hid_t sp = H5Dget_space(d);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(sp, &n, nullptr);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  std::vector<char*> raw(n, nullptr);
  if (n && H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data()) >= 0) {
    for (char* s : raw) out.push_back(s ? s : "");
    H5Dvlen_reclaim(type, sp, H5P_DEFAULT, raw.data());
  }
  H5Tclose(type);
  H5Sclose(sp);
  H5Dclose(d);
  return out;
}

// The final statistics line of eskin stream's stderr, as JSON.
json final_stats(const std::string& err) {
  const size_t at = err.rfind(" packets; link ");
  if (at == std::string::npos) return json();
  const size_t end = err.find('\n', at);
  return json::parse(err.substr(at + 15, end - at - 15), nullptr, false);
}

TEST(StreamControl, ConfigDuringARecordingGoesThroughTheStreamAndNothingIsLost) {
  TestDirs d;
  PtyPair pty;
  // The stream opens the board through a symlink (as the virtual board's
  // path is), config through the pty itself: one port.
  const fs::path link = d.dir / "board.tty";
  fs::create_symlink(pty.slave_path(), link);
  Process stream({ESKIN_BIN, "stream", "--port", link.string(), "--csv", (d.dir / "csv").string(),
                  "--hdf5", (d.dir / "run.h5").string(), "--flush-ms", "100"},
                 (d.dir / "stream.out").string(), (d.dir / "stream.err").string());
  ASSERT_TRUE(stream.wait_output(has("link open"), true, 10s)) << stream.err();
  StreamingBoard board(pty.master());
  ASSERT_TRUE(stream.wait_output([](const std::string& o) { return lines(o) >= 200; }, false, 10s))
      << stream.err();

  const CliRun ok = run(d.dir, "cfg1", {"config", "--port", pty.slave_path(), "set-mask", "0x7"});
  EXPECT_EQ(ok.rc, 0) << ok.out << ok.err;
  EXPECT_NE(ok.out.find("set-mask (type 0x84, seq 1): accepted"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("output mask 0x7"), std::string::npos) << ok.out;
  EXPECT_NE(ok.err.find("sent through eskin stream (pid " + std::to_string(stream.pid()) + ")"),
            std::string::npos)
      << ok.err;
  const CliRun bad = run(d.dir, "cfg2", {"config", "--port", pty.slave_path(), "set-mask", "0x30"});
  EXPECT_EQ(bad.rc, 3) << bad.out << bad.err;
  EXPECT_NE(bad.out.find("set-mask (type 0x84, seq 3): rejected: reserved mask bits set"),
            std::string::npos)
      << bad.out;
  EXPECT_NE(bad.out.find("rejected 1"), std::string::npos) << bad.out;
  // A bad argument is named as when config owns the port (exit 2).
  const CliRun wide = run(d.dir, "cfg3", {"config", "--port", pty.slave_path(), "set-mask", "300"});
  EXPECT_EQ(wide.rc, 2);
  EXPECT_NE(wide.err.find("set-mask mask '300': expected 0..255"), std::string::npos) << wide.err;

  // More data after the commands, then the board stops and the stream is
  // stopped once it has printed every row.
  const size_t after = board.sent().size() + 200;
  for (auto end = std::chrono::steady_clock::now() + 10s;
       board.sent().size() < after && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  board.finish();
  board.join();
  const std::vector<Sent> sent = board.sent();
  const auto want = expected_lines(sent);
  ASSERT_TRUE(stream.wait_output(
      [&](const std::string& o) { return lines(o) >= want.size() + 2; }, false, 20s))
      << "have " << lines(stream.out()) << " of " << want.size() + 2 << " lines\n"
      << stream.err();
  stream.signal(SIGTERM);
  ASSERT_EQ(stream.wait_exit(10s), 0) << stream.err();

  // Every packet the board sent, in order, and the two commands.
  std::vector<json> data, commands;
  for (const json& j : parse_ndjson(stream.out()))
    (j["type"] == "command" ? commands : data).push_back(j);
  ASSERT_EQ(data.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(data[i], want[i]) << "line " << i;
  const json st = final_stats(stream.err());
  ASSERT_TRUE(st.is_object()) << stream.err();
  EXPECT_EQ(st["frames_ok"], sent.size());
  EXPECT_EQ(st["framing_errors"], 0);
  EXPECT_EQ(st["crc_errors"], 0);
  EXPECT_EQ(st["seq_gaps"], 0);
  EXPECT_EQ(st["lost_packets"], 0);
  EXPECT_EQ(st["connects"], 1);

  ASSERT_EQ(commands.size(), 2u) << stream.out();
  EXPECT_EQ(commands[0]["command"], "set-mask");
  EXPECT_EQ(commands[0]["args"], json::array({"0x7"}));
  EXPECT_EQ(commands[0]["ack"], "accepted");
  EXPECT_EQ(commands[0]["cmd_type"], 0x84);
  EXPECT_EQ(commands[0]["seq"], 1);
  EXPECT_EQ(commands[1]["args"], json::array({"0x30"}));
  EXPECT_EQ(commands[1]["ack"], "rejected");
  EXPECT_EQ(commands[1]["message"], "rejected: reserved mask bits set");
  EXPECT_EQ(commands[1]["seq"], 3);
  // Each verdict's samples is the STATUS that decided it, among the data.
  for (const json& c : commands) {
    size_t found = 0;
    for (const json& j : data) found += j["type"] == "status" && j["samples"] == c["samples"];
    EXPECT_EQ(found, 1u) << c;
  }
  EXPECT_NE(stream.err().find("command set-mask 0x7 (type 0x84, seq 1): accepted"),
            std::string::npos)
      << stream.err();
  EXPECT_NE(stream.err().find("command set-mask 0x30 (type 0x84, seq 3): rejected"),
            std::string::npos)
      << stream.err();

  // CSV: the commands table beside the data tables.
  const std::string cmds = slurp((d.dir / "csv" / "commands.csv").string());
  EXPECT_EQ(cmds.substr(0, cmds.find('\n')),
            "host_ms,samples,command,args,ack,message,cmd_type,seq");
  EXPECT_EQ(lines(cmds), 3u) << cmds;
  EXPECT_NE(cmds.find(",set-mask,0x7,accepted,accepted,132,1\n"), std::string::npos) << cmds;
  EXPECT_NE(cmds.find(",set-mask,0x30,rejected,rejected: reserved mask bits set,132,3\n"),
            std::string::npos)
      << cmds;
  size_t amps = 0;
  for (const json& j : want) amps += j["type"] == "amplitudes";
  EXPECT_EQ(lines(slurp((d.dir / "csv" / "amplitudes.csv").string())), amps + 1);

  // HDF5: every data row, and /commands.
  expect_hdf5_matches((d.dir / "run.h5").string(), want);
  const hid_t f = H5Fopen((d.dir / "run.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(read_strings(f, "/commands/command"), (std::vector<std::string>{"set-mask", "set-mask"}));
  EXPECT_EQ(read_strings(f, "/commands/args"), (std::vector<std::string>{"0x7", "0x30"}));
  EXPECT_EQ(read_strings(f, "/commands/ack"), (std::vector<std::string>{"accepted", "rejected"}));
  std::vector<hsize_t> dims;
  EXPECT_EQ(read_set(f, "/commands/seq", dims), (std::vector<int64_t>{1, 3}));
  EXPECT_EQ(read_set(f, "/commands/samples", dims),
            (std::vector<int64_t>{commands[0]["samples"].get<int64_t>(),
                                  commands[1]["samples"].get<int64_t>()}));
  H5Fclose(f);
}

TEST(StreamControl, ASecondOpenerOfAHeldPortIsToldWhoHoldsIt) {
  TestDirs d;
  PtyPair pty;
  const fs::path link = d.dir / "board.tty";
  fs::create_symlink(pty.slave_path(), link);
  Process first({ESKIN_BIN, "stream", "--port", link.string(), "--quiet"},
                (d.dir / "first.out").string(), (d.dir / "first.err").string());
  ASSERT_TRUE(first.wait_output(has("taking commands"), true, 10s)) << first.err();
  // The same port under its other name.
  const CliRun second =
      run(d.dir, "second", {"stream", "--port", pty.slave_path(), "--duration", "5"});
  EXPECT_EQ(second.rc, 6) << second.err;
  EXPECT_NE(second.err.find(pty.slave_path() + " is held by eskin stream (pid " +
                            std::to_string(first.pid()) + ", since "),
            std::string::npos)
      << second.err;
  EXPECT_NE(second.err.find("use eskin config, which goes through it"), std::string::npos)
      << second.err;
  EXPECT_EQ(second.err.find("link open"), std::string::npos) << "it opened the port: " << second.err;
  // Nobody answers on this pty: config through the stream gets no verdict.
  const CliRun cfg = run(d.dir, "cfg", {"config", "--port", link.string(), "--timeout-ms", "300",
                                        "status"});
  EXPECT_EQ(cfg.rc, 4) << cfg.out << cfg.err;
  EXPECT_NE(cfg.out.find("no STATUS packet from the board"), std::string::npos) << cfg.out;
  EXPECT_NE(cfg.err.find("sent through eskin stream"), std::string::npos) << cfg.err;
  first.signal(SIGTERM);
  EXPECT_EQ(first.wait_exit(10s), 0) << first.err();
  // The port is free again.
  const CliRun third = run(d.dir, "third", {"stream", "--port", pty.slave_path(), "--duration",
                                            "0.2", "--quiet"});
  EXPECT_EQ(third.rc, 0) << third.err;
}

// Without a stream, config opens the port itself as it always did.
TEST(StreamControl, ConfigWithoutAStreamOwnsThePortItself) {
  TestDirs d;
  PtyPair pty;
  StreamingBoard board(pty.master());
  const CliRun r = run(d.dir, "cfg", {"config", "--port", pty.slave_path(), "set-mask", "0x3"});
  EXPECT_EQ(r.rc, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("set-mask (type 0x84, seq 1): accepted"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("sent through"), std::string::npos) << r.err;
  EXPECT_GE(board.commands_heard(), 2u) << "REQUEST_STATUS, then the command";
}

// A stream that takes the request and closes without a reply (it died
// while applying it): config says so and exits 4, and sends the request
// once. Sent again, a command the stream did apply would be applied twice
// (the old config resent it until --timeout-ms ran out). The "stream" here
// is this test: it holds the port's lock as a stream that serves commands
// and listens on the port's socket.
TEST(StreamControl, ARequestWithoutAReplyIsNotSentAgain) {
  TestDirs d;
  PtyPair pty;
  const auto paths = eskin::stream::port_paths(pty.slave_path());
  eskin::stream::PortLock lock;
  ASSERT_TRUE(lock.try_acquire(paths, "eskin stream", true, nullptr));
  const int ls = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  ASSERT_LT(paths.socket.size(), sizeof a.sun_path);
  std::memcpy(a.sun_path, paths.socket.c_str(), paths.socket.size() + 1);
  ASSERT_EQ(::bind(ls, reinterpret_cast<sockaddr*>(&a), sizeof a), 0) << paths.socket;
  ASSERT_EQ(::listen(ls, 8), 0);
  std::atomic<bool> stop{false};
  std::atomic<int> requests{0};
  std::thread silent([&] {
    while (!stop) {
      pollfd p{ls, POLLIN, 0};
      if (::poll(&p, 1, 20) <= 0) continue;
      const int fd = ::accept(ls, nullptr, nullptr);
      if (fd < 0) continue;
      std::string line;
      char buf[512];
      for (ssize_t n; line.find('\n') == std::string::npos && (n = ::read(fd, buf, sizeof buf)) > 0;)
        line.append(buf, size_t(n));
      if (!line.empty()) ++requests;
      ::close(fd);  // no reply
    }
  });
  const CliRun r = run(d.dir, "cfg", {"config", "--port", pty.slave_path(), "--timeout-ms", "1000", "status"});
  stop = true;
  silent.join();
  ::close(ls);
  EXPECT_EQ(r.rc, 4) << r.out << r.err;
  EXPECT_NE(r.err.find("may have been applied"), std::string::npos) << r.err;
  EXPECT_EQ(requests, 1) << "the request was sent again";
}

// The runtime directory is private, the socket too, and it goes when the
// stream does.
TEST(StreamControl, RuntimeDirectoryAndSocketArePrivate) {
  TestDirs d;
  PtyPair pty;
  Process s({ESKIN_BIN, "stream", "--port", pty.slave_path(), "--quiet"},
            (d.dir / "s.out").string(), (d.dir / "s.err").string());
  ASSERT_TRUE(s.wait_output(has("taking commands"), true, 10s)) << s.err();
  const fs::path run_dir = d.runtime / "eskin";
  struct stat st {};
  ASSERT_EQ(::stat(run_dir.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0700u);
  std::vector<fs::path> socks;
  for (const auto& e : fs::directory_iterator(run_dir))
    if (e.path().extension() == ".sock") socks.push_back(e.path());
  ASSERT_EQ(socks.size(), 1u);
  ASSERT_EQ(::stat(socks[0].c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_NE(s.err().find(socks[0].string()), std::string::npos) << s.err();
  s.signal(SIGTERM);
  EXPECT_EQ(s.wait_exit(10s), 0) << s.err();
  EXPECT_FALSE(fs::exists(socks[0]));
}

// The server's request handling as the live view's form would call it, and
// over its socket as eskin config does.
TEST(ControlServer, RequestsAreCheckedAndAnsweredInOneLine) {
  TestDirs d;
  PtyPair pty;  // no board: nothing answers
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(pty.slave_path());
  eskin::stream::LinkStream stream(opt);
  stream.start();
  const auto paths = eskin::stream::port_paths(pty.slave_path());
  std::vector<eskin::stream::CommandOutcome> seen;
  std::mutex mu;
  eskin::stream::ControlServer server(stream, paths.socket,
                                      [&](const eskin::stream::CommandOutcome& o) {
                                        std::lock_guard<std::mutex> lk(mu);
                                        seen.push_back(o);
                                      });
  const auto ask = [&](const std::string& req) { return json::parse(server.handle(req)); };
  const json not_json = ask("set-mask 7");
  EXPECT_EQ(not_json["ok"], false);
  EXPECT_EQ(not_json["exit"], 2);
  EXPECT_NE(not_json["error"].get<std::string>().find("not JSON"), std::string::npos);
  const json unknown = ask(R"({"command":"set-volume","args":["3"]})");
  EXPECT_EQ(unknown["exit"], 2);
  EXPECT_NE(unknown["error"].get<std::string>().find("unknown command 'set-volume'"),
            std::string::npos);
  const json numbers = ask(R"({"command":"set-mask","args":[7]})");
  EXPECT_EQ(numbers["exit"], 2);
  EXPECT_NE(numbers["error"].get<std::string>().find("array of strings"), std::string::npos);
  const json range = ask(R"({"command":"set-mask","args":["300"]})");
  EXPECT_NE(range["error"].get<std::string>().find("expected 0..255"), std::string::npos);
  EXPECT_TRUE(seen.empty()) << "a bad request reached the board";

  const std::string line = eskin::stream::control_request(
      paths.socket, eskin::stream::request_json("status", {}, 200), 5s);
  const json r = json::parse(line);
  EXPECT_EQ(r["ok"], true);
  EXPECT_EQ(r["ack"], "no_verdict");
  EXPECT_EQ(r["exit"], 4);
  EXPECT_NE(r["message"].get<std::string>().find("no STATUS packet"), std::string::npos);
  EXPECT_TRUE(r["status"].is_null());
  const auto back = eskin::stream::reply_from_json(line);
  EXPECT_EQ(back.ack, eskin::stream::Ack::Pending);
  std::lock_guard<std::mutex> lk(mu);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].command, "status");
}

}  // namespace
