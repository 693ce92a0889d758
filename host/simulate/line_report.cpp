#include "host/simulate/line_report.h"

#include <fmt/format.h>

#include <fstream>
#include <iterator>
#include <stdexcept>

namespace eskin::simulate {

LineReport line_report(const std::string& tap_file, const std::vector<link::PacketKey>& delivered,
                       const link::DecoderStats& host, const nlohmann::json& done) {
  std::ifstream in(tap_file, std::ios::binary);
  if (!in) throw std::runtime_error(tap_file + ": the board's tap on its uart_txd pin is missing");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  LineReport r;
  link::DecoderStats sent_stats;
  const std::vector<link::PacketKey> sent = link::packet_keys(bytes, &sent_stats);
  if (sent_stats.crc_errors + sent_stats.framing_errors + sent_stats.payload_errors > 0)
    throw std::runtime_error(fmt::format(
        "{}: the FPGA's own bytes hold {} bad frames: the tap (or the FPGA) is wrong, so the line "
        "cannot be judged", tap_file,
        sent_stats.crc_errors + sent_stats.framing_errors + sent_stats.payload_errors));
  r.check = link::check_delivery(sent, delivered);
  r.host = host;
  r.injected = vboard::line_counts_from_json(done.at("line_faults"));
  r.usb_framing_errors = done.at("usb_framing_errors");
  return r;
}


nlohmann::json to_json(const LineReport& r) {
  const link::DeliveryCheck& c = r.check;
  return {{"packets_sent", c.sent},
          {"packets_delivered", c.delivered},
          {"packets_intact", c.intact},
          {"packets_delivered_wrong", c.wrong},
          {"packets_lost", c.lost},
          {"packets_lost_unseen", c.unseen},
          {"recoveries", c.recoveries},
          {"host_counted_lost", r.host.lost_packets},
          {"host_seq_gaps", r.host.seq_gaps},
          {"host_crc_errors", r.host.crc_errors},
          {"host_framing_errors", r.host.framing_errors},
          {"host_payload_errors", r.host.payload_errors},
          {"bridge_framing_errors", r.usb_framing_errors},
          {"injected_to_host", vboard::to_json(r.injected.to_host)},
          {"injected_to_fpga", vboard::to_json(r.injected.to_fpga)},
          {"cable_pulls", r.injected.pulls}};
}

std::vector<std::vector<std::string>> line_rows(const LineReport& r) {
  const link::DeliveryCheck& c = r.check;
  const vboard::DirectionCounts& h = r.injected.to_host;
  const vboard::DirectionCounts& f = r.injected.to_fpga;
  return {
      {"line: packets sent by the FPGA / delivered / lost / delivered wrong / recoveries",
       fmt::format("{} / {} / {} / {} / {}", c.sent, c.delivered, c.lost, c.wrong, c.recoveries)},
      {"line: host counted lost packets / seq gaps / CRC errors / framing errors",
       fmt::format("{} / {} / {} / {}", r.host.lost_packets, r.host.seq_gaps, r.host.crc_errors,
                   r.host.framing_errors)},
      {"line: lost before the first or after the last packet delivered (no host sees them)",
       std::to_string(c.unseen)},
      {"line: injected FPGA->host: characters / bit flips (start, data, stop) / dropped / "
       "inserted / during a pull",
       fmt::format("{} / {} ({}, {}, {}) / {} / {} / {}", h.chars, h.flips(), h.start_flips,
                   h.data_flips, h.stop_flips, h.dropped, h.inserted, h.pulled_chars)},
      {"line: injected host->FPGA: characters / bit flips (start, data, stop) / dropped / "
       "inserted / during a pull",
       fmt::format("{} / {} ({}, {}, {}) / {} / {} / {}", f.chars, f.flips(), f.start_flips,
                   f.data_flips, f.stop_flips, f.dropped, f.inserted, f.pulled_chars)},
      {"line: cable pulls", std::to_string(r.injected.pulls)}};
}

std::string line_text(const LineReport& r) {
  std::string s;
  for (const auto& row : line_rows(r)) s += row[0] + ": " + row[1] + "\n";
  return s;
}

}  // namespace eskin::simulate
