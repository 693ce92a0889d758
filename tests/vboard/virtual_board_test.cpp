// The SystemC virtual board as a host program sees it: eskin-vboard runs as
// its own process, its FPGA's UART is a real pseudo-terminal, and the test
// opens the pty like a serial port (termios, raw, a baud rate), reads the
// bytes, decodes them with host/link and writes commands to it.
#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "hls/dtmf_chain.h"
#include "eskin/dtmf_top_plan.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "sim/scene.h"
#include "sim/vboard/fpga_params.h"
#include "sim/vboard/vboard_process.h"
#include "sim/world_model.h"

namespace {

using eskin::link::Packet;
using eskin::vboard::VboardProcess;
const std::string kScene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";

// The serial port as a host program opens it: raw, 8N1, the given speed.
int open_serial(const std::string& path, speed_t speed) {
  const int fd = open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd < 0) return fd;
  termios t{};
  tcgetattr(fd, &t);
  cfmakeraw(&t);
  cfsetispeed(&t, speed);
  cfsetospeed(&t, speed);
  tcsetattr(fd, TCSANOW, &t);
  return fd;
}

// Reads the pty until the board is done and every byte it sent has arrived;
// `each` sees each packet as it is decoded (and may write commands).
struct Capture {
  std::vector<Packet> packets;
  eskin::link::DecoderStats stats;
  nlohmann::json done;
};
template <class F>
Capture capture(VboardProcess& vb, int fd, F each) {
  Capture c;
  eskin::link::LinkDecoder dec;
  dec.on_packet([&](const Packet& p) {
    c.packets.push_back(p);
    each(p);
  });
  uint64_t got = 0;
  uint8_t buf[4096];
  for (;;) {
    pollfd pf{fd, POLLIN, 0};
    poll(&pf, 1, 20);
    ssize_t n;
    while ((n = read(fd, buf, sizeof buf)) > 0) {
      got += uint64_t(n);
      dec.feed(buf, size_t(n));
    }
    if (vb.poll_done() && got >= vb.done().at("bytes_to_host").get<uint64_t>()) break;
  }
  c.stats = dec.stats();
  c.done = vb.done();
  return c;
}

// A scene file: the default scene's skin with one press of taxel (0, 0),
// `duration_s` long (>= 0.02 s).
std::string short_scene(double duration_s, const std::string& name) {
  std::ifstream in(kScene);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("duration_s: 0.6"), 15, "duration_s: " + std::to_string(duration_s));
  text.erase(text.find("stimuli:"));
  text += "stimuli:\n  - press: {taxel: [0, 0], pressure_kpa: 50, t_start_s: 0.005, ramp_s: 0.005, "
          "hold_s: 0.005, release_s: 0.005}\noutputs: [amplitudes, taxels, spikes]\n";
  const std::string path = testing::TempDir() + name + ".yaml";
  std::ofstream(path) << text;
  return path;
}

// The default scene's HLS chain, configured from the same derivation as
// the board's FPGA build (common/eskin/dtmf_top_plan.h), default mask (no
// periodic status: the chain has none).
using Sizes3 = eskin::hls::DtmfChainSizes<3, 3, 32>;
using Chain3 = eskin::hls::DtmfChain<Sizes3>;
struct Key {
  uint8_t type;
  uint32_t t;
  std::vector<uint8_t> payload;
  bool operator==(const Key& o) const { return type == o.type && t == o.t && payload == o.payload; }
};

std::vector<Key> chain_packets(const eskin::sim::Scene& sc, size_t n) {
  const auto build = eskin::vboard::fpga_build_for(sc);
  auto chain = std::make_unique<Chain3>(eskin::hls::chain_config<Sizes3>(build.plan));
  EXPECT_TRUE(chain->ok());
  eskin::sim::WorldModel world(sc);
  std::vector<int> codes = world.all_codes();
  std::vector<Key> out;
  auto pk = std::make_unique<Chain3::Packet[]>(Chain3::kMaxPackets);
  Chain3::Packet(&pn)[Chain3::kMaxPackets] =
      *reinterpret_cast<Chain3::Packet(*)[Chain3::kMaxPackets]>(pk.get());
  for (size_t i = 0; i < n && i < codes.size(); ++i) {
    const int np = chain->push(uint16_t(codes[i] << build.adc_shift()), uint32_t(i), pn);
    for (int j = 0; j < np; ++j)
      out.push_back({pn[j].type, pn[j].t, {pn[j].payload, pn[j].payload + pn[j].len}});
  }
  return out;
}

