// eskin stream and eskin config as a user runs them: the real binary on a
// real pty, its NDJSON parsed as JSON (nlohmann), its CSV files read back
// and its HDF5 file opened with the HDF5 C API after a clean stop, after the
// board hung up mid-run, and after the process was killed.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "host/link/hall_packets.h"
#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
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
                     ("eskin_stream_cli_" + std::to_string(getpid()) + "_" +
                      ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}


// An int64 dataset's values and dims, quietly: false if it does not open
// or read (no test failure: a file being written may not be there yet).
bool try_read_set(hid_t file, const std::string& name, std::vector<int64_t>& v,
                  std::vector<hsize_t>& dims) {
  const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  if (d < 0) return false;
  const hid_t sp = H5Dget_space(d);
  const int nd = sp < 0 ? -1 : H5Sget_simple_extent_ndims(sp);
  bool ok = nd > 0;
  if (ok) {
    dims.assign(size_t(nd), 0);
    H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
    hsize_t n = 1;
    for (hsize_t x : dims) n *= x;
    v.assign(n, 0);
    ok = n == 0 || H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0;
  }
  if (sp >= 0) H5Sclose(sp);
  H5Dclose(d);
  return ok;
}

// Whether the HDF5 file, read while its writer still runs (file locking
// off: the writer holds the lock), already holds exactly the expected
// lines' values in every table, as expect_hdf5_matches checks them: what
// the writer has flushed. False while the file or a table does not open
// yet, or is short.
bool hdf5_holds(const std::string& path, const std::vector<json>& want) {
  H5E_auto2_t func;
  void* data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);  // a failed open here is expected, not news
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_file_locking(fapl, false, true);
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  bool all = f >= 0;
  std::vector<int64_t> v;
  std::vector<hsize_t> dims;
  for (const char* table : {"amplitudes", "taxels", "taxels_sparse", "spikes", "status"}) {
    if (!all) break;
    std::vector<const json*> rows;
    for (const json& j : want)
      if (j["type"] == table) rows.push_back(&j);
    if (rows.empty()) continue;
    for (const auto& [column, value] : rows[0]->items()) {
      if (column == "type" || value.is_array()) continue;
      all = all && try_read_set(f, std::string("/") + table + "/" + column, v, dims) &&
            v.size() == rows.size();
      for (size_t i = 0; all && i < rows.size(); ++i) all = v[i] == (*rows[i])[column].get<int64_t>();
    }
    const char* vec = std::string(table) == "amplitudes" ? "amp"
                      : std::string(table) == "taxels"   ? "taxel"
                                                         : nullptr;
    if (!vec || !all) continue;
    all = try_read_set(f, std::string("/") + table + "/" + vec, v, dims) && dims.size() == 2 &&
          dims[0] == rows.size();
    for (size_t i = 0; all && i < rows.size(); ++i)
      for (size_t k = 0; all && k < dims[1]; ++k)
        all = v[i * dims[1] + k] == (*rows[i])[vec][k].get<int64_t>();
  }
  if (f >= 0) H5Fclose(f);
  H5Pclose(fapl);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  return all;
}

