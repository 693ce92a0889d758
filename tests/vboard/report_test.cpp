// The `eskin simulate` report as a person sees it: round axis ticks, and a
// carrier chart where every series shows. A real run of a one-press scene
// on the virtual board, its report.html rendered by headless Chromium
// (Debian's chromium), the screenshot decoded with libpng.
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "host/report/html_page.h"
#include "host/report/report_style.h"
#include "run_command.h"

namespace {

namespace fs = std::filesystem;
using eskin::report::Rgb8;
using vboard_test::run;
using vboard_test::slurp;

// Steps of 1, 2 or 5 x 10^k inside [lo, hi], at most max_ticks of them;
// the expected lists are written out by hand.
TEST(ReportTicks, RoundStepsInsideTheRange) {
  using eskin::report::round_ticks;
  EXPECT_EQ(round_ticks(0.89, 600.89, 6), (std::vector<double>{100, 200, 300, 400, 500, 600}));
  EXPECT_EQ(round_ticks(0, 600, 6), (std::vector<double>{0, 200, 400, 600}));
  EXPECT_EQ(round_ticks(0.89, 120.89, 6), (std::vector<double>{20, 40, 60, 80, 100, 120}));
  EXPECT_EQ(round_ticks(0, 1, 5), (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(round_ticks(-3, 3, 7), (std::vector<double>{-3, -2, -1, 0, 1, 2, 3}));
  EXPECT_EQ(round_ticks(10.2, 49.7, 4), (std::vector<double>{20, 30, 40}));
  EXPECT_EQ(round_ticks(5, 5, 6), (std::vector<double>{5}));  // no range: the one value
}

struct Image {
  int w = 0, h = 0;
  std::vector<uint8_t> rgb;
  Rgb8 at(int x, int y) const {
    const size_t i = (size_t(y) * size_t(w) + size_t(x)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

bool read_png(const std::string& path, Image& im) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) return false;
  img.format = PNG_FORMAT_RGB;
  im.rgb.resize(PNG_IMAGE_SIZE(img));
  im.w = int(img.width), im.h = int(img.height);
  return png_image_finish_read(&img, nullptr, im.rgb.data(), 0, nullptr) != 0;
}

bool same(Rgb8 a, Rgb8 b, int tol) {
  return std::abs(a.r - b.r) <= tol && std::abs(a.g - b.g) <= tol && std::abs(a.b - b.b) <= tol;
}

struct Box {
  int x0, y0, x1, y1;  // the frame's outer edges, inclusive
};

// The carrier panels: rectangles framed in kPanelBorder. A top edge is a
// long run of the frame colour with no frame colour above it; its panel
// ends at the first row below where the run's left end is not the frame.
std::vector<Box> find_panels(const Image& im) {
  std::vector<Box> boxes;
  const Rgb8 frame = eskin::report::kPanelBorder;
  for (int y = 1; y < im.h; ++y)
    for (int x = 0; x < im.w;) {
      if (!same(im.at(x, y), frame, 0) || same(im.at(x, y - 1), frame, 0)) {
        ++x;
        continue;
      }
      int x1 = x;
      while (x1 + 1 < im.w && same(im.at(x1 + 1, y), frame, 0)) ++x1;
      if (x1 - x >= 200) {
        int y1 = y;
        while (y1 + 1 < im.h && same(im.at(x, y1 + 1), frame, 0)) ++y1;
        if (y1 - y >= 100) boxes.push_back({x, y, x1, y1});
      }
      x = x1 + 1;
    }
  return boxes;
}

// One 50 kPa press of taxel (1, 2) in the default scene's skin.
fs::path one_press_scene(const fs::path& dir) {
  std::string text = slurp(ESKIN_SOURCE_DIR "/scenes/neuroskin2.yaml");
  text.replace(text.find("duration_s: 0.6"), 15, "duration_s: 0.05");
  text.erase(text.find("stimuli:"));
  text += "stimuli:\n  - press: {taxel: [1, 2], pressure_kpa: 50, t_start_s: 0.010, ramp_s: 0.005, "
          "hold_s: 0.020, release_s: 0.005}\noutputs: [amplitudes, taxels, spikes]\n";
  const fs::path p = dir / "report_press.yaml";
  std::ofstream(p) << text;
  return p;
}

// Every carrier has its panel, titled by row/column and frequency, and in
// each panel's plot area (the frame less its title and legend above, its
// axes' labels left and right) both the FPGA's line (kFpgaRgb) and the
// FPGA - golden line (kDiffRgb) have pixels: at least 150 each. Each line
// is 2 px wide across a plot area over 200 px wide, so a whole line gives
// 400 or more (406..899 measured); the legend's swatches and the tick labels
// in those colours lie outside the counted area. Colours within 12 per
// channel: Chart.js antialiases the lines' edges.
TEST(Report, EveryCarrierPanelShowsTheFpgaAndTheDifference) {
  const fs::path dir = fs::temp_directory_path() / ("eskin_report_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string log;
  ASSERT_EQ(run(std::string(ESKIN_BIN) + " simulate " + one_press_scene(dir).string() + " --out " +
                    (dir / "out").string(), &log), 0)
      << log;
  const std::string html = slurp(dir / "out/report.html");
  for (const char* label : {"row 0 \u00b7 1900 Hz", "row 1 \u00b7 3300 Hz", "row 2 \u00b7 5000 Hz",
                            "col 0 \u00b7 7140 Hz", "col 1 \u00b7 8300 Hz", "col 2 \u00b7 10000 Hz"})
    EXPECT_NE(html.find(label), std::string::npos) << "no panel titled " << label;

  const std::string png = (dir / "report.png").string();
  const std::string cmd = "timeout 120 chromium --headless --no-sandbox --disable-gpu "
                          "--hide-scrollbars --force-device-scale-factor=1 "
                          "--window-size=1200,3200 --virtual-time-budget=3000 --user-data-dir=" +
                          (dir / "profile").string() + " --screenshot=" + png + " file://" +
                          (dir / "out/report.html").string() + " > " +
                          (dir / "chromium.log").string() + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  Image im;
  ASSERT_TRUE(read_png(png, im)) << png;
  const std::vector<Box> panels = find_panels(im);
  ASSERT_EQ(panels.size(), 6u) << "carrier panels found in " << png;
  for (size_t k = 0; k < panels.size(); ++k) {
    const Box& b = panels[k];
    int fpga = 0, diff = 0;
    for (int y = b.y0 + 60; y < b.y1 - 30; ++y)
      for (int x = b.x0 + 80; x < b.x1 - 80; ++x) {
        fpga += same(im.at(x, y), eskin::report::kFpgaRgb, 12);
        diff += same(im.at(x, y), eskin::report::kDiffRgb, 12);
      }
    EXPECT_GE(fpga, 150) << "panel " << k << " (" << b.x0 << "," << b.y0 << "): FPGA line missing (" << fpga << " px)";
    EXPECT_GE(diff, 150) << "panel " << k << " (" << b.x0 << "," << b.y0 << "): difference missing (" << diff << " px)";
  }
  fs::remove_all(dir);
}

}  // namespace