std::vector<Key> of_type(const std::vector<Key>& all, uint8_t type, uint32_t limit) {
  std::vector<Key> r;
  for (const Key& k : all)
    if (k.type == type && (type == eskin::link::kSpikes ? k.t + 35 : k.t) < limit) r.push_back(k);
  return r;
}

// Bound: exact equality, packet for packet. The virtual board runs the same
// RTL on the same samples as tests/rtl/dtmf_top_test.cpp, whose packets
// equal hls/dtmf_chain.h's bit for bit; the pty and the USB-serial bridge
// at the FPGA's own baud rate only move bytes, so any difference in type,
// t or a payload byte is a bug of the board. The whole 0.6 s scene
// (21000 samples, every press) is compared.
TEST(VirtualBoard, DefaultSceneThroughThePtyMatchesTheChain) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {kScene});
  EXPECT_EQ(vb.ready().at("params"), "default");
  const int fd = open_serial(vb.pty(), B3000000);
  ASSERT_GE(fd, 0) << vb.pty();
  const Capture c = capture(vb, fd, [](const Packet&) {});
  close(fd);
  EXPECT_EQ(vb.wait(), 0);

  const auto scene = eskin::sim::load_scene(kScene);
  const size_t n = scene.skin.adc.rate_hz * scene.duration_s;
  ASSERT_EQ(n, 21000u);
  EXPECT_EQ(c.done.at("adc_violations"), 0) << c.done.at("adc_first_violation");
  EXPECT_EQ(c.done.at("usb_framing_errors"), 0);
  EXPECT_EQ(c.done.at("baud_mismatches"), 0);
  EXPECT_EQ(c.stats.crc_errors + c.stats.framing_errors + c.stats.payload_errors, 0u);
  EXPECT_EQ(c.stats.lost_packets, 0u);
  EXPECT_GE(c.done.at("samples").get<uint64_t>(), n);

  const auto want = chain_packets(scene, n);
  std::vector<Key> got;
  for (const Packet& p : c.packets) got.push_back({p.type, p.t, p.payload});
  for (uint8_t type : {eskin::link::kAmplitudes, eskin::link::kTaxelsDense, eskin::link::kSpikes}) {
    const auto w = of_type(want, type, uint32_t(n) - 35), g = of_type(got, type, uint32_t(n) - 35);
    EXPECT_GE(w.size(), 10u) << "type " << int(type);
    ASSERT_EQ(g.size(), w.size()) << "type " << int(type);
    for (size_t i = 0; i < w.size(); ++i) ASSERT_EQ(g[i], w[i]) << "type " << int(type) << " #" << i;
  }
  // Every frame's end reached the host at a time the board logged.
  EXPECT_EQ(c.done.at("frame_end_ns").size(), c.stats.frames_ok);
  const double sim_s = c.done.at("sim_s"), cpu_s = c.done.at("cpu_s");
  std::printf("virtual board: %.3f s simulated in %.3f s CPU (%.3f s wall): %.2f simulated s per "
              "CPU s, %.2f M FPGA cycles per CPU s\n",
              sim_s, cpu_s, c.done.at("wall_s").get<double>(), sim_s / cpu_s,
              c.done.at("cycles").get<double>() / cpu_s / 1e6);
}

