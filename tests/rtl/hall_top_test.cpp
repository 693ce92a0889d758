// rtl/hall_top.v with MLX90393 models on simulated I2C buses, its UART line
// decoded by host/link: every HALL_SAMPLES frame carries one reading per
// sensor, each equal to what that sensor's model sent (token for token);
// frame rate and DRDY-to-host latency in exact cycles.
//
// Figures (docs/hall_fpga.md):
//  * 16 sensors on 4 buses of 4 keep up with back-to-back 2053 us
//    conversions (OSR 0, DIG_FILT 2, XYZ: 487.1 Hz): consecutive frames are
//    exactly 2053 us apart.
//  * 16 sensors on 2 buses of 8 behind TCA9548A channels cannot: one reading
//    with its channel selection takes about 0.3 ms, 8 of them more than a
//    conversion, so frames come further apart than 2053 us.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "Vhall_top.h"
#include "Vhall_top_001.h"
#include "Vhall_top_002.h"
#include "Vhall_top_003.h"
#include "Vhall_top_16s.h"
#include "Vhall_top_deltas.h"
#include "Vhall_top_mux8.h"
#include "host/hall/hall_chain.h"
#include "hall_top_board.h"
#include "hls/ft_calibrate.h"
#include "hls/ft_calibrate_config.h"
#include "hls/force_curve.h"
#include "hls/force_curve_config.h"
#include "hls/hall_baseline.h"
#include "hls/hall_decouple.h"
#include "host/golden/hall_decouple.h"
#include "host/link/hall_packets.h"
#include "host/link/link_encoder.h"
#include "host/link/link_decoder.h"
#include "sim/hall_top_spec.h"
#include "sim/hall_world.h"
#include "sim/scene.h"

namespace {

using eskin::link::HallSample;
using eskin::link::Packet;
using hall_bench::HallBoard;
using hall_bench::kClkNs;
using hall_bench::kConvCyc;

// DRDY of the frame-completing reading to the frame's first UART start bit,
// 16 sensors on 4 buses: mostly the RM read itself (START, 10 bytes of 9
// bits at 34 clocks = 3060, repeated START, STOP and tBUF: about 3150
// clocks), plus DRDY synchronisation and pick (4), the token's 10-byte write
// into the frame RAM, the HALL_SAMPLES header's bytes and seq through
// link_framer to the COBS encoder as it takes them (2 clocks each; 3281
// while the framer held the 7 header bytes before sending any), COBS's
// look-ahead to the first zero byte of the raw frame, and the UART start.
constexpr uint64_t kLatency16s = 3270;  // 272.5 us

// Each sensor's data readings across the frames equal its model's
// deliveries in order (the last one may still be in flight).
template <class V>
void expect_frames_equal_devices(const HallBoard<V>& b) {
  for (size_t s = 0; s < b.io.size(); ++s) {
    std::vector<HallSample> got;
    for (const Packet* f : b.frames()) {
      ASSERT_EQ(f->hall_samples.size(), b.io.size());
      const HallSample& h = f->hall_samples[s];
      EXPECT_EQ(h.id, s);
      if (h.has_data()) got.push_back(h);
    }
    const auto& want = b.io.device(s).delivered();
    ASSERT_TRUE(got.size() == want.size() || got.size() + 1 == want.size())
        << "sensor " << s << ": " << got.size() << " vs " << want.size();
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].x, want[i].x) << s << "/" << i;
      EXPECT_EQ(got[i].y, want[i].y) << s << "/" << i;
      EXPECT_EQ(got[i].z, want[i].z) << s << "/" << i;
    }
  }
}

TEST(HallTop, FramesCarryEveryReadingTokenForToken) {
  HallBoard<Vhall_top> b(2, 2, false);
  b.run(12 * kConvCyc);
  const auto f = b.frames();
  ASSERT_GE(f.size(), 9u);
  expect_frames_equal_devices(b);
  EXPECT_EQ(b.dec.stats().crc_errors + b.dec.stats().framing_errors, 0u);
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
  // The first frame comes from the configuration round: no data yet.
  for (const auto& h : f[0]->hall_samples) EXPECT_EQ(h.flags, HallSample::kReply);
}

