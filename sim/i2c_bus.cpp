#include "sim/i2c_bus.h"

#include <cmath>
#include <cstdio>

namespace eskin::sim {

namespace {
constexpr int kScl = 0, kSda = 1;
// RC multiples of the 30 % and 70 % crossings of a rising RC edge.
constexpr double k30 = 0.357, k70 = 1.204;
}  // namespace

I2cBus::I2cBus(I2cTiming timing, double pullup_ohm, double cap_pf)
    : tm_(timing), rc_ns_(pullup_ohm * cap_pf * 1e-3) {
  seg_.emplace_back();
  const double tr = (k70 - k30) * rc_ns_;
  if (tr > tm_.t_r_max) violate(0, "tr (rise time 30-70 %, pull-up RC)", tr, ">", tm_.t_r_max);
}

int I2cBus::add_segment() {
  seg_.emplace_back();
  return int(seg_.size()) - 1;
}

void I2cBus::connect(int segment, bool joined) {
  if (segment <= 0 || seg_[segment].joined == joined) return;
  seg_[segment].joined = joined;
  settle(now_);
}

int I2cBus::attach(const std::string& name, int segment, I2cListener* listener) {
  parts_.push_back({name, segment, listener});
  return int(parts_.size()) - 1;
}

void I2cBus::drive(int id, double t, bool scl_low, bool sda_low) {
  drive_scl(id, t, scl_low);
  drive_sda(id, t, sda_low);
}
void I2cBus::drive_sda(int id, double t, bool low) {
  pending_.push_back({t, id, kSda, low});
  if (t <= now_) advance_to(now_);
}
void I2cBus::drive_scl(int id, double t, bool low) {
  pending_.push_back({t, id, kScl, low});
  if (t <= now_) advance_to(now_);
}

bool I2cBus::net_pulled(int segment, int line) const {
  const bool on_root = segment == 0 || seg_[segment].joined;
  for (const auto& p : parts_) {
    if (!p.low[line]) continue;
    if (p.segment == segment) return true;
    if (on_root && (p.segment == 0 || seg_[p.segment].joined)) return true;
  }
  return false;
}

void I2cBus::advance_to(double t) {
  if (t < now_) t = now_;
  for (;;) {
    // Earliest pending drive and earliest rise completion up to t; drives
    // first on a tie.
    int pi = -1;
    for (size_t i = 0; i < pending_.size(); ++i)
      if (pending_[i].t <= t && (pi < 0 || pending_[i].t < pending_[pi].t)) pi = int(i);
    int rs = -1, rl = -1;
    for (size_t s = 0; s < seg_.size(); ++s)
      for (int l = 0; l < 2; ++l)
        if (seg_[s].rise_at[l] <= t &&
            (rs < 0 || seg_[s].rise_at[l] < seg_[rs].rise_at[rl])) {
          rs = int(s);
          rl = l;
        }
    if (pi < 0 && rs < 0) break;
    if (pi >= 0 && (rs < 0 || pending_[pi].t <= seg_[rs].rise_at[rl])) {
      const Pending p = pending_[pi];
      pending_.erase(pending_.begin() + pi);
      now_ = p.t > now_ ? p.t : now_;
      Participant& who = parts_[p.id];
      if (who.low[p.line] == p.low) continue;
      who.low[p.line] = p.low;
      if (!p.low) {
        Segment& sg = seg_[who.segment];
        sg.last_releaser[p.line] = p.id;
        if (sg.first_release[p.line] == kNever) sg.first_release[p.line] = now_;
      }
      settle(now_);
    } else {
      Segment& sg = seg_[rs];
      now_ = sg.rise_at[rl];
      sg.rise_at[rl] = kNoRise;
      sg.level[rl] = true;
      line_changed(rs, rl, true, now_);
    }
  }
  now_ = t;
  for (auto& p : parts_)
    if (p.listener) p.listener->advance(t);
}

void I2cBus::settle(double t) {
  for (size_t s = 0; s < seg_.size(); ++s) {
    Segment& sg = seg_[s];
    for (int l = 0; l < 2; ++l) {
      if (net_pulled(int(s), l)) {
        sg.rise_at[l] = kNoRise;
        if (sg.level[l]) {
          sg.level[l] = false;
          sg.first_release[l] = kNever;
          line_changed(int(s), l, false, t);
        }
      } else if (!sg.level[l] && sg.rise_at[l] == kNoRise) {
        // Last puller let go: the pull-up takes the line to VIH.
        sg.rise_at[l] = t + k70 * rc_ns_;
        sg.released_at[l] = t;
        if (s == 0 && l == kScl && sg.first_release[l] != kNever && t > sg.first_release[l]) {
          ++stretches_;  // someone held SCL after the first release
          if (t - sg.first_release[l] > max_stretch_) max_stretch_ = t - sg.first_release[l];
        }
        sg.first_release[l] = kNever;
      }
    }
  }
}

void I2cBus::line_changed(int segment, int line, bool level, double t) {
  if (segment == 0) check_edge(line, level, t);
  const Segment& sg = seg_[segment];
  for (auto& p : parts_) {
    if (!p.listener || p.segment != segment) continue;
    if (line == kScl) {
      if (level) p.listener->on_scl_rise(t, sg.level[kSda]);
      else p.listener->on_scl_fall(t);
    } else if (sg.level[kScl]) {
      if (level) p.listener->on_stop(t);
      else p.listener->on_start(t);
    }
  }
}

void I2cBus::check_edge(int line, bool level, double t) {
  const Segment& sg = seg_[0];
  const double t30 = t - (k70 - k30) * rc_ns_;  // 30 % point of a rising edge
  if (line == kScl && level) {
    ++scl_rises_;
    if (last_scl_fall_ != kNever && t30 - last_scl_fall_ < tm_.t_low)
      violate(t, "tLOW (SCL low period)", t30 - last_scl_fall_, "<", tm_.t_low);
    if (busy_ && sda_changed_while_low_ && t30 - last_sda_change_ < tm_.t_su_dat)
      violate(t, "tSU;DAT (data setup)", t30 - last_sda_change_, "<", tm_.t_su_dat);
    if (last_scl_rise_ != kNever && last_scl_rise_ > last_start_ &&
        t - last_scl_rise_ < tm_.t_scl_min)
      violate(t, "fSCL (SCL clock period)", t - last_scl_rise_, "<", tm_.t_scl_min);
    last_scl_rise_ = t;
  } else if (line == kScl) {
    if (last_scl_rise_ != kNever && t - last_scl_rise_ < tm_.t_high)
      violate(t, "tHIGH (SCL high period)", t - last_scl_rise_, "<", tm_.t_high);
    if (start_since_fall_ && t - last_start_ < tm_.t_hd_sta)
      violate(t, "tHD;STA (START hold)", t - last_start_, "<", tm_.t_hd_sta);
    start_since_fall_ = false;
    last_scl_fall_ = t;
    sda_changed_while_low_ = false;
  } else if (sg.level[kScl]) {  // SDA changes while SCL is high
    if (!level) {
      if (busy_ && t - last_scl_rise_ < tm_.t_su_sta)
        violate(t, "tSU;STA (repeated START setup)", t - last_scl_rise_, "<", tm_.t_su_sta);
      if (!busy_ && last_stop_ != kNever && t - last_stop_ < tm_.t_buf)
        violate(t, "tBUF (bus free between STOP and START)", t - last_stop_, "<", tm_.t_buf);
      busy_ = true;
      ++starts_;
      last_start_ = t;
      start_since_fall_ = true;
    } else {
      if (last_scl_rise_ != kNever && t30 - last_scl_rise_ < tm_.t_su_sto)
        violate(t, "tSU;STO (STOP setup)", t30 - last_scl_rise_, "<", tm_.t_su_sto);
      busy_ = false;
      ++stops_;
      last_stop_ = t;
    }
  } else {  // SDA changes while SCL is low: data
    const double at = level ? t30 : t;
    if (busy_ && last_scl_fall_ != kNever && at - last_scl_fall_ < tm_.t_hd_dat)
      violate(t, "tHD;DAT (data hold)", at - last_scl_fall_, "<", tm_.t_hd_dat);
    sda_changed_while_low_ = true;
    last_sda_change_ = t;
  }
}

void I2cBus::violate(double t, const char* param, double value, const char* rel, double limit) {
  // A value at the limit within 0.01 ns passes: simulated times are sums of
  // clock periods (83.33.. ns) in floating point.
  if (std::fabs(value - limit) < 0.01) return;
  ++violation_count_;
  const std::string p(param);
  ++violated_[p.substr(0, p.find(' '))];
  if (messages_.size() >= 50) return;
  char buf[240];
  std::snprintf(buf, sizeof buf, "%s = %.1f ns %s %.1f ns (%s, at t = %.1f ns)", param, value, rel,
                limit, tm_.mode, t);
  messages_.push_back(buf);
}

}  // namespace eskin::sim