// A reader that closes the port mid-scene does not end the board, as
// closing a USB serial adapter does not end a board: the board runs its
// whole scene (every sample it was given), drops the bytes nobody reads,
// counts the close, then hangs up (nobody reads) and exits 0.
TEST(VirtualBoard, AReaderClosingMidSceneDoesNotEndTheBoard) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {short_scene(0.1, "vboard_close")});
  const int fd = open_serial(vb.pty(), B3000000);
  ASSERT_GE(fd, 0) << vb.pty();
  eskin::link::LinkDecoder dec;
  size_t packets = 0;
  dec.on_packet([&](const Packet&) { ++packets; });
  uint8_t buf[4096];
  for (auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
       packets < 20 && std::chrono::steady_clock::now() < end;) {
    pollfd pf{fd, POLLIN, 0};
    poll(&pf, 1, 20);
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n > 0) dec.feed(buf, size_t(n));
  }
  ASSERT_GE(packets, 20u);
  close(fd);
  EXPECT_EQ(vb.wait(), 0);
  const nlohmann::json& d = vb.done();
  ASSERT_FALSE(d.is_null()) << "no done line";
  EXPECT_EQ(d.at("samples"), vb.ready().at("samples")) << "the board stopped before its scene's end";
  EXPECT_EQ(d.at("reader_closes"), 1);
  EXPECT_GT(d.at("bytes_dropped").get<uint64_t>(), 0u);
  EXPECT_LT(d.at("bytes_dropped").get<uint64_t>(), d.at("bytes_to_host").get<uint64_t>());
}

// Commands written to the pty reach the FPGA's uart_rx as serial bits:
// SET_OUTPUT_MASK(spikes | status) then REQUEST_STATUS, sent once the
// first status packet (step 0) is in. The status answer reports both
// commands accepted and the new mask, and no amplitude or taxel packet
// created after the mask changed arrives.
TEST(VirtualBoard, CommandsThroughThePtyReachTheFpga) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {short_scene(0.08, "vboard_cmd")});
  const int fd = open_serial(vb.pty(), B3000000);
  ASSERT_GE(fd, 0);
  eskin::link::LinkEncoder enc;
  bool sent = false;
  uint32_t sent_after_t = 0;
  const Capture c = capture(vb, fd, [&](const Packet& p) {
    if (sent || p.type != eskin::link::kAmplitudes || p.t < 350) return;
    std::vector<uint8_t> cmd = enc.set_output_mask(eskin::hls::kMaskSpikes | eskin::hls::kMaskStatus);
    const auto req = enc.request_status();
    cmd.insert(cmd.end(), req.begin(), req.end());
    ASSERT_EQ(write(fd, cmd.data(), cmd.size()), ssize_t(cmd.size()));
    sent = true;
    sent_after_t = p.t;
  });
  close(fd);
  EXPECT_EQ(vb.wait(), 0);
  ASSERT_TRUE(sent);
  EXPECT_GT(c.done.at("bytes_to_fpga").get<uint64_t>(), 0u);
  const Packet* answer = nullptr;
  for (const Packet& p : c.packets)
    if (p.type == eskin::link::kStatus && p.status.cmd_accepted > 0) {
      answer = &p;
      break;
    }
  ASSERT_NE(answer, nullptr) << "no status packet acknowledging the commands";
  EXPECT_EQ(answer->status.cmd_accepted, 2);
  EXPECT_EQ(answer->status.cmd_crc_errors + answer->status.cmd_frame_errors, 0);
  EXPECT_EQ(answer->status.uart_rx_errors, 0);
  EXPECT_EQ(answer->status.output_mask, eskin::hls::kMaskSpikes | eskin::hls::kMaskStatus);
  EXPECT_GT(answer->status.samples, sent_after_t);
  int data_after = 0;
  for (const Packet& p : c.packets)
    if ((p.type == eskin::link::kAmplitudes || p.type == eskin::link::kTaxelsDense) &&
        p.t > answer->status.samples)
      ++data_after;
  EXPECT_EQ(data_after, 0);
}

// A reader at the wrong baud rate: the board reports the mismatch and the
// bytes arrive garbled (the bridge samples the FPGA's 3 Mbaud line at
// 115200 baud), so the decoder finds no good frame.
TEST(VirtualBoard, ReaderAtTheWrongBaudRateIsReported) {
  VboardProcess vb(ESKIN_VBOARD_BIN, {short_scene(0.02, "vboard_baud")});
  const int fd = open_serial(vb.pty(), B115200);
  ASSERT_GE(fd, 0);
  const Capture c = capture(vb, fd, [](const Packet&) {});
  close(fd);
  EXPECT_EQ(vb.wait(), 0);
  EXPECT_EQ(c.done.at("reader_baud"), 115200);
  EXPECT_EQ(c.done.at("baud_mismatches"), 1);
  EXPECT_EQ(c.stats.frames_ok, 0u);
  EXPECT_GT(c.done.at("usb_framing_errors").get<uint64_t>(), 0u);
}

