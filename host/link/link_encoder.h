// Host-side encoder of host-link frames (docs/protocol.md): configuration
// commands for the FPGA and, for tests, data packets as the FPGA sends them.
// Independent of the RTL (rtl/link_framer.v) and of the decoder's CRC and
// COBS code (table-driven CRC, its own COBS encoder), so a round trip checks
// two implementations against each other. Hall packets and commands
// (0x11..0x16, 0x98..0x9C): host/link/hall_packets.h.
#pragma once

#include <cstdint>
#include <vector>

#include "host/link/link_decoder.h"

namespace eskin::link {

// CRC-16/CCITT-FALSE, table driven.
uint16_t crc16_table(const uint8_t* data, size_t n, uint16_t crc = 0xFFFF);

// COBS encoding without the trailing delimiter: one code byte per run of up
// to 254 non-zero bytes, always ending with a final block (so a frame ending
// in a full 254-byte run gets a closing 0x01 code).
std::vector<uint8_t> cobs_encode(const std::vector<uint8_t>& raw);

// The raw (pre-COBS) frame: header, payload, big-endian CRC.
std::vector<uint8_t> raw_frame(uint8_t type, uint8_t seq, uint32_t t,
                               const std::vector<uint8_t>& payload);

class LinkEncoder {
 public:
  // A complete wire frame (COBS + 0x00); uses and advances the sequence number.
  std::vector<uint8_t> frame(uint8_t type, uint32_t t, const std::vector<uint8_t>& payload);

  // Data packets (FPGA -> host), as the FPGA would send them.
  std::vector<uint8_t> amplitudes(uint32_t t, const std::vector<uint16_t>& mags);
  std::vector<uint8_t> taxels_dense(uint32_t t, uint8_t rows, uint8_t cols,
                                    const std::vector<uint16_t>& values);
  std::vector<uint8_t> taxels_sparse(uint32_t t, const std::vector<SparseTaxel>& taxels);
  std::vector<uint8_t> spikes(uint32_t t, const std::vector<SpikeEvent>& events);
  std::vector<uint8_t> status(uint32_t t, const StatusBlock& s);

  // Configuration commands (host -> FPGA); timestamp 0.
  // A command of common/eskin/dtmf_commands.h, its index and value fields
  // written at their widths (std::invalid_argument for an unknown type).
  std::vector<uint8_t> command(uint8_t type, uint32_t index, uint32_t value);
  std::vector<uint8_t> set_carrier_inc(uint8_t k, uint32_t inc);
  std::vector<uint8_t> set_threshold(uint8_t id, uint16_t value);
  // id = layer << 4 | parameter (docs/protocol.md §5).
  std::vector<uint8_t> set_neuron(uint8_t id, int32_t value);
  std::vector<uint8_t> set_output_mask(uint8_t mask);
  std::vector<uint8_t> set_decimation(uint8_t stream, uint16_t value);
  std::vector<uint8_t> request_status();
  std::vector<uint8_t> clear_counters();
  std::vector<uint8_t> set_weight(uint8_t id, int16_t value);
  std::vector<uint8_t> set_demix_coef(uint16_t index, int16_t value);

  uint8_t next_seq() const { return seq_; }
  void set_next_seq(uint8_t s) { seq_ = s; }

 private:
  uint8_t seq_ = 0;
};

}  // namespace eskin::link
