// Decoded packets as rows of named tables: the one description of every
// FPGA -> host packet type that all consumers share (NDJSON, CSV, HDF5, the
// live view, the stream's per-type callbacks): the DTMF skin's packets and
// the Hall skins' (readings, deltas, decoded forces, counters). A new packet
// type is one entry in packet_kinds() (packet_table.cpp), after
// link_decoder's parse_payload learns its payload.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"

namespace eskin::stream {

// One row of a table: scalar columns, then (optionally) one vector column
// whose length is fixed within a run (e.g. K amplitudes, rows*cols taxels).
struct Row {
  std::vector<int64_t> scalars;  // in PacketKind::scalars order
  std::vector<int64_t> values;   // PacketKind::vector_name; empty if none
};

struct PacketKind {
  uint8_t type;
  const char* table;                  // table/dataset name, e.g. "amplitudes"
  std::vector<const char*> scalars;   // column names; "seq" and "t" first
  const char* vector_name;            // name of the vector column, or nullptr
  // Appends the packet's rows (one per packet, or one per event for
  // sparse taxels and spikes).
  void (*rows)(const link::Packet& p, std::vector<Row>& out);
};

// Every known FPGA -> host type.
const std::vector<PacketKind>& packet_kinds();
// The entry for `type`, or nullptr.
const PacketKind* find_kind(uint8_t type);

// One NDJSON line (no newline) per row: {"type":"amplitudes","seq":1,...}.
std::string ndjson_line(const PacketKind& kind, const Row& row);

}  // namespace eskin::stream
