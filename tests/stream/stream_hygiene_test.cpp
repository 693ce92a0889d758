// eskin stream's manners: a stdout whose reader leaves (`| head`) ends the
// run with every packet read in the recordings and the statistics printed;
// an earlier recording is not overwritten without --force; the live view,
// which takes commands, stays on loopback unless --live-public says so.
// The real binary, a real pty, a real pipe, real sockets.
#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <hdf5.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "tests/stream/frames.h"
#include "tests/stream/process.h"
#include "tests/stream/pty_pair.h"
#include "tests/stream/recording.h"

namespace fs = std::filesystem;
using namespace eskin::testing;
using namespace std::chrono_literals;
using nlohmann::json;

namespace {

fs::path tmpdir() {
  const fs::path d = fs::temp_directory_path() /
                     ("eskin_hygiene_" + std::to_string(getpid()) + "_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

struct CliRun {
  int rc;
  std::string out, err;
};

CliRun run(const fs::path& dir, std::vector<std::string> args) {
  args.insert(args.begin(), ESKIN_BIN);
  Process p(args, (dir / "out").string(), (dir / "err").string());
  const int rc = p.wait_exit(30s);
  return {rc, p.out(), p.err()};
}

// eskin with stdout into a pipe, SIGPIPE at its default (as a shell
// starts `eskin stream | head`), stderr to a file.
struct PipedProcess {
  pid_t pid = -1;
  int read_fd = -1;
  PipedProcess(const std::vector<std::string>& argv, const std::string& err) {
    int p[2];
    if (::pipe2(p, O_CLOEXEC) != 0) return;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, p[1], 1);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawnattr_t at;
    posix_spawnattr_init(&at);
    sigset_t def;
    sigemptyset(&def);
    sigaddset(&def, SIGPIPE);
    posix_spawnattr_setsigdefault(&at, &def);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGDEF);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (posix_spawn(&pid, args[0], &fa, &at, args.data(), environ) != 0) pid = -1;
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    ::close(p[1]);
    read_fd = p[0];
  }
  ~PipedProcess() {
    if (read_fd >= 0) ::close(read_fd);
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  int wait_exit(std::chrono::milliseconds timeout) {
    for (auto end = std::chrono::steady_clock::now() + timeout;
         std::chrono::steady_clock::now() < end;) {
      int st = 0;
      if (::waitpid(pid, &st, WNOHANG) == pid) {
        pid = -1;
        return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      }
      std::this_thread::sleep_for(5ms);
    }
    return -1;
  }
};

json final_stats(const std::string& err, uint64_t& packets) {
  static const std::regex re(R"(eskin stream: (\d+) packets; link (\{[^\n]*\}))");
  std::smatch m;
  if (!std::regex_search(err, m, re)) return json();
  packets = std::stoull(m[1]);
  return json::parse(m[2].str(), nullptr, false);
}

// `eskin stream | head`: the reader takes a few lines and leaves while the
// board keeps sending. The run ends on the broken pipe (exit 0, the stats
// on stderr), and the HDF5 and CSV recordings hold every packet it read,
// value for value.
TEST(StreamHygiene, ClosedStdoutEndsTheRunWithEveryPacketRecorded) {
  const fs::path dir = tmpdir();
  std::vector<Sent> sent;
  const auto frames = random_frames(6000, 11, sent);
  PtyPair pty;
  PipedProcess p({ESKIN_BIN, "stream", "--port", pty.slave_path(), "--hdf5",
                  (dir / "run.h5").string(), "--csv", (dir / "csv").string(), "--flush-ms",
                  "60000"},
                 (dir / "err").string());
  ASSERT_GT(p.pid, 0);
  bool open = false;
  for (auto end = std::chrono::steady_clock::now() + 10s;
       !(open = slurp((dir / "err").string()).find("link open") != std::string::npos) &&
       std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(10ms);
  ASSERT_TRUE(open) << slurp((dir / "err").string());
  // The board writes on its own thread: eskin stops reading it while its
  // stdout is full, and the board stops when told.
  std::atomic<bool> stop{false};
  ::fcntl(pty.master(), F_SETFL, ::fcntl(pty.master(), F_GETFL) | O_NONBLOCK);
  std::thread board([&] {
    for (const auto& f : frames) {
      size_t off = 0;
      while (off < f.size() && !stop) {
        const ssize_t w = ::write(pty.master(), f.data() + off, f.size() - off);
        if (w > 0) off += size_t(w);
        else if (w < 0 && errno != EAGAIN && errno != EINTR) return;
        else {
          pollfd q{pty.master(), POLLOUT, 0};
          ::poll(&q, 1, 20);
        }
      }
      if (stop) return;
    }
  });
  // head -n 20.
  std::string head;
  char buf[4096];
  for (auto end = std::chrono::steady_clock::now() + 20s;
       count_of(head, "\n") < 20 && std::chrono::steady_clock::now() < end;) {
    pollfd q{p.read_fd, POLLIN, 0};
    if (::poll(&q, 1, 100) <= 0) continue;
    const ssize_t n = ::read(p.read_fd, buf, sizeof buf);
    if (n <= 0) break;
    head.append(buf, size_t(n));
  }
  ASSERT_GE(count_of(head, "\n"), 20u);
  ::close(p.read_fd);
  p.read_fd = -1;
  const int rc = p.wait_exit(30s);
  stop = true;
  board.join();
  const std::string err = slurp((dir / "err").string());
  ASSERT_EQ(rc, 0) << "exit " << rc << "\n" << err;
  EXPECT_NE(err.find("stdout closed by its reader"), std::string::npos) << err;
  uint64_t packets = 0;
  const json st = final_stats(err, packets);
  ASSERT_TRUE(st.is_object()) << err;
  // Every decoded packet recorded: the link's count is the recorders'.
  EXPECT_EQ(st["frames_ok"], packets);
  EXPECT_EQ(st["framing_errors"], 0);
  ASSERT_GT(packets, 20u);
  ASSERT_LE(packets, sent.size());
  const std::vector<Sent> read(sent.begin(), sent.begin() + std::ptrdiff_t(packets));
  const auto want = expected_lines(read);
  // What head saw is the start of it.
  const auto seen = parse_ndjson(head.substr(0, head.rfind('\n') + 1));
  for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], want[i]) << "line " << i;
  SCOPED_TRACE(err);
  expect_hdf5_matches((dir / "run.h5").string(), want);
  size_t amps = 0, spikes = 0;
  for (const json& j : want) amps += j["type"] == "amplitudes", spikes += j["type"] == "spikes";
  EXPECT_EQ(lines(slurp((dir / "csv" / "amplitudes.csv").string())), amps + 1);
  EXPECT_EQ(lines(slurp((dir / "csv" / "spikes.csv").string())), spikes + 1);
  fs::remove_all(dir);
}

TEST(StreamHygiene, AnEarlierRecordingIsNotOverwrittenWithoutForce) {
  const fs::path dir = tmpdir();
  PtyPair pty;
  const std::string h5 = (dir / "run.h5").string();
  { std::ofstream(h5) << "an earlier recording"; }
  const CliRun no = run(dir, {"stream", "--port", pty.slave_path(), "--hdf5", h5, "--duration",
                              "0.2", "--quiet"});
  EXPECT_EQ(no.rc, 2) << no.err;
  EXPECT_NE(no.err.find("--hdf5 " + h5 + ": the file exists"), std::string::npos) << no.err;
  EXPECT_NE(no.err.find("--force"), std::string::npos) << no.err;
  EXPECT_EQ(slurp(h5), "an earlier recording");
  const CliRun yes = run(dir, {"stream", "--port", pty.slave_path(), "--hdf5", h5, "--duration",
                               "0.2", "--quiet", "--force"});
  EXPECT_EQ(yes.rc, 0) << yes.err;
  EXPECT_GT(H5Fis_hdf5(h5.c_str()), 0);

  const fs::path csv = dir / "csv";
  fs::create_directories(csv);
  { std::ofstream(csv / "notes.txt") << "mine"; }
  const CliRun other = run(dir, {"stream", "--port", pty.slave_path(), "--csv", csv.string(),
                                 "--duration", "0.2", "--quiet"});
  EXPECT_EQ(other.rc, 0) << "a directory without tables is fine: " << other.err;
  { std::ofstream(csv / "amplitudes.csv") << "seq,t\n1,2\n"; }
  const CliRun csv_no = run(dir, {"stream", "--port", pty.slave_path(), "--csv", csv.string(),
                                  "--duration", "0.2", "--quiet"});
  EXPECT_EQ(csv_no.rc, 2) << csv_no.err;
  EXPECT_NE(csv_no.err.find((csv / "amplitudes.csv").string()), std::string::npos) << csv_no.err;
  EXPECT_NE(csv_no.err.find("--force"), std::string::npos) << csv_no.err;
  EXPECT_EQ(slurp((csv / "amplitudes.csv").string()), "seq,t\n1,2\n");
  const CliRun csv_yes = run(dir, {"stream", "--port", pty.slave_path(), "--csv", csv.string(),
                                   "--duration", "0.2", "--quiet", "--force"});
  EXPECT_EQ(csv_yes.rc, 0) << csv_yes.err;
  fs::remove_all(dir);
}

// Connects to 127.0.0.1:port (true when something listens there).
bool loopback_listens(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

TEST(StreamHygiene, LiveViewStaysOnLoopbackUnlessPublic) {
  const fs::path dir = tmpdir();
  PtyPair pty;
  const CliRun open = run(dir, {"stream", "--port", pty.slave_path(), "--live", "0.0.0.0:0",
                                "--duration", "0.2", "--quiet"});
  EXPECT_EQ(open.rc, 2) << open.err;
  EXPECT_NE(open.err.find("--live-public"), std::string::npos) << open.err;
  EXPECT_EQ(open.err.find("live view at"), std::string::npos) << open.err;

  const auto served = [&](std::vector<std::string> live, const std::string& url_prefix,
                          bool warned) {
    std::vector<std::string> args = {ESKIN_BIN, "stream", "--port", pty.slave_path(), "--quiet"};
    args.insert(args.end(), live.begin(), live.end());
    Process p(args, (dir / "out").string(), (dir / "err").string());
    // Waits for the whole line: stderr may arrive in pieces.
    static const std::regex re(R"(live view at (http://([^/]*):(\d+)/)\n)");
    ASSERT_TRUE(p.wait_output([](const std::string& e) { return std::regex_search(e, re); },
                              true, 10s))
        << p.err();
    std::smatch m;
    const std::string err = p.err();
    ASSERT_TRUE(std::regex_search(err, m, re)) << err;
    EXPECT_EQ(m[1].str().substr(0, url_prefix.size()), url_prefix) << err;
    const int port = std::stoi(m[3]);
    EXPECT_GT(port, 0) << "the port it got, not 0";
    EXPECT_TRUE(loopback_listens(port)) << err;
    EXPECT_EQ(err.find("warning: the live view is served on") != std::string::npos, warned) << err;
    p.signal(SIGTERM);
    EXPECT_EQ(p.wait_exit(10s), 0) << p.err();
  };
  served({"--live", ":0"}, "http://127.0.0.1:", false);
  served({"--live", "0"}, "http://127.0.0.1:", false);
  served({"--live", "0.0.0.0:0", "--live-public"}, "http://0.0.0.0:", true);
  fs::remove_all(dir);
}

}  // namespace