TEST(HallTop, MissingSensorFlaggedInFramesAndCountedInBusStatus) {
  HallBoard<Vhall_top> b(2, 2, false);
  b.io.device(3).set_absent(true);  // bus 1, sensor 1 never answers
  b.run(66 * kConvCyc);        // HALL_BUS_STATUS follows every 64th frame
  const auto f = b.frames();
  ASSERT_GE(f.size(), 64u);
  for (const Packet* p : f) EXPECT_EQ(p->hall_samples[3].flags, HallSample::kMissing);
  for (size_t i = 2; i < f.size(); ++i)
    for (int s = 0; s < 3; ++s) EXPECT_TRUE(f[i]->hall_samples[s].has_data()) << i;
  expect_frames_equal_devices(b);
  const Packet* st = nullptr;
  for (const auto& p : b.packets)
    if (p.type == eskin::link::kHallBusStatus) st = &p;
  ASSERT_NE(st, nullptr);
  ASSERT_EQ(st->hall_buses.size(), 2u);
  EXPECT_EQ(st->hall_buses[0].nacks, 0);
  // One NACKed attempt per frame: 64 frames, and the next round's attempt
  // may already have happened while the 64th frame was being sent.
  EXPECT_GE(st->hall_buses[1].nacks, 64);
  EXPECT_LE(st->hall_buses[1].nacks, 65);
  EXPECT_EQ(st->hall_buses[1].status_errors, 0);
}

TEST(HallTop, SixteenSensorsOnFourBusesAtTheMaximumRate) {
  HallBoard<Vhall_top_16s> b(4, 4, false);
  b.run(14 * kConvCyc);
  const auto f = b.frames();
  ASSERT_GE(f.size(), 12u);
  expect_frames_equal_devices(b);
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
  // Steady state (from the third frame): all 48 values present, frames
  // exactly one conversion (2053 us) apart, 487.1 Hz.
  for (size_t i = 2; i < f.size(); ++i) {
    for (const auto& h : f[i]->hall_samples) EXPECT_TRUE(h.has_data()) << i;
    EXPECT_EQ(f[i]->t - f[i - 1]->t, 2053u) << i;
  }
  // Latency from the DRDY of the reading that completes a frame to the
  // start bit of the frame's first byte on the UART: the same number of
  // clocks in every steady-state frame.
  std::vector<uint64_t> lat;
  for (size_t i = 2; i < f.size(); ++i)
    lat.push_back(b.frame_latency(i).first_byte);
  for (size_t i = 1; i < lat.size(); ++i) EXPECT_EQ(lat[i], lat[0]);
  std::printf("16 sensors / 4 buses: frame period 2053 us (487.1 Hz); DRDY -> first byte %llu "
              "clocks = %.1f us\n",
              (unsigned long long)lat[0], lat[0] * kClkNs / 1000.0);
  EXPECT_EQ(lat[0], kLatency16s);
}

TEST(HallTop, EightSensorsPerBusBehindMuxesCannotKeepUp) {
  HallBoard<Vhall_top_mux8> b(2, 8, true);
  b.run(14 * kConvCyc);
  const auto f = b.frames();
  ASSERT_GE(f.size(), 6u);
  expect_frames_equal_devices(b);
  const uint32_t period = (f.back()->t - f[2]->t) / uint32_t(f.size() - 3);
  std::printf("16 sensors / 2 buses of 8 behind TCA9548A: mean frame period %u us\n", period);
  EXPECT_GT(period, 2053u);
}

// tests/rtl/hall_top_test.cmake on one line, runs of spaces collapsed.
std::string cmake_flat() {
  std::ifstream cm(ESKIN_SOURCE_DIR "/tests/rtl/hall_top_test.cmake");
  std::stringstream text;
  text << cm.rdbuf();
  std::string flat;
  for (char c : text.str()) flat += (c == '\n') ? ' ' : c;
  for (size_t i; (i = flat.find("  ")) != std::string::npos;) flat.erase(i, 1);
  return flat;
}

// The system path: the seed-000 scene's physics (hall-decode's HallWorld)
// -> 16 MLX90393 models on 4 simulated buses -> the hall_top build generated
// for that scene -> UART -> host/link -> every reading equals what the models
// sent, token for token.
TEST(HallTop, Seed000SceneThroughTheFpgaEqualsTheDeviceModels) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml");
  ASSERT_TRUE(sc.has_hall);
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  // The Vhall_top_16s build is this scene's: its parameters in
  // tests/rtl/hall_top_test.cmake are exactly the generated ones.
  std::string want = "set(hall_16s";
  for (const auto& p : spec.verilog_params()) want += " " + p;
  want += ")";
  const std::string flat = cmake_flat();
  EXPECT_NE(flat.find(want), std::string::npos) << "expected in the cmake file: " << want;
  // Vhall_top_deltas adds the decoding this scene asks for.
  std::string want_d = "set(hall_deltas ${hall_16s}";
  for (const auto& p : spec.decode_params()) want_d += " " + p;
  want_d += ")";
  EXPECT_EQ(want_d, "set(hall_deltas ${hall_16s} -GDELTAS=1)");
  EXPECT_NE(flat.find(want_d), std::string::npos) << "expected in the cmake file: " << want_d;

  const eskin::sim::HallWorld world(sc.hall);
  HallBoard<Vhall_top_16s> b(world, sc.hall.config, spec);
  b.run(10 * kConvCyc);
  const auto f = b.frames();
  ASSERT_GE(f.size(), 8u);
  expect_frames_equal_devices(b);
  for (size_t i = 2; i < f.size(); ++i)
    for (const auto& h : f[i]->hall_samples) EXPECT_TRUE(h.has_data()) << i;
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
}