// `--hold-for-host-bytes N` (what `eskin simulate` uses for its start-up
// commands): the host opens the port and watches it for 1.5 s of wall
// clock, far longer than this 20 ms scene takes to simulate, asserting that
// not one byte comes (a board that ran would have sent its packets), before
// it sends SET_OUTPUT_MASK(status only). Held, the board has not moved: the
// mask acts before the first frame, so not one amplitude, taxel or spike
// packet arrives (the default mask sends all three), and periodic status does.
TEST(VirtualBoard, HeldBoardStartsWithTheHostsCommands) {
  eskin::link::LinkEncoder enc;
  const std::vector<uint8_t> cmd = enc.set_output_mask(eskin::hls::kMaskStatus);
  VboardProcess vb(ESKIN_VBOARD_BIN, {short_scene(0.02, "vboard_hold"), "--hold-for-host-bytes",
                                      std::to_string(cmd.size())});
  const int fd = open_serial(vb.pty(), B3000000);
  ASSERT_GE(fd, 0);
  pollfd quiet{fd, POLLIN, 0};
  ASSERT_EQ(poll(&quiet, 1, 1500), 0) << "the held board sent bytes before the host's";
  ASSERT_EQ(write(fd, cmd.data(), cmd.size()), ssize_t(cmd.size()));
  const Capture c = capture(vb, fd, [](const Packet&) {});
  close(fd);
  EXPECT_EQ(vb.wait(), 0);
  EXPECT_EQ(c.done.at("bytes_to_fpga").get<uint64_t>(), cmd.size());
  int status = 0, data = 0;
  for (const Packet& p : c.packets) {
    status += p.type == eskin::link::kStatus;
    data += p.type == eskin::link::kAmplitudes || p.type == eskin::link::kTaxelsDense ||
            p.type == eskin::link::kSpikes;
  }
  EXPECT_GT(status, 0);
  EXPECT_EQ(data, 0);
}

// A host that closes the port before it has sent the bytes the board holds
// for: the board never starts and exits with an error (status 2, no done
// line), instead of running without the host's configuration. The host
// closes right after its 3 bytes, with no wait: what the pty's reader set
// (its baud rate) and sent stays for the board to find after the close, so
// the board refuses because the host closed early, which its message
// (captured from its stderr) says, not because its reader timeout ran out.
TEST(VirtualBoard, HeldBoardRefusesToStartWithoutTheHostsBytes) {
  const std::string err_path = testing::TempDir() + "vboard_hold_short.err";
  const int saved_err = dup(STDERR_FILENO);
  ASSERT_GE(saved_err, 0);
  const int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(err_fd, 0) << err_path;
  dup2(err_fd, STDERR_FILENO);  // the board inherits it
  close(err_fd);
  std::unique_ptr<VboardProcess> vb;
  try {
    vb = std::make_unique<VboardProcess>(
        ESKIN_VBOARD_BIN,
        std::vector<std::string>{short_scene(0.02, "vboard_hold_short"), "--hold-for-host-bytes",
                                 "100"});
  } catch (...) {
    dup2(saved_err, STDERR_FILENO);
    close(saved_err);
    throw;
  }
  dup2(saved_err, STDERR_FILENO);
  close(saved_err);
  const int fd = open_serial(vb->pty(), B3000000);
  ASSERT_GE(fd, 0);
  const uint8_t three[3] = {0, 1, 2};
  ASSERT_EQ(write(fd, three, 3), 3);
  close(fd);
  EXPECT_EQ(vb->wait(), 2);
  EXPECT_TRUE(vb->done().is_null());
  std::ifstream in(err_path);
  const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(err.find("of the 100 bytes the board was told to wait for (--hold-for-host-bytes) "
                     "before it closed " + vb->pty()),
            std::string::npos)
      << err;
}

}  // namespace
