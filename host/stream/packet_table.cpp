#include "host/stream/packet_table.h"

namespace eskin::stream {

namespace {

using link::Packet;

void amplitude_rows(const Packet& p, std::vector<Row>& out) {
  out.push_back({{p.seq, p.t}, {p.amplitudes.begin(), p.amplitudes.end()}});
}

void dense_rows(const Packet& p, std::vector<Row>& out) {
  out.push_back({{p.seq, p.t, p.rows, p.cols}, {p.taxels.begin(), p.taxels.end()}});
}

void sparse_rows(const Packet& p, std::vector<Row>& out) {
  for (const link::SparseTaxel& s : p.sparse) out.push_back({{p.seq, p.t, s.row, s.col, s.value}, {}});
}

// t of a spike row is its own sample: the packet's t plus the spike's dt.
void spike_rows(const Packet& p, std::vector<Row>& out) {
  for (const link::SpikeEvent& e : p.spikes)
    out.push_back({{p.seq, int64_t(p.t) + e.dt, e.layer, e.neuron}, {}});
}

void status_rows(const Packet& p, std::vector<Row>& out) {
  const link::StatusBlock& s = p.status;
  out.push_back({{p.seq, p.t, s.cmd_crc_errors, s.cmd_frame_errors, s.cmd_accepted,
                  s.cmd_rejected, s.last_reject_type, s.last_reject_reason, s.last_reject_seq,
                  s.output_mask, s.dropped_frames, s.adc_overruns, s.uart_rx_errors,
                  s.frame_overruns, s.spikes_dropped, s.cmd_overflows, s.samples},
                 {}});
}

}  // namespace

const std::vector<PacketKind>& packet_kinds() {
  static const std::vector<PacketKind> kinds = {
      {link::kAmplitudes, "amplitudes", {"seq", "t"}, "amp", amplitude_rows},
      {link::kTaxelsDense, "taxels", {"seq", "t", "rows", "cols"}, "taxel", dense_rows},
      {link::kTaxelsSparse, "taxels_sparse", {"seq", "t", "row", "col", "value"}, nullptr,
       sparse_rows},
      {link::kSpikes, "spikes", {"seq", "t", "layer", "neuron"}, nullptr, spike_rows},
      {link::kStatus,
       "status",
       {"seq", "t", "cmd_crc_errors", "cmd_frame_errors", "cmd_accepted", "cmd_rejected",
        "last_reject_type", "last_reject_reason", "last_reject_seq", "output_mask",
        "dropped_frames", "adc_overruns", "uart_rx_errors", "frame_overruns", "spikes_dropped",
        "cmd_overflows", "samples"},
       nullptr,
       status_rows},
  };
  return kinds;
}

const PacketKind* find_kind(uint8_t type) {
  for (const PacketKind& k : packet_kinds())
    if (k.type == type) return &k;
  return nullptr;
}

std::string ndjson_line(const PacketKind& kind, const Row& row) {
  std::string s = "{\"type\":\"";
  s += kind.table;
  s += '"';
  for (size_t i = 0; i < kind.scalars.size() && i < row.scalars.size(); ++i) {
    s += ",\"";
    s += kind.scalars[i];
    s += "\":";
    s += std::to_string(row.scalars[i]);
  }
  if (kind.vector_name) {
    s += ",\"";
    s += kind.vector_name;
    s += "\":[";
    for (size_t i = 0; i < row.values.size(); ++i) {
      if (i) s += ',';
      s += std::to_string(row.values[i]);
    }
    s += ']';
  }
  s += '}';
  return s;
}

}  // namespace eskin::stream
