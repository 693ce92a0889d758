// The DTMF top's commands (docs/protocol.md section 5): each one's type,
// name and payload, the one definition. The microcode's length table
// (ucode/dtmf_engine_image.h, KC_CLEN), the host link's encoder and decoder
// (host/link) and the payload column of docs/protocol.md's command table
// (checked by DtmfCommands.ProtocolTableIsTheDefinition) all come from here.
//
// Every field is little-endian. A command is checked in one order, for
// every type: type, payload length, index (the first field), value; the
// first check it fails is its reject reason.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace eskin {

namespace dtmf_cmd {  // the types (host/link's PacketType takes its kCmd* from these)
enum Type : uint8_t {
  kSetCarrierInc = 0x81,
  kSetThreshold = 0x82,
  kSetNeuron = 0x83,
  kSetOutputMask = 0x84,
  kSetDecimation = 0x85,
  kRequestStatus = 0x86,
  kClearCounters = 0x87,
  kSetWeight = 0x88,
  kSetDemixCoef = 0x89,
};
}  // namespace dtmf_cmd

struct CommandField {
  const char* name = nullptr;
  uint8_t bytes = 0;  // 1, 2 or 4
  bool is_signed = false;
};

struct DtmfCommand {
  dtmf_cmd::Type type;
  const char* name;
  CommandField index, value;  // an unused field has no name (0 bytes)

  constexpr int payload_bytes() const { return index.bytes + value.bytes; }
};

// In type order, from 0x81 without a gap (the microcode indexes its length
// table by type - 0x81).
inline constexpr DtmfCommand kDtmfCommands[] = {
    {dtmf_cmd::kSetCarrierInc, "SET_CARRIER_INC", {"k", 1, false}, {"inc", 4, false}},
    {dtmf_cmd::kSetThreshold, "SET_THRESHOLD", {"id", 1, false}, {"value", 2, false}},
    {dtmf_cmd::kSetNeuron, "SET_NEURON", {"id", 1, false}, {"value", 4, true}},
    {dtmf_cmd::kSetOutputMask, "SET_OUTPUT_MASK", {}, {"mask", 1, false}},
    {dtmf_cmd::kSetDecimation, "SET_DECIMATION", {"stream", 1, false}, {"d", 2, false}},
    {dtmf_cmd::kRequestStatus, "REQUEST_STATUS", {}, {}},
    {dtmf_cmd::kClearCounters, "CLEAR_COUNTERS", {}, {}},
    {dtmf_cmd::kSetWeight, "SET_WEIGHT", {"id", 1, false}, {"value", 2, true}},
    {dtmf_cmd::kSetDemixCoef, "SET_DEMIX_COEF", {"index", 2, false}, {"value", 2, true}},
};
inline constexpr int kDtmfCommandCount = int(sizeof kDtmfCommands / sizeof kDtmfCommands[0]);
inline constexpr uint8_t kDtmfCommandFirst = dtmf_cmd::kSetCarrierInc;

constexpr bool dtmf_commands_in_type_order() {
  for (int i = 0; i < kDtmfCommandCount; ++i)
    if (kDtmfCommands[i].type != kDtmfCommandFirst + i) return false;
  return true;
}
static_assert(dtmf_commands_in_type_order(), "kDtmfCommands: types 0x81.. in order, no gap");

// The command of a type, or null.
constexpr const DtmfCommand* find_dtmf_command(uint8_t type) {
  return type >= kDtmfCommandFirst && type < kDtmfCommandFirst + kDtmfCommandCount
             ? &kDtmfCommands[type - kDtmfCommandFirst]
             : nullptr;
}

// The payload of command c: its index and value fields at their widths,
// little-endian.
inline std::vector<uint8_t> dtmf_command_payload(const DtmfCommand& c, uint32_t index,
                                                 uint32_t value) {
  std::vector<uint8_t> p;
  for (int i = 0; i < c.index.bytes; ++i) p.push_back(uint8_t(index >> (8 * i)));
  for (int i = 0; i < c.value.bytes; ++i) p.push_back(uint8_t(value >> (8 * i)));
  return p;
}

// The payload as docs/protocol.md writes it: "k u8, inc u32", "(none)".
inline std::string dtmf_command_payload_text(const DtmfCommand& c) {
  std::string s;
  for (const CommandField* f : {&c.index, &c.value}) {
    if (!f->name) continue;
    if (!s.empty()) s += ", ";
    s += std::string(f->name) + (f->is_signed ? " s" : " u") + std::to_string(8 * f->bytes);
  }
  return s.empty() ? "(none)" : s;
}

}  // namespace eskin
