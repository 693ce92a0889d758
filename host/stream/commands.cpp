#include "host/stream/commands.h"

#include <cstdint>
#include <stdexcept>

#include "host/link/hall_packets.h"

namespace eskin::stream {

namespace {

using link::LinkEncoder;
using V = std::vector<int64_t>;

constexpr int64_t kU8 = 0xFF, kU16 = 0xFFFF, kU32 = 0xFFFFFFFFLL;
// SET_NEURON's id byte is layer << 4 | param: four bits each.
constexpr int64_t kNibble = 0xF;

}  // namespace

const std::vector<CommandSpec>& command_specs() {
  static const std::vector<CommandSpec> specs = {
      {"set-carrier", link::kCmdSetCarrierInc, {{"k", 0, kU8}, {"inc", 0, kU32}},
       "phase increment of carrier k: round(f / fs * 2^32), 1 <= inc < 2^31; send the demix "
       "coefficients after it when the FPGA demixes",
       [](LinkEncoder& e, const V& a) { return e.set_carrier_inc(uint8_t(a[0]), uint32_t(a[1])); }},
      {"set-threshold", link::kCmdSetThreshold, {{"id", 0, kU8}, {"value", 0, kU16}},
       "threshold id: 0 sparse minimum (UQ1.15), 1 ghost onset (magnitude units), 2 ghost "
       "release (UQ1.15), 3 ghost pairing tolerance (magnitude units)",
       [](LinkEncoder& e, const V& a) { return e.set_threshold(uint8_t(a[0]), uint16_t(a[1])); }},
      {"set-neuron", link::kCmdSetNeuron,
       {{"layer", 0, kNibble}, {"param", 0, kNibble}, {"value", INT32_MIN, INT32_MAX}},
       "parameter of neuron layer (0 receptors, 1 weighted): 0 v_reset, 1 u_jump, 2 gain, "
       "3 gain_shift, 4 x_shift, 5 c_const, 6/8/10 m2/m3/m4, 7/9/11 s2/s3/s4, 12 u_frac, "
       "13 input_change, 14 v_init, 15 u_init; raw fixed-point value (docs/protocol.md)",
       [](LinkEncoder& e, const V& a) {
         return e.set_neuron(uint8_t(a[0] << 4 | a[1]), int32_t(a[2]));
       }},
      {"set-weight", link::kCmdSetWeight, {{"id", 0, kU8}, {"value", INT16_MIN, INT16_MAX}},
       "synaptic weight W[id / 3][id % 3] of layer 1 (id 0..8, centre 4), 8 fraction bits",
       [](LinkEncoder& e, const V& a) { return e.set_weight(uint8_t(a[0]), int16_t(a[1])); }},
      {"set-demix-coef", link::kCmdSetDemixCoef,
       {{"index", 0, kU16}, {"value", INT16_MIN, INT16_MAX}},
       "demix matrix entry, row-major, Q2.14 (index < (2K+1)^2; none without demixing)",
       [](LinkEncoder& e, const V& a) {
         return e.set_demix_coef(uint16_t(a[0]), int16_t(a[1]));
       }},
      {"set-mask", link::kCmdSetOutputMask, {{"mask", 0, kU8}},
       "output enable: bit 0 amplitudes, 1 dense taxels, 2 spikes, 3 periodic status, "
       "4 sparse taxels",
       [](LinkEncoder& e, const V& a) { return e.set_output_mask(uint8_t(a[0])); }},
      {"set-decimation", link::kCmdSetDecimation, {{"stream", 0, kU8}, {"d", 0, kU16}},
       "one packet every d >= 1 frames: stream 0 amplitudes, 1 taxels and spike windows, "
       "2 periodic status",
       [](LinkEncoder& e, const V& a) { return e.set_decimation(uint8_t(a[0]), uint16_t(a[1])); }},
      {"status", link::kCmdRequestStatus, {}, "request a STATUS packet",
       [](LinkEncoder& e, const V&) { return e.request_status(); }},
      {"clear", link::kCmdClearCounters, {}, "zero the status counters and last reject",
       [](LinkEncoder& e, const V&) { return e.clear_counters(); }},
      // The Hall top (docs/protocol.md section 9).
      {"hall-set-baseline", link::kCmdHallSetBaseline,
       {{"sensor", 0, kU8}, {"axis", 0, kU8}, {"value", INT16_MIN, INT16_MAX}},
       "Hall: baseline of one sensor axis (0 x, 1 y, 2 z) in LSB; a sensor with all three "
       "set stops capturing",
       [](LinkEncoder& e, const V& a) {
         return link::hall_set_baseline(e, uint8_t(a[0]), uint8_t(a[1]), int16_t(a[2]));
       },
       true},
      {"hall-recapture", link::kCmdHallRecapture, {},
       "Hall: capture every sensor's baseline again (its next 16 readings)",
       [](LinkEncoder& e, const V&) { return link::hall_recapture(e); }, true},
      {"hall-load-c", link::kCmdHallLoadC,
       {{"row", 0, kU8}, {"col", 0, kU8}, {"value", INT32_MIN, INT32_MAX}},
       "Hall: six-axis matrix entry C[row 0..5][col 0..8], mN (mN*mm) per LSB * 2^16",
       [](LinkEncoder& e, const V& a) {
         return link::hall_load_c(e, uint8_t(a[0]), uint8_t(a[1]), int32_t(a[2]));
       },
       true},
      {"hall-load-curve", link::kCmdHallLoadCurve,
       {{"cell", 0, kU8}, {"index", 0, kU8}, {"which", 0, kU8}, {"value", INT32_MIN, INT32_MAX}},
       "Hall: force curve breakpoint of a cell: which 0 |dB| (1/64 uT), 1 force (mN), "
       "2 slope (Q15.16 mN per 1/64 uT)",
       [](LinkEncoder& e, const V& a) {
         return link::hall_load_curve(e, uint8_t(a[0]), uint8_t(a[1]), uint8_t(a[2]), int32_t(a[3]));
       },
       true},
      {"hall-set-decouple", link::kCmdHallSetDecouple,
       {{"k1", INT16_MIN, INT16_MAX}, {"c1", INT32_MIN, INT32_MAX}, {"k2", INT16_MIN, INT16_MAX},
        {"c2", INT32_MIN, INT32_MAX}},
       "Hall: seed-001 compensation k1, k2 (Q2.14) and c1, c2 (1/64 uT)",
       [](LinkEncoder& e, const V& a) {
         return link::hall_set_decouple(e, int16_t(a[0]), int32_t(a[1]), int16_t(a[2]), int32_t(a[3]));
       },
       true},
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

Ack judge_hall_reply(uint8_t type, uint8_t seq, const link::HallDecodeStatus& base,
                     const link::HallDecodeStatus& st) {
  if (st.cmd_rejected != base.cmd_rejected && st.last_reject_seq == seq &&
      st.last_reject_type == type)
    return Ack::Rejected;
  if (base.cmd_accepted == 0xFFFF) return Ack::Unknown;  // saturated
  if (st.cmd_accepted > base.cmd_accepted) return Ack::Accepted;
  return Ack::Pending;
}

}  // namespace eskin::stream
