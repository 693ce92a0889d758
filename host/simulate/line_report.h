// A virtual board run with line faults (docs/vboard.md, "Line faults"):
// what the host delivered against what the FPGA sent (the board's tap on
// its uart_txd pin, before the line), the host's own counters and the
// faults the line injected, side by side. eskin simulate puts it in
// line.json, summary.json and the report; the soak (soak.h) in its table.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/link/delivery_check.h"
#include "host/link/link_decoder.h"
#include "sim/vboard/line_faults.h"

namespace eskin::simulate {

struct LineReport {
  link::DeliveryCheck check;   // delivered against sent
  link::DecoderStats host;     // the host's counters (crc, framing, seq gaps, lost)
  vboard::LineCounts injected; // the line's (the board's done line)
  uint64_t usb_framing_errors = 0;  // stop bits the bridge read as 0
};

// `tap_file`: the board's --tap-to-host file; `done`: its done line.
LineReport line_report(const std::string& tap_file, const std::vector<link::PacketKey>& delivered,
                       const link::DecoderStats& host, const nlohmann::json& done);

nlohmann::json to_json(const LineReport& r);
// {figure, value} rows for the report's table.
std::vector<std::vector<std::string>> line_rows(const LineReport& r);
// The table on stdout.
std::string line_text(const LineReport& r);

}  // namespace eskin::simulate