// The decoding's first block inside hall_top (DELTAS=1, the seed-000
// build): every HALL_SAMPLES frame is followed by a HALL_DELTAS packet whose
// slots equal hls::HallBaseline run on the frames' readings, bit for bit
// (a slot without a delta: zeros and the REPLY flag).
TEST(HallTop, DeltasFollowEveryFrameAndEqualTheHlsBaseline) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml");
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  const eskin::sim::HallWorld world(sc.hall);
  HallBoard<Vhall_top_deltas> b(world, sc.hall.config, spec);
  b.run(24 * kConvCyc);
  eskin::hls::HallBaseline<16, 4> k;
  size_t frames = 0, deltas = 0;
  for (size_t i = 0; i + 1 < b.packets.size(); ++i) {
    const Packet& p = b.packets[i];
    if (p.type != eskin::link::kHallSamples) continue;
    const Packet& q = b.packets[i + 1];
    ASSERT_EQ(q.type, eskin::link::kHallDeltas) << "packet " << i + 1;
    ASSERT_EQ(q.hall.deltas.size(), p.hall_samples.size());
    ++frames;
    for (size_t s = 0; s < p.hall_samples.size(); ++s) {
      const HallSample& h = p.hall_samples[s];
      eskin::hls::HallSampleToken t;
      t.id = h.id, t.flags = h.flags, t.x = h.x, t.y = h.y, t.z = h.z;
      eskin::hls::HallDeltaToken want;
      const bool has = k.push(t, want);
      const auto& got = q.hall.deltas[s];
      EXPECT_EQ(got.id, h.id);
      EXPECT_EQ(got.t16, h.t16);
      if (has) {
        ++deltas;
        EXPECT_EQ(got.flags, h.flags) << "frame " << frames << " sensor " << s;
        EXPECT_EQ(got.dx, want.d[0]) << "frame " << frames << " sensor " << s;
        EXPECT_EQ(got.dy, want.d[1]);
        EXPECT_EQ(got.dz, want.d[2]);
      } else {
        EXPECT_EQ(got.flags, h.flags | 0x20);
        EXPECT_EQ(got.dx, 0);
        EXPECT_EQ(got.dz, 0);
      }
    }
  }
  EXPECT_GE(frames, 20u);
  EXPECT_GE(deltas, 16u * 3);  // frames past the 16-reading capture carry deltas
}

