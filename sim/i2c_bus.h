// Open-drain I2C bus model for Verilator benches and device-model tests.
//
// Electrical model: every participant (the FPGA master's pins, each device
// model) only pulls SCL/SDA low or releases them; a line is low while anyone
// pulls it (wired-AND, falls at once) and, after the last release, rises
// through the pull-up R and the bus capacitance C: it crosses 30 % of VDD
// 0.357 RC and 70 % (VIH) 1.204 RC after the release. Receivers see the
// logic level (high from the 70 % crossing on).
//
// Segments: segment 0 is the master's bus. A TCA9548A model joins further
// segments (its channels) to it with connect(); a joined segment is one net
// with segment 0, an unjoined one is a net of its own (idle high).
//
// Checks (UM10204 fast-mode or standard-mode limits, measured at the 30 %/
// 70 % points the spec uses), on segment 0, each violation recorded with the
// parameter's name: fSCL, tLOW, tHIGH, tSU;STA (repeated START), tHD;STA,
// tSU;DAT, tHD;DAT, tSU;STO, tBUF, and the pull-up's rise time tr. Clock
// stretching (someone other than the releasing master holding SCL low) is
// allowed and counted.
//
// Time is in ns and never goes back. Drives may be scheduled in the future
// (a device's output delay); advance_to(t) applies everything up to t in
// time order and tells the listeners (devices) about START, STOP and SCL
// edges on their segment.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace eskin::sim {

struct I2cTiming {  // ns, UM10204 Table 10 (tr is a maximum, the rest minima)
  const char* mode;
  double t_scl_min;  // 1 / fSCL max
  double t_low, t_high, t_su_sta, t_hd_sta, t_su_dat, t_hd_dat, t_su_sto, t_buf;
  double t_r_max;
  static I2cTiming fast() {
    return {"fast-mode", 2500, 1300, 600, 600, 600, 100, 0, 600, 1300, 300};
  }
  static I2cTiming standard() {
    return {"standard-mode", 10000, 4700, 4000, 4700, 4000, 250, 0, 4000, 4700, 1000};
  }
};

// A device on the bus. Events arrive in time order at the logic-level
// transitions of its segment's net.
class I2cListener {
 public:
  virtual ~I2cListener() = default;
  virtual void on_start(double t) = 0;  // START or repeated START
  virtual void on_stop(double t) = 0;
  virtual void on_scl_rise(double t, bool sda) = 0;  // sda: level at the rise
  virtual void on_scl_fall(double t) = 0;
  // Called by advance_to() for internal time (conversions, DRDY), after the
  // bus events up to t.
  virtual void advance(double /*t*/) {}
};

class I2cBus {
 public:
  static constexpr double kNever = -std::numeric_limits<double>::infinity();
  static constexpr double kNoRise = std::numeric_limits<double>::infinity();

  explicit I2cBus(I2cTiming timing = I2cTiming::fast(), double pullup_ohm = 2200.0,
                  double cap_pf = 100.0);

  int add_segment();                      // a further net (mux channel)
  void connect(int segment, bool joined); // join/split a segment with segment 0
  // A participant that may pull the lines low; returns its id.
  int attach(const std::string& name, int segment = 0, I2cListener* listener = nullptr);

  // From time t on, participant `id` pulls SCL / SDA low (true) or releases.
  void drive(int id, double t, bool scl_low, bool sda_low);
  void drive_sda(int id, double t, bool low);
  void drive_scl(int id, double t, bool low);
  void advance_to(double t);
  double now() const { return now_; }

  bool scl(int segment = 0) const { return seg_[segment].level[0]; }
  bool sda(int segment = 0) const { return seg_[segment].level[1]; }

  const I2cTiming& timing() const { return tm_; }
  double rise_to_vih_ns() const { return 1.204 * rc_ns_; }
  const std::vector<std::string>& violations() const { return messages_; }
  size_t violation_count() const { return violation_count_; }
  // Counts of each violated parameter by name, e.g. {"tLOW", 3}.
  const std::map<std::string, size_t>& violated() const { return violated_; }
  size_t starts() const { return starts_; }
  size_t stops() const { return stops_; }
  size_t scl_pulses() const { return scl_rises_; }
  size_t stretches() const { return stretches_; }
  double max_stretch_ns() const { return max_stretch_; }

 private:
  struct Participant {
    std::string name;
    int segment;
    I2cListener* listener;
    bool low[2] = {false, false};  // 0 SCL, 1 SDA
  };
  struct Pending {
    double t;
    int id, line;
    bool low;
  };
  struct Segment {
    bool joined = false;
    bool level[2] = {true, true};
    double rise_at[2] = {kNoRise, kNoRise};  // scheduled VIH crossing
    double released_at[2] = {kNever, kNever};
    int last_releaser[2] = {-1, -1};
    double first_release[2] = {kNever, kNever};  // SCL: when the first puller let go
  };

  bool net_pulled(int segment, int line) const;
  void settle(double t);  // recompute levels after a change at t
  void line_changed(int segment, int line, bool level, double t);
  void check_edge(int line, bool level, double t);
  void violate(double t, const char* param, double value, const char* rel, double limit);

  I2cTiming tm_;
  double rc_ns_;
  double now_ = 0;
  std::vector<Participant> parts_;
  std::vector<Segment> seg_;
  std::vector<Pending> pending_;

  // checker state (segment 0)
  bool busy_ = false;
  double last_scl_fall_ = kNever, last_scl_rise_ = kNever;
  double last_sda_change_ = kNever, last_start_ = kNever, last_stop_ = kNever;
  bool start_since_fall_ = false, sda_changed_while_low_ = false;
  size_t starts_ = 0, stops_ = 0, scl_rises_ = 0, stretches_ = 0;
  double max_stretch_ = 0;
  std::vector<std::string> messages_;
  std::map<std::string, size_t> violated_;
  size_t violation_count_ = 0;
};

}  // namespace eskin::sim
