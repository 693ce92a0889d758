// The FPGA's configuration commands by name (docs/protocol.md §5 for the
// DTMF top, §9 for the Hall top's hall-* commands), and how their
// acknowledgement is read from STATUS (HALL_DECODE_STATUS) packets.
//
// The FPGA sends no ack packet. A rejected command bumps cmd_rejected and
// records its type, reason and seq, and makes the FPGA send a STATUS at
// once; an accepted one only bumps cmd_accepted. So the host sends the
// command followed by REQUEST_STATUS (itself counted as accepted) and judges
// the STATUS packets that follow against the last STATUS seen before.
//
// The Hall top has no status request: it sends HALL_DECODE_STATUS with
// every HALL_BUS_STATUS (every STATUS_EVERY frames, 64 by default: about
// 130 ms) and after a rejected command. The host sends the command alone and
// judges the HALL_DECODE_STATUS packets after it against the one before.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"

namespace eskin::stream {

struct CommandArg {
  const char* name;  // "k", "inc", "id", "value", ...
  int64_t lo, hi;    // what fits the wire field (the FPGA checks the real range)
};

struct CommandSpec {
  const char* name;  // "set-mask", "status", ...
  uint8_t type;      // link::kCmd...
  std::vector<CommandArg> args;
  const char* help;
  // Builds the wire frame with the encoder (advances its seq).
  std::vector<uint8_t> (*build)(link::LinkEncoder& enc, const std::vector<int64_t>& args);
  bool hall = false;  // a Hall top command: judged by HALL_DECODE_STATUS
};

const std::vector<CommandSpec>& command_specs();
const CommandSpec* find_command(const std::string& name);

// Parses the textual arguments (decimal, 0x hex, negative for signed fields)
// against spec.args; throws std::invalid_argument naming the argument.
std::vector<int64_t> parse_command_args(const CommandSpec& spec,
                                        const std::vector<std::string>& text);

// "value out of range" etc. for RejectReason codes; "reason N" otherwise.
std::string reject_reason_text(uint8_t reason);

enum class Ack { Pending, Accepted, Rejected, Unknown };

// Judges one STATUS `st` received after the command (type, seq) and the
// REQUEST_STATUS that followed it were sent; `base` is the last STATUS
// before. Rejected: a new rejection recorded with our seq and type.
// Accepted: cmd_accepted grew by 2 (ours and the status request), or for
// CLEAR_COUNTERS: the counters restarted. Unknown: counters saturated.
Ack judge_reply(uint8_t type, uint8_t seq, const link::StatusBlock& base,
                const link::StatusBlock& st);
// The same for a Hall command and one HALL_DECODE_STATUS `st` after it:
// Rejected as above; Accepted: cmd_accepted grew.
Ack judge_hall_reply(uint8_t type, uint8_t seq, const link::HallDecodeStatus& base,
                     const link::HallDecodeStatus& st);

}  // namespace eskin::stream
