#include "host/link/hall_packets.h"

#include "host/link/link_encoder.h"

namespace eskin::link {
namespace {

uint16_t g16(const uint8_t* p) { return uint16_t(p[0] | (p[1] << 8)); }
uint32_t g32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
void p16(std::vector<uint8_t>& v, uint16_t x) { v.push_back(uint8_t(x)), v.push_back(uint8_t(x >> 8)); }
void p32(std::vector<uint8_t>& v, uint32_t x) {
  for (int i = 0; i < 4; ++i) v.push_back(uint8_t(x >> (8 * i)));
}
bool bad(std::string* why, const char* msg) {
  if (why) *why = msg;
  return false;
}

}  // namespace

bool parse_hall_payload(uint8_t type, const std::vector<uint8_t>& b, HallPayload& h, bool& known,
                        std::string* why) {
  const size_t n = b.size();
  known = true;
  switch (type) {
    case kHallDeltas:
      if (n % 10) return bad(why, "hall deltas: payload length must be a multiple of 10");
      for (size_t i = 0; i < n; i += 10)
        h.deltas.push_back({b[i], b[i + 1], g16(&b[i + 2]), int16_t(g16(&b[i + 4])), int16_t(g16(&b[i + 6])),
                            int16_t(g16(&b[i + 8]))});
      return true;
    case kHallDecouple3:
      if (n != 14) return bad(why, "decouple3: payload length must be 14");
      h.decouple = {int32_t(g32(&b[0])), int32_t(g32(&b[4])), int32_t(g32(&b[8])), b[12], b[13]};
      if (h.decouple.valid > 1) return bad(why, "decouple3: valid must be 0 or 1");
      return true;
    case kHallWrench6:
      if (n != 25) return bad(why, "wrench6: payload length must be 25");
      for (int i = 0; i < 6; ++i) h.wrench.w[i] = int32_t(g32(&b[size_t(4 * i)]));
      h.wrench.flags = b[24];
      return true;
    case kHallForceCurve:
      if (n % 11) return bad(why, "force curve: payload length must be a multiple of 11");
      for (size_t i = 0; i < n; i += 11)
        h.forces.push_back({b[i], b[i + 1], b[i + 2], g32(&b[i + 3]), int32_t(g32(&b[i + 7]))});
      return true;
    case kHallDecodeStatus:
      if (n != 17) return bad(why, "hall decode status: payload length must be 17");
      h.status = {g16(&b[0]), g16(&b[2]), g16(&b[4]), g16(&b[6]), g16(&b[8]), g16(&b[10]),
                  g16(&b[12]), b[14], b[15], b[16]};
      return true;
    case kCmdHallLoadC:
      if (n != 6) return bad(why, "hall_load_c: payload length must be 6");
      h.cmd.index = b[0], h.cmd.sub = b[1], h.cmd.value = int32_t(g32(&b[2]));
      return true;
    case kCmdHallSetBaseline:
      if (n != 4) return bad(why, "hall_set_baseline: payload length must be 4");
      h.cmd.index = b[0], h.cmd.sub = b[1], h.cmd.value = int16_t(g16(&b[2]));
      return true;
    case kCmdHallRecapture:
      if (n != 0) return bad(why, "hall_recapture: payload must be empty");
      return true;
    case kCmdHallLoadCurve:
      if (n != 7) return bad(why, "hall_load_curve: payload length must be 7");
      h.cmd.index = b[0], h.cmd.sub = b[1], h.cmd.which = b[2], h.cmd.value = int32_t(g32(&b[3]));
      return true;
    case kCmdHallSetDecouple:
      if (n != 12) return bad(why, "hall_set_decouple: payload length must be 12");
      h.cmd.k1 = int16_t(g16(&b[0])), h.cmd.c1 = int32_t(g32(&b[2]));
      h.cmd.k2 = int16_t(g16(&b[6])), h.cmd.c2 = int32_t(g32(&b[8]));
      return true;
    default:
      known = false;
      return false;
  }
}

std::vector<uint8_t> hall_deltas(LinkEncoder& e, uint32_t t, const std::vector<HallDeltaRecord>& s) {
  std::vector<uint8_t> p;
  for (const auto& r : s) {
    p.push_back(r.id), p.push_back(r.flags);
    p16(p, r.t16), p16(p, uint16_t(r.dx)), p16(p, uint16_t(r.dy)), p16(p, uint16_t(r.dz));
  }
  return e.frame(kHallDeltas, t, p);
}

std::vector<uint8_t> hall_decouple3(LinkEncoder& e, uint32_t t, const DecoupleRecord& d) {
  std::vector<uint8_t> p;
  p32(p, uint32_t(d.rx)), p32(p, uint32_t(d.ry)), p32(p, uint32_t(d.sz));
  p.push_back(d.valid), p.push_back(d.flags);
  return e.frame(kHallDecouple3, t, p);
}

std::vector<uint8_t> hall_wrench6(LinkEncoder& e, uint32_t t, const WrenchRecord& w) {
  std::vector<uint8_t> p;
  for (int32_t v : w.w) p32(p, uint32_t(v));
  p.push_back(w.flags);
  return e.frame(kHallWrench6, t, p);
}

std::vector<uint8_t> hall_force_curve(LinkEncoder& e, uint32_t t, const std::vector<ForceRecord>& f) {
  std::vector<uint8_t> p;
  for (const auto& r : f) {
    p.push_back(r.cell), p.push_back(r.range), p.push_back(r.flags);
    p32(p, r.t), p32(p, uint32_t(r.force_mn));
  }
  return e.frame(kHallForceCurve, t, p);
}

std::vector<uint8_t> hall_decode_status(LinkEncoder& e, uint32_t t, const HallDecodeStatus& s) {
  std::vector<uint8_t> p;
  for (uint16_t v : {s.baseline_dropped, s.ft_skipped, s.cmd_accepted, s.cmd_rejected,
                     s.cmd_crc_errors, s.cmd_frame_errors, s.cmd_overflows})
    p16(p, v);
  p.push_back(s.last_reject_type), p.push_back(s.last_reject_reason), p.push_back(s.last_reject_seq);
  return e.frame(kHallDecodeStatus, t, p);
}

std::vector<uint8_t> hall_load_c(LinkEncoder& e, uint8_t row, uint8_t col, int32_t value) {
  std::vector<uint8_t> p{row, col};
  p32(p, uint32_t(value));
  return e.frame(kCmdHallLoadC, 0, p);
}

std::vector<uint8_t> hall_set_baseline(LinkEncoder& e, uint8_t sensor, uint8_t axis, int16_t value) {
  std::vector<uint8_t> p{sensor, axis};
  p16(p, uint16_t(value));
  return e.frame(kCmdHallSetBaseline, 0, p);
}

std::vector<uint8_t> hall_recapture(LinkEncoder& e) { return e.frame(kCmdHallRecapture, 0, {}); }

std::vector<uint8_t> hall_load_curve(LinkEncoder& e, uint8_t cell, uint8_t index, uint8_t which, int32_t value) {
  std::vector<uint8_t> p{cell, index, which};
  p32(p, uint32_t(value));
  return e.frame(kCmdHallLoadCurve, 0, p);
}

std::vector<uint8_t> hall_set_decouple(LinkEncoder& e, int16_t k1, int32_t c1, int16_t k2, int32_t c2) {
  std::vector<uint8_t> p;
  p16(p, uint16_t(k1)), p32(p, uint32_t(c1)), p16(p, uint16_t(k2)), p32(p, uint32_t(c2));
  return e.frame(kCmdHallSetDecouple, 0, p);
}

}  // namespace eskin::link