TEST(StreamCli, DefaultSceneToNdjsonCsvAndHdf5) {
  const fs::path dir = tmpdir();
  std::vector<Sent> sent;
  const auto wire = scene_frames(sent, SIZE_MAX, 0x1F);  // sparse taxels too
  const auto want = expected_lines(sent);
  PtyPair pty;
  Process p({ESKIN_BIN, "stream", "--port", pty.slave_path(), "--count",
             std::to_string(sent.size()), "--csv", (dir / "csv").string(), "--hdf5",
             (dir / "run.h5").string(), "--scene", ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml"},
            (dir / "out").string(), (dir / "err").string());
  ASSERT_TRUE(p.wait_output([](const std::string& e) { return e.find("link open") != e.npos; },
                            true, 10s));
  ASSERT_TRUE(write_fully(pty.master(), wire));
  ASSERT_EQ(p.wait_exit(30s), 0) << p.err();
  const auto got = parse_ndjson(p.out());
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << "line " << i;

  // CSV: header plus one line per row of each table, values as in NDJSON.
  size_t amps = 0, spikes = 0, sparse = 0;
  for (const json& j : want)
    amps += j["type"] == "amplitudes", spikes += j["type"] == "spikes",
        sparse += j["type"] == "taxels_sparse";
  ASSERT_GT(sparse, 0u) << "the presses light taxels above g = 1";
  const std::string sparse_csv = slurp((dir / "csv" / "taxels_sparse.csv").string());
  EXPECT_EQ(sparse_csv.substr(0, sparse_csv.find('\n')), "seq,t,row,col,value");
  EXPECT_EQ(lines(sparse_csv), sparse + 1);
  const std::string amp_csv = slurp((dir / "csv" / "amplitudes.csv").string());
  EXPECT_EQ(amp_csv.substr(0, amp_csv.find('\n')), "seq,t,amp0,amp1,amp2,amp3,amp4,amp5");
  EXPECT_EQ(lines(amp_csv), amps + 1);
  EXPECT_EQ(lines(slurp((dir / "csv" / "spikes.csv").string())), spikes + 1);
  std::ostringstream first;
  first << want[0]["seq"] << ',' << want[0]["t"];
  for (const auto& a : want[0]["amp"]) first << ',' << a;
  EXPECT_EQ(amp_csv.substr(amp_csv.find('\n') + 1, first.str().size()), first.str());

  expect_hdf5_matches((dir / "run.h5").string(), want);
  const hid_t f = H5Fopen((dir / "run.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_EQ(read_attr(f, "scene_name"), "neuroskin2");
  EXPECT_EQ(read_attr(f, "skin_rows"), "3");
  EXPECT_EQ(read_attr(f, "baud"), "3000000");
  EXPECT_NE(read_attr(f, "scene_yaml").find("rows: [1900, 3300, 5000]"), std::string::npos);
  EXPECT_NE(read_attr(f, "endpoint").find(pty.slave_path()), std::string::npos);
  H5Fclose(f);
  fs::remove_all(dir);
}

// The board hangs up mid-run (pty master closed, as the virtual board does
// at the end of its scene): a pty never comes back (a new board gets a new
// one), so eskin stream says so and ends on its own, exit 0, with its
// statistics, and the HDF5 file holds every packet. (A serial device that
// drops is reopened: LinkStreamPty.ReportsALostDeviceAndReopensIt.)
TEST(StreamCli, BoardThatHangsUpEndsTheRunWithTheRecordingKept) {
  const fs::path dir = tmpdir();
  std::vector<Sent> sent;
  const auto frames = random_frames(200, 7, sent);
  const auto want = expected_lines(sent);
  const size_t all_lines = ndjson_rows(sent);
  const fs::path link = dir / "board.tty";
  auto board = std::make_unique<PtyPair>();
  fs::create_symlink(board->slave_path(), link);
  Process p({ESKIN_BIN, "stream", "--port", link.string(), "--hdf5", (dir / "run.h5").string()},
            (dir / "out").string(), (dir / "err").string());
  const auto has = [](const char* what, size_t n) {
    return [what, n](const std::string& e) { return count_of(e, what) >= n; };
  };
  ASSERT_TRUE(p.wait_output(has("link open", 1), true, 10s));
  ASSERT_TRUE(write_fully(board->master(), concat(frames)));
  ASSERT_TRUE(p.wait_output([&](const std::string& o) { return lines(o) >= all_lines; }, false,
                            10s));
  board->close_master();
  ASSERT_EQ(p.wait_exit(10s), 0) << p.err();
  EXPECT_NE(p.err().find("the board hung up (the virtual board's scene is over); the stream ends"),
            std::string::npos)
      << p.err();
  EXPECT_EQ(p.err().find("attempt"), std::string::npos) << "it retried:\n" << p.err();
  EXPECT_NE(p.err().find("eskin stream: 200 packets;"), std::string::npos) << p.err();
  EXPECT_NE(p.err().find("\"connects\":1"), std::string::npos) << p.err();
  SCOPED_TRACE("eskin stream's stderr:\n" + p.err());
  expect_hdf5_matches((dir / "run.h5").string(), want);
  fs::remove_all(dir);
}

// SIGKILL, no chance to close the file: everything flushed before the kill
// (every packet's row, seen in the file by a reader while the recorder
// runs) is in a file that opens.
TEST(StreamCli, KilledRunLeavesAReadableHdf5File) {
  const fs::path dir = tmpdir();
  std::vector<Sent> sent;
  const auto wire = scene_frames(sent, 10000);
  const auto want = expected_lines(sent);
  PtyPair pty;
  Process p({ESKIN_BIN, "stream", "--port", pty.slave_path(), "--hdf5",
             (dir / "run.h5").string(), "--flush-ms", "100"},
            (dir / "out").string(), (dir / "err").string());
  ASSERT_TRUE(p.wait_output([](const std::string& e) { return e.find("link open") != e.npos; },
                            true, 10s));
  ASSERT_TRUE(write_fully(pty.master(), wire));
  const size_t all_lines = ndjson_rows(sent);
  ASSERT_TRUE(p.wait_output([&](const std::string& o) { return lines(o) >= all_lines; }, false,
                            10s));
  // Killed once a flush has put every row in the file: a reader sees them
  // all, value for value (polled until it does, not timed).
  bool flushed = false;
  for (auto end = std::chrono::steady_clock::now() + 30s;
       !(flushed = hdf5_holds((dir / "run.h5").string(), want)) &&
       std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(20ms);
  ASSERT_TRUE(flushed) << "no flush put every row in the file within 30 s";
  p.signal(SIGKILL);
  EXPECT_EQ(p.wait_exit(10s), 128 + SIGKILL);
  expect_hdf5_matches((dir / "run.h5").string(), want);
  fs::remove_all(dir);
}

// A Hall board's packets (docs/protocol.md sections 8 and 9) through the
// real binary: every reading, delta, decoded force and counter comes out as
// one NDJSON row per sensor, bus or cell record, in CSV and HDF5 too. The
// payloads are written here byte by byte from the protocol's layouts, and
// the expected rows read back from those bytes, so the decoder and the
// tables are what is tested.
TEST(StreamCli, HallPacketsToNdjsonCsvAndHdf5) {
  const fs::path dir = tmpdir();
  eskin::link::LinkEncoder enc;
  std::vector<uint8_t> wire;
  std::vector<json> want;
  auto u16 = [](std::vector<uint8_t>& b, uint32_t v) { b.push_back(uint8_t(v)), b.push_back(uint8_t(v >> 8)); };
  auto u32 = [&](std::vector<uint8_t>& b, uint32_t v) { u16(b, v & 0xFFFF), u16(b, v >> 16); };
  auto send = [&](uint8_t type, uint32_t t, const std::vector<uint8_t>& payload) {
    const uint8_t seq = enc.next_seq();
    const auto f = enc.frame(type, t, payload);
    wire.insert(wire.end(), f.begin(), f.end());
    return seq;
  };
  for (uint32_t k = 0; k < 40; ++k) {
    const uint32_t t = 2053 * (k + 1);
    std::vector<uint8_t> samples, deltas;
    for (int id = 0; id < 3; ++id) {  // three sensors; sensor 2 missing on odd frames
      const uint8_t flags = (id == 2 && k % 2) ? 0x08 : 0x00;
      const uint16_t x = uint16_t(1000 * id + k), y = uint16_t(0xFF00 - k), z = uint16_t(7 * k);
      const int16_t dx = int16_t(-int(k) - id), dy = int16_t(3 * k), dz = int16_t(-300 + id);
      samples.insert(samples.end(), {uint8_t(id), flags}), u16(samples, t & 0xFFFF), u16(samples, x),
          u16(samples, y), u16(samples, z);
      deltas.insert(deltas.end(), {uint8_t(id), flags}), u16(deltas, t & 0xFFFF), u16(deltas, uint16_t(dx)),
          u16(deltas, uint16_t(dy)), u16(deltas, uint16_t(dz));
    }
    const uint8_t s1 = send(eskin::link::kHallSamples, t, samples);
    const uint8_t s2 = send(eskin::link::kHallDeltas, t, deltas);
    for (int id = 0; id < 3; ++id) {
      const size_t o = size_t(10 * id);
      auto le = [&](const std::vector<uint8_t>& b, size_t i) { return int(b[i] | b[i + 1] << 8); };
      want.push_back({{"type", "hall_samples"}, {"seq", s1}, {"t", t}, {"id", samples[o]},
                      {"flags", samples[o + 1]}, {"t16", le(samples, o + 2)}, {"x", le(samples, o + 4)},
                      {"y", le(samples, o + 6)}, {"z", le(samples, o + 8)}});
    }
    for (int id = 0; id < 3; ++id) {
      const size_t o = size_t(10 * id);
      auto sle = [&](size_t i) { return int(int16_t(deltas[i] | deltas[i + 1] << 8)); };
      want.push_back({{"type", "hall_deltas"}, {"seq", s2}, {"t", t}, {"id", deltas[o]},
                      {"flags", deltas[o + 1]}, {"t16", sle(o + 2) & 0xFFFF}, {"dx", sle(o + 4)},
                      {"dy", sle(o + 6)}, {"dz", sle(o + 8)}});
    }
    std::vector<uint8_t> dec;  // rx, ry, sz s32, valid, flags
    const int32_t rx = -int32_t(k) * 100000, ry = int32_t(k) * 7, sz = 16777216 * 5 + int32_t(k);
    u32(dec, uint32_t(rx)), u32(dec, uint32_t(ry)), u32(dec, uint32_t(sz)), dec.push_back(1), dec.push_back(0);
    want.push_back({{"type", "hall_decouple"}, {"seq", send(eskin::link::kHallDecouple3, t, dec)}, {"t", t},
                    {"rx", rx}, {"ry", ry}, {"sz", sz}, {"valid", 1}, {"flags", 0}});
    std::vector<uint8_t> w;  // six s32, flags
    json wj = {{"type", "hall_wrench"}, {"t", t}, {"flags", 2}};
    const char* names[] = {"fx_mn", "fy_mn", "fz_mn", "tx_mnmm", "ty_mnmm", "tz_mnmm"};
    for (int a = 0; a < 6; ++a) {
      const int32_t v = (a % 2 ? -1 : 1) * int32_t(1000 * a + k);
      u32(w, uint32_t(v));
      wj[names[a]] = v;
    }
    w.push_back(2);
    wj["seq"] = send(eskin::link::kHallWrench6, t, w);
    want.push_back(wj);
    std::vector<uint8_t> fc;  // cell, range, flags, t u32, force s32
    const uint8_t sf = enc.next_seq();
    for (int c = 0; c < 2; ++c) {
      fc.insert(fc.end(), {uint8_t(c), uint8_t(k % 3), uint8_t(c ? 0x20 : 0)});
      u32(fc, c ? 0u : t - 300), u32(fc, uint32_t(c ? 0 : 450 * int32_t(k) - 2000));
      want.push_back({{"type", "hall_forces"}, {"seq", sf}, {"t", t}, {"cell", c}, {"range", k % 3},
                      {"flags", c ? 0x20 : 0}, {"t_us", c ? 0u : t - 300},
                      {"force_mn", c ? 0 : 450 * int32_t(k) - 2000}});
    }
    send(eskin::link::kHallForceCurve, t, fc);
  }
  std::vector<uint8_t> bus;  // two buses of five u16 counters
  for (int b = 0; b < 2; ++b)
    for (int c = 0; c < 5; ++c) u16(bus, uint16_t(10 * b + c));
  const uint8_t sb = send(eskin::link::kHallBusStatus, 90000, bus);
  for (int b = 0; b < 2; ++b)
    want.push_back({{"type", "hall_bus_status"}, {"seq", sb}, {"t", 90000}, {"bus", b},
                    {"nacks", 10 * b}, {"status_errors", 10 * b + 1}, {"reply_errors", 10 * b + 2},
                    {"recoveries", 10 * b + 3}, {"bus_errors", 10 * b + 4}});
  std::vector<uint8_t> st;  // seven u16, three u8
  const char* st16[] = {"baseline_dropped", "ft_skipped", "cmd_accepted", "cmd_rejected",
                        "cmd_crc_errors", "cmd_frame_errors", "cmd_overflows"};
  json sj = {{"type", "hall_decode_status"}, {"t", 90001}};
  for (int i = 0; i < 7; ++i) u16(st, uint16_t(100 + i)), sj[st16[i]] = 100 + i;
  st.insert(st.end(), {0x98, 3, 17});
  sj["last_reject_type"] = 0x98, sj["last_reject_reason"] = 3, sj["last_reject_seq"] = 17;
  sj["seq"] = send(eskin::link::kHallDecodeStatus, 90001, st);
  want.push_back(sj);

  const size_t frames = 40 * 5 + 2;
  PtyPair pty;
  Process p({ESKIN_BIN, "stream", "--port", pty.slave_path(), "--count", std::to_string(frames),
             "--csv", (dir / "csv").string(), "--hdf5", (dir / "run.h5").string()},
            (dir / "out").string(), (dir / "err").string());
  ASSERT_TRUE(p.wait_output([](const std::string& e) { return e.find("link open") != e.npos; },
                            true, 10s));
  ASSERT_TRUE(write_fully(pty.master(), wire));
  ASSERT_EQ(p.wait_exit(30s), 0) << p.err();
  const auto got = parse_ndjson(p.out());
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) ASSERT_EQ(got[i], want[i]) << "line " << i;
  const std::string forces = slurp((dir / "csv" / "hall_forces.csv").string());
  EXPECT_EQ(forces.substr(0, forces.find('\n')), "seq,t,cell,range,flags,t_us,force_mn");
  EXPECT_EQ(lines(forces), 80u + 1);
  EXPECT_EQ(lines(slurp((dir / "csv" / "hall_samples.csv").string())), 120u + 1);
  // HDF5: every scalar column of every Hall table, row for row.
  const hid_t f = H5Fopen((dir / "run.h5").string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::vector<hsize_t> dims;
  for (const char* table : {"hall_samples", "hall_deltas", "hall_decouple", "hall_wrench",
                            "hall_forces", "hall_bus_status", "hall_decode_status"}) {
    std::vector<const json*> rows;
    for (const json& j : want)
      if (j["type"] == table) rows.push_back(&j);
    ASSERT_FALSE(rows.empty()) << table;
    for (const auto& [column, value] : rows[0]->items()) {
      if (column == "type") continue;
      const auto v = read_set(f, std::string("/") + table + "/" + column, dims);
      ASSERT_EQ(v.size(), rows.size()) << table << "/" << column;
      for (size_t i = 0; i < rows.size(); ++i)
        ASSERT_EQ(v[i], (*rows[i])[column].get<int64_t>()) << table << "/" << column << " row " << i;
    }
  }
  H5Fclose(f);
}

TEST(StreamCli, BadOptionsFailWithAMessage) {
  const fs::path dir = tmpdir();
  const auto run = [&](std::vector<std::string> args) {
    args.insert(args.begin(), ESKIN_BIN);
    Process p(args, (dir / "out").string(), (dir / "err").string());
    const int rc = p.wait_exit(20s);
    return std::make_pair(rc, p.err());
  };
  auto [rc1, e1] = run({"stream", "--tcp", "localhost"});
  EXPECT_NE(rc1, 0);
  EXPECT_NE(e1.find("expected HOST:PORT"), std::string::npos) << e1;
  auto [rc2, e2] = run({"stream", "--duration", "1"});
  EXPECT_NE(rc2, 0);
  EXPECT_NE(e2.find("--port DEV or --tcp HOST:PORT"), std::string::npos) << e2;
  auto [rc3, e3] = run({"stream", "--port", "/nonexistent/tty", "--duration", "0.3"});
  EXPECT_EQ(rc3, 1);
  EXPECT_NE(e3.find("/nonexistent/tty: cannot open"), std::string::npos) << e3;
  EXPECT_NE(e3.find("never opened"), std::string::npos) << e3;
  auto [rc4, e4] = run({"stream", "--port", "/dev/null", "--live", "127.0.0.1:99999"});
  EXPECT_NE(rc4, 0);
  EXPECT_NE(e4.find("--live '127.0.0.1:99999'"), std::string::npos) << e4;
  fs::remove_all(dir);
}

}  // namespace
