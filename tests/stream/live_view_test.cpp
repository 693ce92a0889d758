// The live view in a real browser: the default scene's packets (what the
// FPGA sends) stream through a pty into LinkStream and the LiveView
// recorder, up to the middle of the press on taxel (1, 2) (scene: 0.235 s
// + 5 ms ramp, held to 0.265 s; we stop at 0.245 s = sample 8575).
// Headless Chromium (Debian's chromium) loads the page and takes a
// screenshot; libpng decodes it and the heatmap cell of (1, 2) must be red
// (the frame's maximum) and the cells of untouched taxels blue.
// Geometry and colour ramp: host/stream/live_view_page.h.
#include <gtest/gtest.h>
#include <httplib.h>
#include <png.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "host/stream/link_stream.h"
#include "host/stream/commands.h"
#include "host/stream/live_view.h"
#include "host/stream/live_view_page.h"
#include "sim/scene.h"
#include "tests/stream/frames.h"
#include "tests/stream/pty_pair.h"

namespace fs = std::filesystem;
using namespace eskin::testing;
using namespace std::chrono_literals;

namespace {

struct Rgb {
  int r, g, b;
};

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::ostringstream o;
  o << f.rdbuf();
  return o.str();
}

// Decodes a PNG into 8-bit RGB.
bool read_png(const std::string& path, int& w, int& h, std::vector<uint8_t>& rgb) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) return false;
  img.format = PNG_FORMAT_RGB;
  rgb.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, rgb.data(), 0, nullptr)) return false;
  w = int(img.width);
  h = int(img.height);
  return true;
}

