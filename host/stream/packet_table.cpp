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

// Hall skins (docs/protocol.md sections 8 and 9): one row per sensor
// reading, bus, or cell record; raw integers as the FPGA sent them.
void hall_sample_rows(const Packet& p, std::vector<Row>& out) {
  for (const link::HallSample& h : p.hall_samples)
    out.push_back({{p.seq, p.t, h.id, h.flags, h.t16, h.x, h.y, h.z}, {}});
}

void hall_bus_rows(const Packet& p, std::vector<Row>& out) {
  for (size_t b = 0; b < p.hall_buses.size(); ++b) {
    const link::HallBusStatus& s = p.hall_buses[b];
    out.push_back({{p.seq, p.t, int64_t(b), s.nacks, s.status_errors, s.reply_errors,
                    s.recoveries, s.bus_errors},
                   {}});
  }
}

void hall_delta_rows(const Packet& p, std::vector<Row>& out) {
  for (const link::HallDeltaRecord& d : p.hall.deltas)
    out.push_back({{p.seq, p.t, d.id, d.flags, d.t16, d.dx, d.dy, d.dz}, {}});
}

void hall_decouple_rows(const Packet& p, std::vector<Row>& out) {
  const link::DecoupleRecord& d = p.hall.decouple;
  out.push_back({{p.seq, p.t, d.rx, d.ry, d.sz, d.valid, d.flags}, {}});
}

void hall_wrench_rows(const Packet& p, std::vector<Row>& out) {
  const link::WrenchRecord& w = p.hall.wrench;
  out.push_back({{p.seq, p.t, w.w[0], w.w[1], w.w[2], w.w[3], w.w[4], w.w[5], w.flags}, {}});
}

void hall_force_rows(const Packet& p, std::vector<Row>& out) {
  for (const link::ForceRecord& f : p.hall.forces)
    out.push_back({{p.seq, p.t, f.cell, f.range, f.flags, f.t, f.force_mn}, {}});
}

void hall_decode_status_rows(const Packet& p, std::vector<Row>& out) {
  const link::HallDecodeStatus& s = p.hall.status;
  out.push_back({{p.seq, p.t, s.baseline_dropped, s.ft_skipped, s.cmd_accepted, s.cmd_rejected,
                  s.cmd_crc_errors, s.cmd_frame_errors, s.cmd_overflows, s.last_reject_type,
                  s.last_reject_reason, s.last_reject_seq},
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
      {link::kHallSamples, "hall_samples", {"seq", "t", "id", "flags", "t16", "x", "y", "z"},
       nullptr, hall_sample_rows},
      {link::kHallBusStatus,
       "hall_bus_status",
       {"seq", "t", "bus", "nacks", "status_errors", "reply_errors", "recoveries", "bus_errors"},
       nullptr,
       hall_bus_rows},
      {link::kHallDeltas, "hall_deltas", {"seq", "t", "id", "flags", "t16", "dx", "dy", "dz"},
       nullptr, hall_delta_rows},
      {link::kHallDecouple3, "hall_decouple", {"seq", "t", "rx", "ry", "sz", "valid", "flags"},
       nullptr, hall_decouple_rows},
      {link::kHallWrench6,
       "hall_wrench",
       {"seq", "t", "fx_mn", "fy_mn", "fz_mn", "tx_mnmm", "ty_mnmm", "tz_mnmm", "flags"},
       nullptr,
       hall_wrench_rows},
      {link::kHallForceCurve, "hall_forces",
       {"seq", "t", "cell", "range", "flags", "t_us", "force_mn"}, nullptr, hall_force_rows},
      {link::kHallDecodeStatus,
       "hall_decode_status",
       {"seq", "t", "baseline_dropped", "ft_skipped", "cmd_accepted", "cmd_rejected",
        "cmd_crc_errors", "cmd_frame_errors", "cmd_overflows", "last_reject_type",
        "last_reject_reason", "last_reject_seq"},
       nullptr,
       hall_decode_status_rows},
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