// Commands through the top (the seed-000 build with its decoding): once the
// baseline is captured, HALL_SET_BASELINE (sensor 5, z, 1000 LSB) and later
// HALL_RECAPTURE come in over the UART, each sent when a frame's
// HALL_SAMPLES has been decoded: the buses read the next round about 1 ms
// later and a command frame takes 50 us, so each takes effect between two
// frames. Checks:
//  * every HALL_DELTAS equals hls::HallBaseline given the same commands
//    between the same frames, bit for bit;
//  * independently of the kernel: after the set, sensor 5's dz is its raw
//    z code (two's complement at these registers) minus 1000; after the
//    recapture every sensor has exactly 16 frames without a delta (the
//    capture, CAPTURE_LOG2 4) and then deltas again;
//  * a HALL_LOAD_C (this build has no ft_calibrate) is rejected as an
//    unknown type (reason 1) and answered at the end of the frame packets
//    being sent by a HALL_DECODE_STATUS counting 2 accepted, 1 rejected.
TEST(HallTop, BaselineCommandsOverTheUartTakeEffectBetweenFrames) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_000_skin.yaml");
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  const eskin::sim::HallWorld world(sc.hall);
  HallBoard<Vhall_top_deltas> b(world, sc.hall.config, spec);
  eskin::link::LinkEncoder e;
  auto frames_seen = [&] {
    size_t n = 0;
    for (const auto& p : b.packets) n += p.type == eskin::link::kHallSamples;
    return n;
  };
  auto send_after_frame = [&](size_t f, const std::vector<uint8_t>& cmd) {
    while (frames_seen() < f) b.run(500);
    b.line.send(cmd);
  };
  constexpr size_t kSet = 20, kRecap = 24, kBad = 44, kEnd = 47;
  send_after_frame(kSet, eskin::link::hall_set_baseline(e, 5, 2, 1000));
  send_after_frame(kRecap, eskin::link::hall_recapture(e));
  const uint8_t bad_seq = e.next_seq();
  send_after_frame(kBad, eskin::link::hall_load_c(e, 0, 0, 1));
  while (frames_seen() < kEnd) b.run(500);
  b.run(kConvCyc / 2);  // the last frame's HALL_DELTAS

  eskin::hls::HallBaseline<16, 4> k;
  size_t frame = 0, statuses = 0;
  std::array<int, 16> no_delta_after_recap{};
  for (size_t i = 0; i + 1 < b.packets.size(); ++i) {
    const Packet& p = b.packets[i];
    if (p.type == eskin::link::kHallDecodeStatus) {
      ++statuses;
      // Rejected while frame kBad's HALL_DELTAS was on the line: answered
      // at the end of that frame's packets.
      EXPECT_EQ(frame, kBad);
      EXPECT_EQ(b.packets[i - 1].type, eskin::link::kHallDeltas);
      EXPECT_EQ(p.hall.status.cmd_accepted, 2);
      EXPECT_EQ(p.hall.status.cmd_rejected, 1);
      EXPECT_EQ(p.hall.status.last_reject_type, eskin::link::kCmdHallLoadC);
      EXPECT_EQ(p.hall.status.last_reject_reason, 1);
      EXPECT_EQ(p.hall.status.last_reject_seq, bad_seq);
    }
    if (p.type != eskin::link::kHallSamples) continue;
    if (frame == kSet) k.set(5, 2, 1000);
    if (frame == kRecap) k.recapture();
    ++frame;
    const Packet& q = b.packets[i + 1];
    ASSERT_EQ(q.type, eskin::link::kHallDeltas) << "packet " << i + 1;
    for (size_t s = 0; s < p.hall_samples.size(); ++s) {
      const HallSample& h = p.hall_samples[s];
      eskin::hls::HallSampleToken t;
      t.id = h.id, t.flags = h.flags, t.x = h.x, t.y = h.y, t.z = h.z;
      eskin::hls::HallDeltaToken want;
      const bool has = k.push(t, want);
      const auto& got = q.hall.deltas[s];
      ASSERT_EQ(bool(got.flags & 0x20), !has) << "frame " << frame << " sensor " << s;
      if (has) {
        ASSERT_EQ(got.dx, want.d[0]) << "frame " << frame << " sensor " << s;
        ASSERT_EQ(got.dy, want.d[1]) << "frame " << frame << " sensor " << s;
        ASSERT_EQ(got.dz, want.d[2]) << "frame " << frame << " sensor " << s;
      }
      if (s == 5 && frame > kSet && frame <= kRecap) {
        EXPECT_TRUE(has) << "frame " << frame;
        EXPECT_EQ(got.dz, int16_t(h.z) - 1000) << "frame " << frame;
      }
      if (frame > kRecap && !has) {
        EXPECT_TRUE(h.has_data()) << "frame " << frame << " sensor " << s;
        ++no_delta_after_recap[s];
      }
    }
  }
  EXPECT_EQ(frame, kEnd);
  EXPECT_EQ(statuses, 1u);
  for (int s = 0; s < 16; ++s) EXPECT_EQ(no_delta_after_recap[size_t(s)], 16) << "sensor " << s;
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
}

// A HALL_DECODE_STATUS after `accepted` good commands and one bad one.
void expect_one_rejected(const eskin::link::HallDecodeStatus& st, int accepted, int type,
                         int reason, uint8_t seq) {
  EXPECT_EQ(st.cmd_accepted, accepted);
  EXPECT_EQ(st.cmd_rejected, 1);
  EXPECT_EQ(st.last_reject_type, type);
  EXPECT_EQ(st.last_reject_reason, reason);
  EXPECT_EQ(st.last_reject_seq, seq);
}

// A scene's field seen from `t0` on (the bench starts at time 0).
struct ShiftedField : eskin::sim::HallFieldSource {
  const eskin::sim::HallFieldSource& src;
  double t0;
  ShiftedField(const eskin::sim::HallFieldSource& s, double t) : src(s), t0(t) {}
  std::array<double, 3> field_uT(int sensor, double t_s) const override {
    return src.field_uT(sensor, t_s + t0);
  }
};