TEST(LiveView, ChromiumScreenshotShowsThePressedTaxel) {
  std::vector<Sent> sent;
  const auto wire = scene_frames(sent, 8575);
  // Precondition from the packets themselves: the last taxel frame peaks at (1, 2).
  const Sent* last = nullptr;
  for (const Sent& s : sent)
    if (s.type == eskin::link::kTaxelsDense) last = &s;
  ASSERT_NE(last, nullptr);
  std::vector<int> values;
  for (size_t i = 2; i < last->payload.size(); i += 2)
    values.push_back(last->payload[i] | (last->payload[i + 1] << 8));
  ASSERT_EQ(values.size(), 9u);
  ASSERT_EQ(std::max_element(values.begin(), values.end()) - values.begin(), 1 * 3 + 2);
  std::printf("taxel frame at t = %u:", last->t);
  for (int v : values) std::printf(" %d", v);
  std::printf("\n");

  PtyPair pty;
  eskin::stream::StreamOptions opt;
  opt.endpoint = eskin::stream::Endpoint::serial(pty.slave_path());
  eskin::stream::LinkStream stream(opt);
  eskin::stream::LiveView live("127.0.0.1", 0);
  live.set_link_stats([&stream] { return eskin::stream::stats_json(stream.stats()); });
  eskin::stream::RecorderSet recorders;
  recorders.add(&live);
  std::atomic<size_t> n{0};
  stream.on_packet([&](const eskin::link::Packet& p) {
    recorders.write(p);
    ++n;
  });
  stream.start();
  // Polled with a deadline: each wait ends as soon as its condition holds.
  for (auto end = std::chrono::steady_clock::now() + 10s;
       !stream.connected() && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  ASSERT_TRUE(stream.connected()) << "the stream did not open " << pty.slave_path();
  ASSERT_TRUE(write_fully(pty.master(), wire));
  for (auto end = std::chrono::steady_clock::now() + 30s;
       n < sent.size() && std::chrono::steady_clock::now() < end;)
    std::this_thread::sleep_for(5ms);
  ASSERT_EQ(n, sent.size());

  // The data endpoint over HTTP.
  httplib::Client cli("127.0.0.1", live.port());
  auto res = cli.Get("/data.json");
  ASSERT_TRUE(res) << "GET /data.json failed";
  const auto d = nlohmann::json::parse(res->body);
  EXPECT_EQ(d["taxels"]["rows"], 3);
  EXPECT_EQ(d["taxels"]["cols"], 3);
  EXPECT_EQ(d["taxels"]["t"], last->t);
  EXPECT_EQ(d["taxels"]["values"].get<std::vector<int>>(), values);
  EXPECT_EQ(d["link"]["frames_ok"], sent.size());
  EXPECT_GT(d["spikes"].size(), 0u);
  EXPECT_EQ(d["amplitudes"].size(), 8575u / 35);  // one per 35 samples, all kept (< 500)

  // The page in headless Chromium.
  const fs::path dir = fs::temp_directory_path() / ("eskin_live_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string png = (dir / "live.png").string();
  const std::string cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu "
                          "--hide-scrollbars --force-device-scale-factor=1 "
                          "--window-size=1200,760 --virtual-time-budget=2000 --user-data-dir=" +
                          (dir / "profile").string() + " --screenshot=" + png + " " + live.url() + "?static" +
                          " > " + (dir / "chromium.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << (dir / "chromium.log");
  int w = 0, h = 0;
  std::vector<uint8_t> rgb;
  ASSERT_TRUE(read_png(png, w, h, rgb)) << png;
  ASSERT_EQ(w, 1200);
  ASSERT_EQ(h, 760);
  const auto at = [&](int row, int col) {  // centre of the heatmap cell
    const size_t i = (size_t(60 + 60 * row + 30) * size_t(w) + size_t(20 + 60 * col + 30)) * 3;
    return Rgb{rgb[i], rgb[i + 1], rgb[i + 2]};
  };
  // Colour at value fraction f: (20 + 210 f, 40 - 10 f, 160 - 130 f).
  const Rgb hot = at(1, 2);
  EXPECT_GE(hot.r, 225) << "pressed taxel's cell is not red: " << hot.r << "," << hot.g << "," << hot.b;
  EXPECT_LE(hot.b, 35);
  const int max = values[5];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      if (r == 1 && c == 2) continue;
      const Rgb px = at(r, c);
      const double f = double(values[size_t(r * 3 + c)]) / max;
      // Canvas colours are exact to +-1 from rounding; the ramp is linear.
      EXPECT_NEAR(px.r, 20 + 210 * f, 2) << r << "," << c;
      EXPECT_NEAR(px.b, 160 - 130 * f, 2) << r << "," << c;
      EXPECT_LT(px.r, hot.r - 20) << "(" << r << "," << c << ") drawn as hot as the pressed taxel";
      // Taxels sharing neither the pressed row nor its column see no
      // carrier of the press (only leakage): they stay blue.
      if (r != 1 && c != 2) {
        EXPECT_GT(px.b, px.r) << "(" << r << "," << c << ") drawn hot";
      }
    }
  // The colour bar beside the map (live_view_page.h): the ramp's top (red,
  // the maximum) and bottom (blue, 0), same ramp as the cells, +-2.
  const auto px = [&](int x, int y) {
    const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 3;
    return Rgb{rgb[i], rgb[i + 1], rgb[i + 2]};
  };
  using G = eskin::stream::LiveViewGeometry;
  const int bx = G::bar_x(3) + G::kBarWidth / 2;
  const Rgb bar_top = px(bx, G::kHeatY + 1), bar_bottom = px(bx, G::kHeatY + 3 * G::kCell - 2);
  EXPECT_NEAR(bar_top.r, 230, 2) << "colour bar top";
  EXPECT_NEAR(bar_top.b, 30, 2) << "colour bar top";
  EXPECT_NEAR(bar_bottom.r, 20, 2) << "colour bar bottom";
  EXPECT_NEAR(bar_bottom.b, 160, 2) << "colour bar bottom";

  // The page's text after its scripts ran: the bar's scale and unit, the
  // link's health with every error count (0 here: a clean pty).
  const std::string dom_file = (dir / "dom.html").string();
  const std::string dom_cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu "
                              "--virtual-time-budget=2000 --user-data-dir=" +
                              (dir / "profile").string() + " --dump-dom " + live.url() + "?static > " +
                              dom_file + " 2>/dev/null";
  ASSERT_EQ(std::system(dom_cmd.c_str()), 0) << dom_cmd;
  const std::string full = slurp(dom_file);
  // The page's text without the inlined chart library (for the messages).
  const size_t lib = full.find("<script>"), lib_end = full.find("</script>", lib);
  const std::string dom = lib == std::string::npos || lib_end == std::string::npos
                              ? full
                              : full.substr(0, lib) + full.substr(lib_end);
  const auto text_of = [&](const std::string& id) {  // a div's text, its style attribute aside
    const size_t at = dom.find("<div id=\"" + id + "\"");
    if (at == std::string::npos) return std::string("(no #" + id + ")");
    const size_t open = dom.find('>', at) + 1;
    return dom.substr(open, dom.find("</div>", open) - open);
  };
  EXPECT_EQ(text_of("barmax"), std::to_string(max) + " code");
  EXPECT_EQ(text_of("barmin"), "0 code");
  EXPECT_NE(dom.find("link: " + std::to_string(sent.size()) +
                     " packets, framing errors 0, CRC errors 0, payload errors 0, sequence gaps 0, "
                     "lost packets 0"),
            std::string::npos)
      << dom;
  EXPECT_NE(dom.find("<option>set-mask</option>"), std::string::npos) << "command form\n" << dom;
  stream.stop();
  fs::remove_all(dir);
}

// With the scene (eskin stream --live --scene): taxels in kPa through its
// conductance curve, g = p / (p + 50 kPa) for scenes/neuroskin2.yaml, so
// p = 50 g / (1 - g) with g = code / 32768 (UQ1.15); carriers named by row
// or column and frequency (the scene's 1900 ... 10000 Hz).
TEST(LiveView, WithTheSceneTaxelsAreInKpaAndCarriersNamedByFrequency) {
  const auto sc = eskin::sim::load_scene(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  eskin::stream::LiveView live("127.0.0.1", 0);
  live.set_carrier_labels(sc.skin.carrier_labels());
  live.set_taxel_unit("kPa", [skin = sc.skin](int64_t c) { return skin.conductance.inverse(c / 32768.0); });
  eskin::stream::RecorderSet recorders;
  recorders.add(&live);
  eskin::link::LinkEncoder enc;
  eskin::link::LinkDecoder dec;
  dec.on_packet([&](const eskin::link::Packet& p) { recorders.write(p); });
  const std::vector<uint16_t> codes = {0, 1000, 4096, 8192, 16384, 20000, 24576, 100, 10};
  dec.feed(enc.taxels_dense(35, 3, 3, codes));
  const auto d = nlohmann::json::parse(live.data_json());
  EXPECT_EQ(d["taxels"]["unit"], "kPa");
  ASSERT_EQ(d["taxels"]["values_unit"].size(), codes.size());
  for (size_t i = 0; i < codes.size(); ++i) {
    const double g = codes[i] / 32768.0;
    EXPECT_NEAR(d["taxels"]["values_unit"][i].get<double>(), 50 * g / (1 - g), 1e-9) << i;
  }
  EXPECT_EQ(d["carriers"].get<std::vector<std::string>>(),
            (std::vector<std::string>{"row 0 \u00b7 1900 Hz", "row 1 \u00b7 3300 Hz",
                                      "row 2 \u00b7 5000 Hz", "col 0 \u00b7 7140 Hz",
                                      "col 1 \u00b7 8300 Hz", "col 2 \u00b7 10000 Hz"}));
}

// The command form's route: POST /command hands the body to the handler
// (the stream's ControlServer::handle) and returns its reply unchanged;
// 503 with none, 400 for a body that is not JSON; /commands.json is
// host/stream/commands.h's list.
TEST(LiveView, CommandRoutePassesRequestsToTheHandler) {
  eskin::stream::LiveView live("127.0.0.1", 0);
  httplib::Client cli("127.0.0.1", live.port());
  const std::string req = R"({"command":"set-mask","args":["0x7"]})";
  auto none = cli.Post("/command", req, "application/json");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 503);
  EXPECT_FALSE(nlohmann::json::parse(none->body)["ok"].get<bool>());
  std::vector<std::string> got;
  live.set_command_handler([&](const std::string& body) {
    got.push_back(body);
    return std::string(R"({"ok":true,"ack":"accepted","message":"accepted"})");
  });
  auto bad = cli.Post("/command", "set-mask 0x7", "text/plain");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_TRUE(got.empty()) << "a body that is not JSON reached the handler";
  auto ok = cli.Post("/command", req, "application/json");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_EQ(ok->body, R"({"ok":true,"ack":"accepted","message":"accepted"})");
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], req);
  auto list = cli.Get("/commands.json");
  ASSERT_TRUE(list);
  const auto cmds = nlohmann::json::parse(list->body);
  ASSERT_EQ(cmds.size(), eskin::stream::command_specs().size());
  bool mask = false;
  for (const auto& c : cmds)
    if (c["name"] == "set-mask") mask = c["args"].size() == 1;
  EXPECT_TRUE(mask) << list->body;
}

