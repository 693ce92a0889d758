#include "host/stream/commands.h"

#include <stdexcept>

namespace eskin::stream {

namespace {

using link::LinkEncoder;
using V = std::vector<int64_t>;

constexpr int64_t kU8 = 0xFF, kU16 = 0xFFFF, kU32 = 0xFFFFFFFFLL;

}  // namespace

const std::vector<CommandSpec>& command_specs() {
  static const std::vector<CommandSpec> specs = {
      {"set-carrier", link::kCmdSetCarrierInc, {{"k", 0, kU8}, {"inc", 0, kU32}},
       "sdft_bank phase increment of carrier k: round(f / fs * 2^32)",
       [](LinkEncoder& e, const V& a) { return e.set_carrier_inc(uint8_t(a[0]), uint32_t(a[1])); }},
      {"set-threshold", link::kCmdSetThreshold, {{"id", 0, kU8}, {"value", 0, kU16}},
       "threshold id (0 taxel activity, 1 ghost, 2 ghost onset, 3 spare)",
       [](LinkEncoder& e, const V& a) { return e.set_threshold(uint8_t(a[0]), uint16_t(a[1])); }},
      {"set-neuron", link::kCmdSetNeuron, {{"id", 0, kU8}, {"value", INT32_MIN, INT32_MAX}},
       "neuron parameter id (0 V_RESET, 1 U_JUMP, 2 GAIN, 3 X_SHIFT), raw fixed-point value",
       [](LinkEncoder& e, const V& a) { return e.set_neuron(uint8_t(a[0]), int32_t(a[1])); }},
      {"set-mask", link::kCmdSetOutputMask, {{"mask", 0, kU8}},
       "output enable: bit 0 amplitudes, 1 taxels, 2 spikes, 3 periodic status",
       [](LinkEncoder& e, const V& a) { return e.set_output_mask(uint8_t(a[0])); }},
      {"set-decimation", link::kCmdSetDecimation, {{"stream", 0, kU8}, {"d", 0, kU16}},
       "emit stream (0 amplitudes, 1 taxels, 2 status) every d samples",
       [](LinkEncoder& e, const V& a) { return e.set_decimation(uint8_t(a[0]), uint16_t(a[1])); }},
      {"status", link::kCmdRequestStatus, {}, "request a STATUS packet",
       [](LinkEncoder& e, const V&) { return e.request_status(); }},
      {"clear", link::kCmdClearCounters, {}, "zero the status counters and last reject",
       [](LinkEncoder& e, const V&) { return e.clear_counters(); }},
  };
  return specs;
}

const CommandSpec* find_command(const std::string& name) {
  for (const CommandSpec& c : command_specs())
    if (name == c.name) return &c;
  return nullptr;
}

std::vector<int64_t> parse_command_args(const CommandSpec& spec,
                                        const std::vector<std::string>& text) {
  if (text.size() != spec.args.size()) {
    std::string want;
    for (const CommandArg& a : spec.args) want += std::string(" ") + a.name;
    throw std::invalid_argument(std::string(spec.name) + ": expected " +
                                std::to_string(spec.args.size()) + " argument(s)" +
                                (want.empty() ? "" : " (" + want.substr(1) + ")") + ", got " +
                                std::to_string(text.size()));
  }
  std::vector<int64_t> v;
  for (size_t i = 0; i < text.size(); ++i) {
    const CommandArg& a = spec.args[i];
    const std::string where = std::string(spec.name) + " " + a.name + " '" + text[i] + "'";
    size_t used = 0;
    long long x = 0;
    try {
      x = std::stoll(text[i], &used, 0);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text[i].size())
      throw std::invalid_argument(where + ": expected an integer (decimal or 0x hex)");
    if (x < a.lo || x > a.hi)
      throw std::invalid_argument(where + ": expected " + std::to_string(a.lo) + ".." +
                                  std::to_string(a.hi) + " (the wire field's range)");
    v.push_back(x);
  }
  return v;
}

std::string reject_reason_text(uint8_t reason) {
  switch (reason) {
    case link::kRejectUnknownType: return "unknown command type";
    case link::kRejectBadLength: return "payload length wrong for the type";
    case link::kRejectBadIndex: return "index out of range";
    case link::kRejectBadValue: return "value out of range";
    case link::kRejectReservedBits: return "reserved mask bits set";
    default: return "reason " + std::to_string(reason);
  }
}

Ack judge_reply(uint8_t type, uint8_t seq, const link::StatusBlock& base,
                const link::StatusBlock& st) {
  if (st.cmd_rejected != base.cmd_rejected && st.last_reject_seq == seq &&
      st.last_reject_type == type)
    return Ack::Rejected;
  if (type == link::kCmdClearCounters)
    return st.cmd_accepted <= 1 && st.cmd_rejected == 0 && st.last_reject_type == 0 &&
                   (base.cmd_accepted > 1 || base.cmd_rejected > 0 || base.last_reject_type != 0 ||
                    st.cmd_accepted == 1)
               ? Ack::Accepted
               : Ack::Pending;
  if (base.cmd_accepted >= 0xFFFE) return Ack::Unknown;  // 16-bit counters saturate
  if (st.cmd_accepted >= base.cmd_accepted + 2) return Ack::Accepted;
  return Ack::Pending;
}

}  // namespace eskin::stream
