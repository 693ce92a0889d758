// Board faults on the virtual board (sim/vboard/board_faults.h,
// docs/vboard.md "Board faults"): the real eskin-vboard (the Verilated
// dtmf_top; the mixed top for SDA held low) run with --fault, its pty read
// through host/stream as eskin simulate reads it, against the same scene
// without the fault. The default scene: 3x3 skin, 35 kS/s, a DFT window
// of N = 32 samples, a frame (AMPLITUDES, TAXELS, SPIKES) every STEP = 35
// samples; sample n is at n / 35 kHz of scene time.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <functional>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "eskin/process.h"
#include "host/link/link_encoder.h"
#include "host/stream/board_link.h"
#include "sim/scene.h"
#include "sim/vboard/board_faults.h"
#include "sim/vboard/mixed_build.h"
#include "sim/vboard/vboard_build.h"
#include "sim/vboard/vboard_process.h"
#include "fault_harness.h"

namespace {

using fault_harness::exit_of;
using fault_harness::slurp;

using eskin::link::Packet;

const std::string kScene = ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml";
constexpr uint32_t kN = 32, kStep = 35;
constexpr double kFs = 35000;

struct FaultRun {
  eskin::stream::BoardRun run;
  nlohmann::json faults;  // the done line's board_faults
  int exit = -1;
  std::vector<const Packet*> of(uint8_t type) const {
    std::vector<const Packet*> v;
    for (const Packet& p : run.rx)
      if (p.type == type) v.push_back(&p);
    return v;
  }
};

// `sends`: bytes the host sends once a packet of the skin with t >= its
// time arrives, in order, from a thread of its own (the reader must go on
// reading meanwhile).
FaultRun run_board(const std::vector<std::string>& extra,
                   const std::vector<std::vector<uint8_t>>& commands = {},
                   const std::string& bin = ESKIN_VBOARD_BIN, const std::string& scene = kScene,
                   const std::vector<std::pair<uint32_t, std::vector<uint8_t>>>& sends = {}) {
  FaultRun r;
  eskin::vboard::VboardProcess board(bin, eskin::stream::board_args(scene, "", commands, extra));
  eskin::stream::LinkStream port(eskin::stream::board_link_options(board.pty(), 3000000));
  std::vector<Packet> rx;
  std::atomic<uint32_t> skin_t{0};
  port.on_packet([&](const Packet& p) {
    rx.push_back(p);
    if (p.type < 0x10) skin_t = p.t;
  });
  port.start();
  for (const auto& c : commands) port.send(c);
  std::thread side;
  if (!sends.empty()) {
    side = std::thread([&] {
      for (const auto& [t, bytes] : sends) {
        while (skin_t < t && port.ended() == eskin::stream::StreamEnd::Running)
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        port.send(bytes);
      }
    });
  }
  eskin::stream::read_until_board_done(board, port, [] {});
  if (side.joinable()) side.join();
  r.run = eskin::stream::finish_board_run(board, port, std::move(rx));
  r.exit = board.wait();
  r.faults = r.run.done.at("board_faults");
  return r;
}

uint64_t link_errors(const FaultRun& r) {
  return r.run.link.crc_errors + r.run.link.framing_errors + r.run.link.payload_errors;
}

// ---------------------------------------------------------------- resets

// The reset button pressed for 10 us while the FPGA is sending a frame at
// 100 ms. The cut frame has no delimiter, so the restarted board's first
// frame ends it: one error frame holds both. What must hold:
//  * every packet delivered before the reset is the fault-free run's;
//  * the host counts one restart, one error frame, and as lost only the
//    restarted board's first packet (seq 0, in that frame);
//  * the board resumes by itself: its first frame after the restart has
//    t <= N + STEP (the window filled, then the next frame boundary) and
//    every frame after it follows STEP samples apart, none missing.
TEST(BoardFaults, AResetInAFrameCostsThatFrameAndTheBoardResumesWithinAWindow) {
  const FaultRun ref = run_board({});
  ASSERT_EQ(ref.exit, 0);
  ASSERT_EQ(link_errors(ref), 0u);
  const FaultRun r = run_board({"--fault", "reset-in-frame@100"});
  ASSERT_EQ(r.exit, 0);
  ASSERT_EQ(r.faults.size(), 1u);
  ASSERT_TRUE(r.faults[0].at("begun").get<bool>()) << r.faults.dump();
  EXPECT_GE(r.faults[0].at("begin_ns").get<double>(), 100e6);
  EXPECT_LT(r.faults[0].at("begin_ns").get<double>(), 101e6) << "frames go out every ms";

  size_t k = 0;  // delivered before the restart, equal to the reference's
  while (k < r.run.rx.size() && k < ref.run.rx.size() &&
         r.run.rx[k].t >= (k ? r.run.rx[k - 1].t : 0) &&
         r.run.rx[k].payload == ref.run.rx[k].payload && r.run.rx[k].seq == ref.run.rx[k].seq)
    ++k;
  ASSERT_GT(k, 0u) << "the first packet already differs from the fault-free run";
  ASSERT_LT(k, r.run.rx.size());
  EXPECT_LT(r.run.rx[k].t, r.run.rx[k - 1].t) << "the first difference is the restart";
  EXPECT_GT(r.run.rx[k - 1].t, 3400u);  // 100 ms = sample 3500: nothing lost before
  EXPECT_EQ(r.run.link.restarts, 1u);
  EXPECT_EQ(link_errors(r), 1u);
  EXPECT_EQ(r.run.link.lost_packets, uint64_t(r.run.rx[k].seq));
  EXPECT_LE(r.run.rx[k].seq, 1) << "only the restarted board's first packet shares the cut frame";
  EXPECT_LE(r.run.rx[k].t, kN + kStep);
  uint32_t last = 0;
  size_t frames = 0;
  for (size_t i = k; i < r.run.rx.size(); ++i) {
    const Packet& p = r.run.rx[i];
    if (p.type != eskin::link::kAmplitudes) continue;
    if (frames++ > 0) {
      EXPECT_EQ(p.t - last, kStep) << "a frame missing after the restart";
    }
    last = p.t;
  }
  EXPECT_GT(frames, 400u);  // 0.5 s of scene left at a frame per ms
}

// 200 commands (a SET_THRESHOLD for a taxel id that does not exist, each
// rejected with a STATUS reply naming its seq; 76 characters apart, one
// every 253.3 us on the wire from time 0, as in LineBoard) with the reset
// pressed for 10 us in the body of the one on the wire at 5 ms (command
// 19's body ends at 4.85 ms, so the cut one is command 20, give or take
// the bridge's start). What must hold: no command is judged twice or out
// of order (each reply's seq above the last); the unanswered commands are
// one run ending at the cut command: it is never applied, and those just
// before it had their replies in the FPGA's output when the reset came,
// at most as many as its 512-byte FIFO holds 39-byte STATUS frames (13);
// every command after it is judged; the restarted command decoder counts
// the cut command's tail as one damaged frame; the host sees one restart.
TEST(BoardFaults, AResetInACommandNeverAppliesItAndEveryLaterCommandIsJudgedOnce) {
  const int n = 200;
  const std::vector<std::vector<uint8_t>> cmds = fault_harness::rejected_commands(n);
  const FaultRun r = run_board({"--fault", "reset-in-command@5"}, cmds);
  ASSERT_EQ(r.exit, 0);
  ASSERT_TRUE(r.faults[0].at("begun").get<bool>()) << r.faults.dump();
  const int cut = int(r.faults[0].at("begin_ns").get<double>() / 253333.3);
  EXPECT_EQ(r.run.link.restarts, 1u);
  const auto status = r.of(eskin::link::kStatus);
  ASSERT_FALSE(status.empty());
  int prev = -1;
  std::vector<int> unanswered;
  bool after = false;
  int first_after_errors = -1;
  for (size_t i = 0; i < status.size(); ++i) {
    const eskin::link::StatusBlock& s = status[i]->status;
    if (i && status[i]->t < status[i - 1]->t) after = true;
    if (s.cmd_rejected == 0) continue;  // a periodic STATUS before any rejection
    EXPECT_GE(int(s.last_reject_seq), prev) << "a command judged out of order";
    if (int(s.last_reject_seq) == prev) continue;  // a periodic STATUS repeats the last verdict
    for (int q = prev + 1; q < int(s.last_reject_seq); ++q) unanswered.push_back(q);
    if (after && first_after_errors < 0)
      first_after_errors = int(s.cmd_crc_errors + s.cmd_frame_errors);
    prev = s.last_reject_seq;
  }
  EXPECT_EQ(prev, n - 1) << "the last command was judged";
  ASSERT_FALSE(unanswered.empty()) << "the cut command was applied";
  EXPECT_LE(unanswered.size(), 1u + 512 / 39);
  EXPECT_EQ(unanswered.back() - unanswered.front() + 1, int(unanswered.size())) << "not one run";
  EXPECT_NEAR(unanswered.back(), cut, 1) << "the run does not end at the command the reset cut";
  EXPECT_EQ(first_after_errors, 1) << "the cut command's tail, counted by the restarted decoder";
  std::printf("reset at command %d: commands %d..%d unanswered\n", cut, unanswered.front(),
              unanswered.back());
}

// ---------------------------------------------------------------- the ADC

// AMPLITUDES by t, and the frames (by t) whose window [t - N + 1, t]
// holds a sample of [n0, n1).
std::map<uint32_t, std::vector<uint16_t>> amplitudes(const FaultRun& r) {
  std::map<uint32_t, std::vector<uint16_t>> m;
  for (const Packet* p : r.of(eskin::link::kAmplitudes)) m[p->t] = p->amplitudes;
  return m;
}

struct Window {
  size_t clean = 0;                  // frames whose window misses every fault
  std::vector<size_t> inside;        // per fault: frames whose window is all inside it
  std::vector<size_t> inside_differ; // ... that differ from the reference
};

// The sliding DFT sums its window exactly (dtmf_top: ACC_W bits, "window
// sums never wrap"), so a fault is forgotten exactly once it leaves the
// window: every frame whose window [t - N + 1, t] misses every fault's
// samples [n0, n1) must equal the fault-free run's, bit for bit; no
// tolerance is needed or given.
Window compare(const FaultRun& ref, const FaultRun& r,
               const std::vector<std::pair<uint32_t, uint32_t>>& faults,
               const std::function<void(size_t, uint32_t, const std::vector<uint16_t>&,
                                        const std::vector<uint16_t>&)>& inside) {
  const auto a = amplitudes(ref), b = amplitudes(r);
  EXPECT_EQ(a.size(), b.size());
  Window w;
  w.inside.assign(faults.size(), 0);
  w.inside_differ.assign(faults.size(), 0);
  for (const auto& [t, v] : b) {
    const auto it = a.find(t);
    if (it == a.end()) {
      ADD_FAILURE() << "frame t " << t << " not in the reference";
      continue;
    }
    bool touched = false;
    for (size_t f = 0; f < faults.size(); ++f) {
      const auto [n0, n1] = faults[f];
      touched = touched || (t + 1 > n0 && t < n1 + kN - 1);
      if (t >= n0 + kN - 1 && t < n1) {
        ++w.inside[f];
        w.inside_differ[f] += v != it->second;
        inside(f, t, v, it->second);
      }
    }
    if (!touched) {
      ++w.clean;
      EXPECT_EQ(v, it->second) << "t " << t << ": its window misses every fault";
    }
  }
  return w;
}

// The ADC reads its top code for 20 ms from 100 ms, then 0 for 20 ms from
// 200 ms: a constant input carries no carrier, so the taxel pressed at
// those times (carriers 0 and 5 near 4960 in the reference) must read
// below 2% of it inside the fault (what is left is the window's leakage of
// the constant, tens of LSB), and the board must forget the fault exactly,
// one window after it.
TEST(BoardFaults, AnAdcStuckAtARailIsForgottenExactlyOneWindowAfterIt) {
  const FaultRun ref = run_board({});
  const FaultRun r =
      run_board({"--fault", "adc-stuck-high@100:20", "--fault", "adc-stuck-low@200:20"});
  ASSERT_EQ(r.exit, 0);
  EXPECT_EQ(link_errors(r) + r.run.link.lost_packets, 0u);
  for (const auto& f : r.faults) ASSERT_TRUE(f.at("begun").get<bool>()) << r.faults.dump();
  size_t checked = 0;
  const Window w = compare(ref, r, {{3500, 4200}, {7000, 7700}},
                           [&](size_t, uint32_t t, const auto& v, const auto& want) {
                             for (size_t k = 0; k < want.size(); ++k)
                               if (want[k] > 1000) {
                                 ++checked;
                                 EXPECT_LT(v[k], want[k] / 50) << "t " << t << " carrier " << k;
                               }
                           });
  EXPECT_GT(w.clean, 400u);
  for (size_t f = 0; f < 2; ++f) {
    EXPECT_GE(w.inside[f], 15u);
    EXPECT_EQ(w.inside_differ[f], w.inside[f]);
  }
  EXPECT_GT(checked, 0u) << "no carrier lit inside the fault: the test shows nothing";
}

// Carrier 0 (row 0, 1900 Hz) missing for 20 ms from 100 ms, while taxel
// (0, 2) is pressed (carriers 0 and 5 lit): carrier 0 must read below 2%
// of the reference inside the fault, and everything must be exact again
// one window after it.
TEST(BoardFaults, AMissingCarrierReadsNothingOnItsLineAndComesBackExactly) {
  const FaultRun ref = run_board({});
  const FaultRun r = run_board({"--fault", "carrier-off=0@100:20"});
  ASSERT_EQ(r.exit, 0);
  EXPECT_EQ(link_errors(r) + r.run.link.lost_packets, 0u);
  size_t lit = 0;
  const Window w = compare(ref, r, {{3500, 4200}},
                           [&](size_t, uint32_t t, const auto& v, const auto& want) {
                             if (want[0] > 1000) {
                               ++lit;
                               EXPECT_LT(v[0], want[0] / 50) << "t " << t;
                             }
                             EXPECT_GT(v[5], want[5] / 2)
                                 << "t " << t << ": the column's carrier is still there";
                           });
  EXPECT_GE(w.inside[0], 15u);
  EXPECT_GT(w.clean, 400u);
  EXPECT_GT(lit, 10u);
}

// ---------------------------------------------------------------- a flood

// The host sends REQUEST_STATUS back to back at the full line rate for
// over a second: 45000 of them (12 bytes each framed, 120 bits on the
// wire: 1.8 s at 3 Mbaud), from 100 ms, on the default scene with 2 s of idle input
// after it (--tail 2) so that the flood ends inside the run. Each reply is
// far longer than its command, so the output cannot keep up: the FPGA
// must drop (and count) what does not fit, never lock up, and go back to
// every frame once the flood is over. What must hold, from the board's
// last STATUS (the reply to one more command long after the flood): every
// command is accounted for (accepted, or dropped whole as a command FIFO
// overflow, or a damaged frame; the u16 counters below their 65535
// ceiling); every accepted one's reply was delivered or counted as a
// dropped packet; no packet is delivered damaged; from the first frame
// after the last flood reply was built (its STATUS's t) to the end, no
// frame is missing (AMPLITUDES STEP samples apart).
TEST(BoardFaults, ACommandFloodAtTheFullLineRateIsCountedAndTheStreamComesBack) {
  eskin::link::LinkEncoder enc;
  std::vector<uint8_t> flood;
  const int n = 45000;
  for (int i = 0; i < n; ++i) {
    const std::vector<uint8_t> c = enc.request_status();
    flood.insert(flood.end(), c.begin(), c.end());
  }
  // One more at 2.3 s, after the flood: its reply's counters hold
  // every command of the flood.
  const uint32_t last_at = uint32_t(2.3 * kFs);
  const FaultRun r = run_board({"--tail", "2"}, {}, ESKIN_VBOARD_BIN, kScene,
                               {{3500, flood}, {last_at, enc.request_status()}});
  ASSERT_EQ(r.exit, 0);
  EXPECT_EQ(link_errors(r), 0u);
  const auto status = r.of(eskin::link::kStatus);
  ASSERT_GT(status.size(), 100u);
  const eskin::link::StatusBlock& s = status.back()->status;
  ASSERT_GE(status.back()->t, last_at) << "the last STATUS is not the late command's reply";
  const uint32_t flood_end = status[status.size() - 2]->t;
  const auto amps = r.of(eskin::link::kAmplitudes);
  ASSERT_FALSE(amps.empty());
  ASSERT_EQ(flood.size(), size_t(12 * n));
  size_t missing_in_flood = 0, after = 0;
  for (size_t i = 1; i < amps.size(); ++i) {
    const uint32_t gap = amps[i]->t - amps[i - 1]->t;
    if (amps[i - 1]->t >= flood_end) {
      ++after;
      EXPECT_EQ(gap, kStep) << "a frame missing at t " << amps[i]->t << ", after the flood";
    } else if (gap > kStep) {
      missing_in_flood += gap / kStep - 1;
    }
  }
  std::printf("flood: %d commands, the last reply built at t %u (%.3f s); %zu STATUS delivered; "
              "board: accepted %u, overflows %u, crc %u, frame %u, dropped packets %u; frames "
              "missing in the flood %zu, after it %zu frames\n",
              n, flood_end, flood_end / kFs, status.size(), s.cmd_accepted, s.cmd_overflows,
              s.cmd_crc_errors, s.cmd_frame_errors, s.dropped_frames, missing_in_flood, after);
  EXPECT_GT(flood_end, uint32_t(1.0 * kFs)) << "the flood lasted under a second";
  EXPECT_LT(s.cmd_accepted + s.cmd_overflows, 65535);
  EXPECT_EQ(int(s.cmd_accepted) + int(s.cmd_overflows) + int(s.cmd_crc_errors) +
                int(s.cmd_frame_errors),
            n + 1);
  EXPECT_EQ(status.size() + s.dropped_frames, size_t(s.cmd_accepted));
  EXPECT_GT(s.dropped_frames, 0) << "the output never overflowed: no flood";
  EXPECT_GT(after, 500u);
}

// ---------------------------------------------------------------- I2C

// A Hall sensor holds SDA of bus 0 low for 5 ms from 100 ms, mid-transfer,
// on the mixed board (mixed_neuroskin_split.yaml: the DTMF skin and Hall
// sensors on one FPGA). i2c_master times out (a stuck line ends in
// ERR_TIMEOUT, proven in tests/formal/i2c_master.sby); the bus counters
// must show it, the skin's frames must not notice, and the Hall sensors'
// samples must carry data again within 10 ms of the release (the timeout,
// the sequencer's recovery and a conversion, each a few ms at most). The
// skin's frames must equal those of the same scene without the fault.
TEST(BoardFaults, SdaHeldLowIsCountedAndTheHallSamplesComeBack) {
  const std::string scene_file = ESKIN_SOURCE_DIR "/scenes/mixed_neuroskin_split.yaml";
  const auto scene = eskin::sim::load_scene(scene_file);
  const auto build = eskin::vboard::mixed_build_for(scene, eskin::vboard::fpga_build_for(scene));
  const std::string exe = eskin::vboard::board_executable(
      build, [](const std::string& m) { std::printf("%s\n", m.c_str()); });
  const FaultRun ref = run_board({}, {}, exe, scene_file);
  const FaultRun r = run_board({"--fault", "sda-low=0@100:5"}, {}, exe, scene_file);
  ASSERT_EQ(r.exit, 0);
  const auto skin = [](const FaultRun& x) {
    std::vector<std::pair<uint32_t, std::vector<uint16_t>>> v;
    for (const Packet* p : x.of(eskin::link::kAmplitudes)) v.emplace_back(p->t, p->amplitudes);
    return v;
  };
  EXPECT_EQ(skin(r), skin(ref)) << "the skin's frames changed with the Hall bus's fault";
  EXPECT_GT(skin(r).size(), 400u);
  ASSERT_TRUE(r.faults[0].at("begun").get<bool>()) << r.faults.dump();
  const double end_ns = r.faults[0].at("end_ns");
  EXPECT_EQ(link_errors(r) + r.run.link.lost_packets, 0u);
  const auto buses = r.of(eskin::link::kHallBusStatus);
  ASSERT_FALSE(buses.empty());
  const auto& b0 = buses.back()->hall_buses.at(0);
  std::printf("bus 0: nacks %u status %u reply %u recoveries %u bus errors %u\n", b0.nacks,
              b0.status_errors, b0.reply_errors, b0.recoveries, b0.bus_errors);
  EXPECT_GT(b0.bus_errors + b0.recoveries, 0) << "the stuck SDA was not counted";
  // Hall frames carry the FPGA's us counter (docs/protocol.md), which runs
  // with the board's clock from 0.
  const double from_us = r.faults[0].at("begin_ns").get<double>() / 1e3, to_us = end_ns / 1e3;
  size_t flagged = 0, frames_after = 0;
  for (const Packet* p : r.of(eskin::link::kHallSamples)) {
    if (p->t >= from_us && p->t < to_us + 10000)
      for (const auto& s : p->hall_samples) flagged += (s.flags & s.kBus) != 0;
    if (p->t >= to_us + 10000) {
      ++frames_after;
      for (const auto& s : p->hall_samples)
        EXPECT_TRUE(s.has_data()) << "sensor " << int(s.id) << " at " << p->t << " us";
    }
  }
  EXPECT_GT(flagged, 0u) << "no reading flagged BUS while SDA was held";
  EXPECT_GT(frames_after, 10u);
}

// ---------------------------------------------------------------- options

// A bad --fault ends eskin simulate and eskin-vboard with exit 2 before
// anything runs, naming the option and what it expects.
TEST(BoardFaultCli, BadFaultsExitTwoNamingTheOption) {
  const std::string log = testing::TempDir() + "/board_fault_cli.log";
  const std::string out = testing::TempDir() + "/board_fault_cli_out";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"reset", "--fault 'reset': no '@AT_MS'"},
      {"melt@5", "unknown kind 'melt'"},
      {"adc-stuck-low@5", "adc-stuck-low needs :FOR_MS"},
      {"carrier-off@5:1", "carrier-off needs =N"},
      {"reset=2@5", "reset takes no =N"},
      {"reset@x", "AT_MS 'x' is not a number"},
      {"adc-stuck-high@5:0", "FOR_MS must be above 0"},
      {"carrier-off=6@5:1", "the skin has 6 carriers (rows, then columns: 0..5)"},
      {"sda-low=0@5:1", "this board has no I2C bus"},
      {"reset@900", "--fault reset@900:0.01: the scene ends at 600 ms"}};
  for (const auto& [value, says] : cases) {
    EXPECT_EQ(exit_of({ESKIN_BIN, "simulate", kScene, "--out", out, "--fault", value}, log), 2)
        << value;
    EXPECT_NE(slurp(log).find(says), std::string::npos) << slurp(log);
    if (says.find("scene ends") != std::string::npos) continue;  // eskin simulate's check
    EXPECT_EQ(exit_of({ESKIN_VBOARD_BIN, kScene, "--no-wait", "--fault", value}, log), 2) << value;
    EXPECT_NE(slurp(log).find(says), std::string::npos) << slurp(log);
  }
}

