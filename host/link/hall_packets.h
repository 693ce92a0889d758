// Host-link packets of the Hall decoding chain (docs/protocol.md section
// 9): data 0x12..0x16 (FPGA -> host) and commands 0x98..0x9C (host -> FPGA);
// the raw readings (0x10) and bus counters (0x20) are section 8's. Parsed by the LinkDecoder into Packet::hall; built by the
// functions at the end for tests and for configuring the FPGA.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace eskin::link {

enum HallPacketType : uint8_t {
  kHallDeltas = 0x12,      // n x HallDeltaRecord: baseline-removed signed LSB
  kHallDecouple3 = 0x13,   // DecoupleRecord: seed-001 Rx, Ry, Sz
  kHallWrench6 = 0x14,     // WrenchRecord: seed-002 force/torque
  kHallForceCurve = 0x15,  // n x ForceRecord: seed-003 cell forces
  kHallDecodeStatus = 0x16,  // HallDecodeStatus
  kCmdHallLoadC = 0x98,        // row u8, col u8, value s32
  kCmdHallSetBaseline = 0x99,  // sensor u8, axis u8, value s16
  kCmdHallRecapture = 0x9A,    // no payload
  kCmdHallLoadCurve = 0x9B,    // cell u8, index u8, which u8, value s32
  kCmdHallSetDecouple = 0x9C,  // k1 s16, c1 s32, k2 s16, c2 s32
};

// The Hall top's packet types, 0x10..0x2F (docs/protocol.md section 4): on
// a mixed board's shared link (rtl/mixed_top.v) everything else is the
// DTMF top's.
constexpr bool is_hall_packet(uint8_t type) { return type >= 0x10 && type <= 0x2F; }

struct HallDeltaRecord {  // 10 bytes, HALL_SAMPLES' layout
  uint8_t id = 0, flags = 0;
  uint16_t t16 = 0;
  int16_t dx = 0, dy = 0, dz = 0;
};
struct DecoupleRecord {  // 14 bytes
  int32_t rx = 0, ry = 0, sz = 0;  // Q8.24 rad / ln(uT)
  uint8_t valid = 0, flags = 0;
};
struct WrenchRecord {  // 25 bytes
  int32_t w[6] = {0, 0, 0, 0, 0, 0};  // mN (Fx, Fy, Fz), mN*mm (Tx, Ty, Tz)
  uint8_t flags = 0;
};
struct ForceRecord {  // 11 bytes
  uint8_t cell = 0, range = 0, flags = 0;
  uint32_t t = 0;
  int32_t force_mn = 0;
};
struct HallDecodeStatus {  // 17 bytes: seven u16, then three u8
  uint16_t baseline_dropped = 0, ft_skipped = 0;      // the decoding blocks' counters
  uint16_t cmd_accepted = 0, cmd_rejected = 0;        // hall_cmd
  uint16_t cmd_crc_errors = 0, cmd_frame_errors = 0, cmd_overflows = 0;  // cmd_decoder
  uint8_t last_reject_type = 0, last_reject_reason = 0, last_reject_seq = 0;
};
struct HallCommand {
  uint8_t index = 0, sub = 0, which = 0;  // row/sensor/cell, col/axis/index, curve field
  int32_t value = 0;
  int16_t k1 = 0, k2 = 0;
  int32_t c1 = 0, c2 = 0;
};

struct HallPayload {
  std::vector<HallDeltaRecord> deltas;    // 0x12
  DecoupleRecord decouple;                // 0x13
  WrenchRecord wrench;                    // 0x14
  std::vector<ForceRecord> forces;        // 0x15
  HallDecodeStatus status;                // 0x16
  HallCommand cmd;                        // 0x98..0x9C
};

// Parses a Hall packet's payload; false (reason in *why) when it does not fit
// its type; `known` is set false for types that are not Hall packets.
bool parse_hall_payload(uint8_t type, const std::vector<uint8_t>& payload, HallPayload& out,
                        bool& known, std::string* why);

class LinkEncoder;
// Data packets as the FPGA sends them.
std::vector<uint8_t> hall_deltas(LinkEncoder& e, uint32_t t, const std::vector<HallDeltaRecord>& s);
std::vector<uint8_t> hall_decouple3(LinkEncoder& e, uint32_t t, const DecoupleRecord& d);
std::vector<uint8_t> hall_wrench6(LinkEncoder& e, uint32_t t, const WrenchRecord& w);
std::vector<uint8_t> hall_force_curve(LinkEncoder& e, uint32_t t, const std::vector<ForceRecord>& f);
std::vector<uint8_t> hall_decode_status(LinkEncoder& e, uint32_t t, const HallDecodeStatus& s);
// Commands.
std::vector<uint8_t> hall_load_c(LinkEncoder& e, uint8_t row, uint8_t col, int32_t value);
std::vector<uint8_t> hall_set_baseline(LinkEncoder& e, uint8_t sensor, uint8_t axis, int16_t value);
std::vector<uint8_t> hall_recapture(LinkEncoder& e);
std::vector<uint8_t> hall_load_curve(LinkEncoder& e, uint8_t cell, uint8_t index, uint8_t which, int32_t value);
std::vector<uint8_t> hall_set_decouple(LinkEncoder& e, int16_t k1, int32_t c1, int16_t k2, int32_t c2);

}  // namespace eskin::link