// Seed 002 (MagTac) through the FPGA: the hall_top build generated for the
// scene (1 bus of 3 sensors, hall_baseline, ft_calibrate, command path).
// The 6x9 C, fitted by the golden chain (eskin calibrate), is loaded by 54
// HALL_LOAD_C commands over the UART, then a bad one (row 6), which is
// answered by a HALL_DECODE_STATUS. Checks:
//  * every WRENCH6 equals hls::FtCalibrate (C loaded the same) run on the
//    HALL_DELTAS records of its frame, bit for bit, and follows them;
//  * HALL_DECODE_STATUS counts 54 accepted and 1 rejected command, with the
//    rejected one's type, reason (3: row 6) and seq;
//  * over the holds of all ten wrenches the decoded force/torque is the
//    scene's within 10% of each axis' calibration range on average: the
//    linear C itself is off by 4.1-8.1% per axis on this skin (docs/hall.md,
//    the HLS chain over the same scene; 5.5% mean), the FPGA is bit-exact
//    with that chain (checked above), so only the noise draw differs.
//    Single holds are not bounded: the linear model's error depends on the
//    wrench (up to 29% of range on Fx for the first one).
TEST(HallTop, Seed002WrenchWithCommandLoadedC) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_002_magtac.yaml");
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  std::string want = "set(hall_002";
  for (const auto& p : spec.verilog_params()) want += " " + p;
  for (const auto& p : spec.decode_params()) want += " " + p;
  want += ")";
  EXPECT_NE(cmake_flat().find(want), std::string::npos) << "expected in the cmake file: " << want;

  const eskin::sim::HallWorld world(sc.hall);
  const auto cal = eskin::hall::calibrate_wrench(world, sc.seed, 300);
  const double t0 = 0.14;  // 60 ms of rest (baseline capture), then the first wrench
  const ShiftedField field(world, t0);
  HallBoard<Vhall_top_002> b(field, sc.hall.config, spec);
  eskin::link::LinkEncoder e;
  eskin::hls::FtCalibrate<16> k;
  std::vector<uint8_t> cmds;
  auto add = [&](const std::vector<uint8_t>& f) { cmds.insert(cmds.end(), f.begin(), f.end()); };
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 9; ++j) {
      const int32_t v = eskin::hls::ft_entry(
          cal.c(i, j), eskin::mlx90393::sensitivity_uT(sc.hall.config.mlx, j % 3), 16, i, j);
      k.load(i, j, v);
      add(eskin::link::hall_load_c(e, uint8_t(i), uint8_t(j), v));
    }
  const uint8_t bad_seq = e.next_seq();
  add(eskin::link::hall_load_c(e, 6, 0, 1));
  b.line.send(cmds);
  b.run(uint64_t((sc.duration_s - t0) * 12e6));

  size_t wrenches = 0, statuses = 0;
  std::array<double, 6> err{};
  int held = 0;
  for (size_t i = 0; i < b.packets.size(); ++i) {
    const Packet& p = b.packets[i];
    if (p.type == eskin::link::kHallDecodeStatus) {
      ++statuses;
      expect_one_rejected(p.hall.status, 54, eskin::link::kCmdHallLoadC, 3, bad_seq);
      EXPECT_EQ(p.hall.status.cmd_crc_errors + p.hall.status.cmd_frame_errors, 0);
      EXPECT_EQ(p.hall.status.ft_skipped, 0);
    }
    if (p.type != eskin::link::kHallDeltas) continue;
    // The wrench the HLS kernel makes of this frame's deltas.
    eskin::hls::WrenchToken want_w;
    bool has = false;
    for (const auto& r : p.hall.deltas) {
      if (r.flags & HallSample::kNoData) continue;  // no delta in this slot
      eskin::hls::HallDeltaToken t;
      t.id = r.id, t.t = r.t16, t.flags = r.flags, t.d[0] = r.dx, t.d[1] = r.dy, t.d[2] = r.dz;
      has |= k.push(t, want_w);
    }
    const bool next_is_wrench =
        i + 1 < b.packets.size() && b.packets[i + 1].type == eskin::link::kHallWrench6;
    ASSERT_EQ(next_is_wrench, has) << "packet " << i;
    if (!has) continue;
    const Packet& w = b.packets[i + 1];
    ++wrenches;
    EXPECT_EQ(w.t & 0xFFFF, want_w.t);  // the closing token's time
    EXPECT_EQ(w.hall.wrench.flags, want_w.flags);
    for (int a = 0; a < 6; ++a) ASSERT_EQ(w.hall.wrench.w[a], want_w.w[a]) << "wrench " << wrenches;
    // In the holds, against the truth.
    const double ts = w.t * 1e-6 + t0;
    bool steady = false;
    if (eskin::hall::active_stimuli(sc.hall, ts, steady) > 0 && steady) {
      const auto tr = world.truth(ts);
      const double truth[6] = {tr.force_n[0], tr.force_n[1], tr.force_n[2],
                               tr.torque_nmm[0], tr.torque_nmm[1], tr.torque_nmm[2]};
      for (int a = 0; a < 6; ++a)
        err[size_t(a)] += std::fabs(w.hall.wrench.w[a] * 1e-3 - truth[a]) / cal.full_scale(a);
      ++held;
    }
  }
  EXPECT_GE(statuses, 1u);
  EXPECT_GE(wrenches, 1800u);  // 487 Hz over 3.86 s, less the baseline capture
  ASSERT_GE(held, 500);
  std::printf("seed 002 through hall_top: %zu wrenches, %d in holds; mean |error| in %% of range:",
              wrenches, held);
  for (int a = 0; a < 6; ++a) {
    std::printf(" %.1f", 100 * err[size_t(a)] / held);
    EXPECT_LT(err[size_t(a)] / held, 0.10) << "axis " << a;
  }
  std::printf("\n");
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
}