// eskin simulate with a reset in a frame: the fault's times in
// summary.json, and the report's rows say what the host saw (one restart,
// one error frame, one lost packet, as the board test above shows).
TEST(BoardFaultCli, SimulateReportsTheBoardsFaults) {
  const std::string log = testing::TempDir() + "/board_fault_sim.log";
  const std::string out = testing::TempDir() + "/board_fault_sim_out";
  std::filesystem::remove_all(out);
  ASSERT_EQ(exit_of({ESKIN_BIN, "simulate", kScene, "--out", out, "--fault", "reset-in-frame@100"},
                    log),
            0)
      << slurp(log);
  const nlohmann::json sum = nlohmann::json::parse(slurp(out + "/summary.json"));
  ASSERT_EQ(sum.at("board_faults").size(), 1u);
  EXPECT_EQ(sum["board_faults"][0].at("fault"), "reset-in-frame@100:0.01");
  EXPECT_TRUE(sum["board_faults"][0].at("begun").get<bool>());
  const std::string html = slurp(out + "/report.html");
  EXPECT_NE(html.find("board fault reset-in-frame@100:0.01"), std::string::npos);
  EXPECT_NE(slurp(log).find("host: board restarts / error frames / lost packets: 1 / 1 / 1"),
            std::string::npos)
      << slurp(log);
}

// The same on a mixed scene (its own report and summary, and the Hall
// part's): SDA held low, timed, in every report.
TEST(BoardFaultCli, SimulateReportsTheBoardsFaultsOnAMixedScene) {
  const std::string log = testing::TempDir() + "/board_fault_mixed.log";
  const std::string out = testing::TempDir() + "/board_fault_mixed_out";
  std::filesystem::remove_all(out);
  ASSERT_EQ(exit_of({ESKIN_BIN, "simulate", ESKIN_SOURCE_DIR "/scenes/mixed_neuroskin_split.yaml",
                     "--out", out, "--fault", "sda-low=0@100:5"},
                    log),
            0)
      << slurp(log);
  for (const std::string dir : {"", "/hall"}) {
    const nlohmann::json sum = nlohmann::json::parse(slurp(out + dir + "/summary.json"));
    ASSERT_EQ(sum.at("board_faults").size(), 1u) << dir;
    EXPECT_TRUE(sum["board_faults"][0].at("begun").get<bool>()) << dir;
    EXPECT_NE(slurp(out + dir + "/report.html").find("board fault sda-low=0@100:5"),
              std::string::npos)
        << dir;
  }
}

}  // namespace