// Sparse taxel frames (docs/protocol.md §4, mask bit 4) in the heatmap's
// data: a sparse frame replaces the map (so an empty one clears it); a
// sparse packet of a frame whose dense packet came first changes nothing.
TEST(LiveView, SparseFramesReplaceTheMapAndEmptyOnesClearIt) {
  eskin::stream::LiveView live("127.0.0.1", 0);
  eskin::stream::RecorderSet recorders;
  recorders.add(&live);
  eskin::link::LinkEncoder enc;
  eskin::link::LinkDecoder dec;
  dec.on_packet([&](const eskin::link::Packet& p) { recorders.write(p); });
  const auto taxels = [&] { return nlohmann::json::parse(live.data_json())["taxels"]; };
  const std::vector<uint16_t> dense = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  dec.feed(enc.taxels_dense(35, 3, 3, dense));
  dec.feed(enc.taxels_sparse(35, {{0, 0, 999}}));
  EXPECT_EQ(taxels()["values"].get<std::vector<int>>(), std::vector<int>(dense.begin(), dense.end()));
  dec.feed(enc.taxels_sparse(70, {{2, 1, 500}, {0, 2, 40}}));
  EXPECT_EQ(taxels()["t"], 70);
  EXPECT_EQ(taxels()["values"].get<std::vector<int>>(), (std::vector<int>{0, 0, 40, 0, 0, 0, 0, 500, 0}));
  dec.feed(enc.taxels_sparse(105, {}));
  EXPECT_EQ(taxels()["t"], 105);
  EXPECT_EQ(taxels()["values"].get<std::vector<int>>(), std::vector<int>(9, 0));
  dec.feed(enc.spikes(140, {{3, 0, 4}, {5, 1, 7}}));
  const auto spikes = nlohmann::json::parse(live.data_json())["spikes"];
  ASSERT_EQ(spikes.size(), 2u);
  EXPECT_EQ(spikes[1]["layer"], 1);
  EXPECT_EQ(spikes[1]["neuron"], 7);
  EXPECT_EQ(spikes[1]["t"], 145);
  EXPECT_EQ(dec.stats().frames_ok, 5u);
}

}  // namespace