// The cmake file builds hall_top_TAG with exactly the parameters the spec
// generates for the scene.
void expect_generated_build(const std::string& tag, const eskin::sim::HallTopSpec& spec) {
  std::string want = "set(hall_" + tag;
  for (const auto& p : spec.verilog_params()) want += " " + p;
  for (const auto& p : spec.decode_params()) want += " " + p;
  want += ")";
  EXPECT_NE(cmake_flat().find(want), std::string::npos) << "expected in the cmake file: " << want;
}

// The HLS delta token of a HALL_DELTAS record (false: the slot has none).
bool delta_token(const eskin::link::HallDeltaRecord& r, eskin::hls::HallDeltaToken& t) {
  if (r.flags & HallSample::kNoData) return false;
  t.id = r.id, t.t = r.t16, t.flags = r.flags, t.d[0] = r.dx, t.d[1] = r.dy, t.d[2] = r.dz;
  return true;
}

// Seed 001 (split cell, 3D force) through the FPGA: the hall_top build
// generated for the scene (1 sensor, hall_baseline, hall_decouple, command
// path). Over the UART: the geomagnetic baseline (3 HALL_SET_BASELINE, as
// the HLS chain sets it: the film's own field must stay in the deltas), the
// compensation k1, c1, k2, c2 fitted by the golden chain (HALL_SET_DECOUPLE),
// then a HALL_SET_DECOUPLE one byte short (rejected, reason 2). 2.3 s of the
// scene (six presses, three with shear). Checks:
//  * every DECOUPLE3 equals hls::HallDecouple (same compensation) run on the
//    HALL_DELTAS record of its frame, bit for bit, and follows it;
//  * HALL_DECODE_STATUS: 4 accepted, 1 rejected (type, reason 2, seq);
//  * in the holds, the host's force polynomials of the FPGA's Rx, Ry, Sz
//    give the scene's force within 2.5 % of full scale on average (shear
//    and normal): the same kernels over the whole scene give 1.23 % and
//    0.62 % (docs/hall.md, hall_figures); bit-exact here, so only the
//    noise draw and the shorter window differ; 2.5 % is about twice the
//    larger of them.
TEST(HallTop, Seed001DecouplingWithCommandSetCompensation) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_001_split.yaml");
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  expect_generated_build("001", spec);
  ASSERT_TRUE(spec.decouple);
  const eskin::sim::HallWorld world(sc.hall);
  const auto& h = world.config();
  const auto cal = eskin::hall::calibrate_decouple(world, sc.seed);
  eskin::hls::HallDecoupleConfig cfg;
  for (int a = 0; a < 3; ++a) cfg.gain[a] = spec.dec_gain[a];
  cfg.k1 = int16_t(std::lround(cal.params.k1 * 16384)), cfg.k2 = int16_t(std::lround(cal.params.k2 * 16384));
  cfg.c1 = int32_t(std::lround(cal.params.c1_ut * 64)), cfg.c2 = int32_t(std::lround(cal.params.c2_ut * 64));
  eskin::hls::HallDecouple<0> k(cfg);

  HallBoard<Vhall_top_001> b(world, h, spec);
  eskin::link::LinkEncoder e;
  std::vector<uint8_t> cmds;
  auto add = [&](const std::vector<uint8_t>& f) { cmds.insert(cmds.end(), f.begin(), f.end()); };
  for (int a = 0; a < 3; ++a)
    add(eskin::link::hall_set_baseline(
        e, 0, uint8_t(a),
        int16_t(std::lround(h.geomagnetic_ut[size_t(a)] / eskin::mlx90393::sensitivity_uT(h.mlx, a)))));
  add(eskin::link::hall_set_decouple(e, cfg.k1, cfg.c1, cfg.k2, cfg.c2));
  const uint8_t bad_seq = e.next_seq();
  add(e.frame(eskin::link::kCmdHallSetDecouple, 0, std::vector<uint8_t>(11, 0)));  // one byte short
  b.line.send(cmds);
  constexpr double kRun = 2.3;
  b.run(uint64_t(kRun * 12e6));

  const eskin::golden::Decoupled rest = eskin::golden::hall_decouple(cal.rest_film_ut, cal.params);
  size_t outs = 0, statuses = 0;
  double shear = 0, normal = 0;
  int held = 0;
  for (size_t i = 0; i < b.packets.size(); ++i) {
    const Packet& p = b.packets[i];
    if (p.type == eskin::link::kHallDecodeStatus) {
      ++statuses;
      expect_one_rejected(p.hall.status, 4, eskin::link::kCmdHallSetDecouple, 2, bad_seq);
    }
    if (p.type != eskin::link::kHallDeltas) continue;
    ASSERT_EQ(p.hall.deltas.size(), 1u);
    eskin::hls::HallDeltaToken t;
    eskin::hls::DecoupleToken want;
    const bool has = delta_token(p.hall.deltas[0], t) && k.push(t, want);
    const bool next_is =
        i + 1 < b.packets.size() && b.packets[i + 1].type == eskin::link::kHallDecouple3;
    ASSERT_EQ(next_is, has) << "packet " << i;
    if (!has) continue;
    const Packet& d = b.packets[i + 1];
    ++outs;
    EXPECT_EQ(d.t & 0xFFFF, want.t);
    ASSERT_EQ(d.hall.decouple.rx, want.rx) << "output " << outs;
    ASSERT_EQ(d.hall.decouple.ry, want.ry) << "output " << outs;
    ASSERT_EQ(d.hall.decouple.sz, want.sz) << "output " << outs;
    ASSERT_EQ(d.hall.decouple.valid, want.valid) << "output " << outs;
    ASSERT_EQ(d.hall.decouple.flags, want.flags) << "output " << outs;
    bool steady = false;
    const double ts = d.t * 1e-6;
    if (!want.valid || eskin::hall::active_stimuli(sc.hall, ts, steady) == 0 || !steady) continue;
    eskin::golden::Decoupled g;
    g.rx = want.rx / 16777216.0, g.ry = want.ry / 16777216.0, g.sz = want.sz / 16777216.0, g.valid = true;
    const auto f = eskin::golden::decoupled_force(g, rest, cal.params);
    const auto tr = world.truth(ts);
    shear += (std::fabs(f[0] - tr.force_n[0]) + std::fabs(f[1] - tr.force_n[1])) / (2 * cal.shear_fs_n);
    normal += std::fabs(f[2] + tr.force_n[2]) / cal.normal_fs_n;
    ++held;
  }
  EXPECT_GE(statuses, 1u);
  EXPECT_GE(outs, 1000u);  // 487 Hz over 2.3 s
  ASSERT_GE(held, 300);
  std::printf("seed 001 through hall_top: %zu DECOUPLE3, %d in holds; mean |error| shear %.2f%%, normal %.2f%% of full scale\n",
              outs, held, 100 * shear / held, 100 * normal / held);
  EXPECT_LT(shear / held, 0.025);
  EXPECT_LT(normal / held, 0.025);
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
}


