// Colours and sizes of the simulate report's carrier panels, shared by the
// page (simulate_report.cpp, html_page.cpp) and the test that reads its
// screenshot (tests/vboard/report_test.cpp): each carrier is a panel with
// a kPanelBorder frame, its FPGA amplitude drawn in kFpgaRgb on the left
// axis and FPGA - golden in kDiffRgb on the right axis. No Chart.js
// default colour is any of these.
#pragma once

namespace eskin::report {

struct Rgb8 {
  int r, g, b;
};

inline constexpr Rgb8 kPanelBorder{200, 210, 250};
inline constexpr Rgb8 kFpgaRgb{31, 119, 180};
inline constexpr Rgb8 kDiffRgb{230, 85, 13};
inline constexpr int kPanelBorderPx = 3;
inline constexpr int kPanelHeightPx = 200;
inline constexpr int kPanelColumns = 3;

}  // namespace eskin::report