// Seed 003 (metamaterial cells, three stiffness ranges) through the FPGA:
// the hall_top build generated for the scene (9 sensors behind a TCA9548A
// on one bus, hall_baseline, force_curve of 9 cells, command path). The
// curves fitted by the golden chain are loaded by 351 HALL_LOAD_CURVE over
// the UART, then one with index 13 (rejected, reason 3). 2.3 s of the scene
// (presses from 0.06 to 7.5 N: all three ranges). Checks:
//  * every FORCE_CURVE follows its frame's HALL_DELTAS and has 9 records:
//    for a slot with a delta, hls::ForceCurve (same tables) on it, bit for
//    bit; for one without, force 0, t 0 and the REPLY flag;
//  * HALL_DECODE_STATUS: 351 accepted, 1 rejected (type, reason 3, seq);
//  * in the holds, each pressed cell's force within 2 % of its range's top
//    on average, per range: the same kernels over the whole scene give
//    0.39 / 0.16 / 0.15 % (docs/hall.md); bit-exact here, so only the noise
//    draw and the window differ; 2 % leaves room for a window with fewer
//    frames per range.
TEST(HallTop, Seed003ForceCurvesWithCommandLoadedTables) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/hall_003_metamaterial.yaml");
  const auto spec = eskin::sim::hall_top_spec(sc.hall.config);
  expect_generated_build("003", spec);
  ASSERT_TRUE(spec.curve);
  constexpr int kNb = 13, kNc = 9;
  ASSERT_EQ(spec.curve_nb, kNb);
  ASSERT_EQ(spec.nc, kNc);
  const eskin::sim::HallWorld world(sc.hall);
  const auto& h = world.config();
  const auto curves = eskin::hall::calibrate_force_curves(world, sc.seed);
  eskin::hls::ForceCurveConfig<kNb, 3> cfg;
  for (int a = 0; a < 3; ++a) cfg.gain[a] = eskin::hls::force_curve_gain(eskin::mlx90393::sensitivity_uT(h.mlx, a));
  for (int r = 0; r < 3; ++r) cfg.lock_mn[r] = spec.lock_mn[size_t(r)];
  eskin::hls::ForceCurve<kNc, kNb> k(cfg);

  HallBoard<Vhall_top_003> b(world, h, spec);
  eskin::link::LinkEncoder e;
  std::vector<uint8_t> cmds;
  auto add = [&](const std::vector<uint8_t>& f) { cmds.insert(cmds.end(), f.begin(), f.end()); };
  for (int c = 0; c < kNc; ++c) {
    const auto t = eskin::hls::force_curve_table<kNb>(curves[size_t(c)].db_ut.data(), curves[size_t(c)].force_n.data(), kNb);
    k.table(c) = t;
    for (int i = 0; i < kNb; ++i)
      for (int which = 0; which < 3; ++which)
        add(eskin::link::hall_load_curve(e, uint8_t(c), uint8_t(i), uint8_t(which),
                                         which == 0 ? t.db[i] : which == 1 ? t.f[i] : t.slope[i]));
  }
  const uint8_t bad_seq = e.next_seq();
  add(eskin::link::hall_load_curve(e, 0, kNb, 0, 1));
  b.line.send(cmds);
  constexpr double kRun = 2.3;
  b.run(uint64_t(kRun * 12e6));

  const auto lock = h.cells[0].stack_lock_forces_n();
  size_t outs = 0, statuses = 0, results = 0;
  std::array<double, 3> err{};
  std::array<int, 3> held{};
  for (size_t i = 0; i < b.packets.size(); ++i) {
    const Packet& p = b.packets[i];
    if (p.type == eskin::link::kHallDecodeStatus) {
      ++statuses;
      expect_one_rejected(p.hall.status, kNc * kNb * 3, eskin::link::kCmdHallLoadCurve, 3, bad_seq);
    }
    if (p.type != eskin::link::kHallDeltas) continue;
    ASSERT_TRUE(i + 1 < b.packets.size() && b.packets[i + 1].type == eskin::link::kHallForceCurve)
        << "packet " << i;
    const Packet& f = b.packets[i + 1];
    ASSERT_EQ(f.hall.forces.size(), size_t(kNc));
    ++outs;
    for (int c = 0; c < kNc; ++c) {
      const auto& got = f.hall.forces[size_t(c)];
      ASSERT_EQ(got.cell, c);
      eskin::hls::HallDeltaToken t;
      eskin::hls::ForceToken want;
      if (!delta_token(p.hall.deltas[size_t(spec.slot[size_t(c)])], t) || !k.push(t, want)) {
        ASSERT_EQ(got.force_mn, 0) << "frame " << outs << " cell " << c;
        ASSERT_EQ(got.t, 0u);
        ASSERT_EQ(got.flags, HallSample::kReply);
        continue;
      }
      ++results;
      ASSERT_EQ(got.t & 0xFFFF, want.t) << "frame " << outs << " cell " << c;
      ASSERT_EQ(got.force_mn, want.force_mn) << "frame " << outs << " cell " << c;
      ASSERT_EQ(got.range, want.range) << "frame " << outs << " cell " << c;
      ASSERT_EQ(got.flags, want.flags) << "frame " << outs << " cell " << c;
      bool steady = false;
      const double ts = got.t * 1e-6;
      if (eskin::hall::active_stimuli(sc.hall, ts, steady) == 0 || !steady) continue;
      const double ft = -world.truth(ts).cells[size_t(c)].force_n[2];
      if (ft <= 0) continue;
      const size_t r = size_t(std::lower_bound(lock.begin(), lock.end(), ft) - lock.begin());
      if (r > 2) continue;
      err[r] += std::fabs(got.force_mn / 1000.0 - ft) / lock[r];
      ++held[r];
    }
  }
  EXPECT_GE(statuses, 1u);
  EXPECT_GE(outs, 600u);  // about 340 frames/s (9 readings behind the mux per round) over 2.3 s
  EXPECT_GE(results, outs * kNc - 16 * kNc - kNc);  // all but the baseline capture
  std::printf("seed 003 through hall_top: %zu FORCE_CURVE packets; mean |error| in %% of the range's top:", outs);
  for (int r = 0; r < 3; ++r) {
    ASSERT_GE(held[size_t(r)], 20) << "range " << r;
    std::printf(" range %d %.2f (%d)", r + 1, 100 * err[size_t(r)] / held[size_t(r)], held[size_t(r)]);
    EXPECT_LT(err[size_t(r)] / held[size_t(r)], 0.02) << "range " << r;
  }
  std::printf("\n");
  for (const auto& v : b.io.violations()) ADD_FAILURE() << v;
}

}  // namespace
