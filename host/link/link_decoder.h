// Host-link protocol (docs/protocol.md) and its streaming decoder.
//
// Wire format of one frame (both directions):
//   COBS( type u8 | seq u8 | t u32 LE | len u16 LE | payload[len] | crc u16 BE )
//   followed by one 0x00 delimiter.
// crc = CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, not reflected, xorout
// 0) over type..payload, sent high byte first so that the CRC register over
// the whole raw frame (CRC bytes included) ends at 0.
//
// LinkDecoder::feed() accepts any split of the byte stream; every frame that
// is malformed (COBS violation, too short, length field disagrees with the
// frame, bad CRC, payload malformed for its type) is counted and skipped and
// decoding resumes at the next 0x00 delimiter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <array>
#include <deque>
#include <functional>
#include <string>
#include <vector>

#include "eskin/dtmf_commands.h"
#include "host/link/hall_packets.h"

namespace eskin::link {

// Packet types. FPGA -> host below 0x80, host -> FPGA commands from 0x80.
enum PacketType : uint8_t {
  kAmplitudes = 0x01,    // n x u16: carrier magnitudes, rows then columns
  kTaxelsDense = 0x02,   // rows u8, cols u8, rows*cols x u16 row-major
  kTaxelsSparse = 0x03,  // n x {row u8, col u8, value u16}
  kSpikes = 0x04,        // n x {dt u16, layer u8, neuron u16}
  kStatus = 0x05,        // fixed 28-byte counter block (StatusBlock)
  kHallSamples = 0x10,   // n x HallSample (10 bytes): one frame of Hall sensor readings
  kHallBusStatus = 0x20, // n x HallBusStatus (10 bytes): per-I2C-bus counters
  // Commands: their payloads in common/eskin/dtmf_commands.h.
  kCmdSetCarrierInc = dtmf_cmd::kSetCarrierInc,
  kCmdSetThreshold = dtmf_cmd::kSetThreshold,
  kCmdSetNeuron = dtmf_cmd::kSetNeuron,
  kCmdSetOutputMask = dtmf_cmd::kSetOutputMask,
  kCmdSetDecimation = dtmf_cmd::kSetDecimation,
  kCmdRequestStatus = dtmf_cmd::kRequestStatus,
  kCmdClearCounters = dtmf_cmd::kClearCounters,
  kCmdSetWeight = dtmf_cmd::kSetWeight,
  kCmdSetDemixCoef = dtmf_cmd::kSetDemixCoef,
};

// Reason codes of a rejected command (StatusBlock::last_reject_reason).
enum RejectReason : uint8_t {
  kRejectNone = 0,
  kRejectUnknownType = 1,
  kRejectBadLength = 2,    // payload length wrong for the command type
  kRejectBadIndex = 3,     // carrier / threshold / neuron / stream index
  kRejectBadValue = 4,     // value outside its documented range
  kRejectReservedBits = 5, // output mask bits 5..7 must be 0
};

constexpr size_t kHeaderBytes = 8;   // type, seq, t (4), len (2)
constexpr size_t kCrcBytes = 2;
constexpr size_t kStatusBytes = 28;  // StatusBlock on the wire

// CRC-16/CCITT-FALSE, bitwise (the encoder has its own table-driven copy).
uint16_t crc16_ccitt_false(const uint8_t* data, size_t n, uint16_t crc = 0xFFFF);

struct SparseTaxel { uint8_t row = 0, col = 0; uint16_t value = 0; };
struct SpikeEvent { uint16_t dt = 0; uint8_t layer = 0; uint16_t neuron = 0; };
// One MLX90393 reading in a HALL_SAMPLES frame (rtl/hall_top.v). x, y, z
// are the device's codes (format per RES/TCMP: common/eskin/mlx90393_config.h);
// t16 is the low 16 bits of the µs time the reading arrived.
struct HallSample {
  enum Flag : uint8_t { kSatX = 1, kSatY = 2, kSatZ = 4, kMissing = 8, kError = 16,
                        kReply = 32, kBus = 64, kRecovered = 128 };
  static constexpr uint8_t kNoData = kMissing | kError | kReply | kBus;
  uint8_t id = 0, flags = 0;
  uint16_t t16 = 0, x = 0, y = 0, z = 0;
  bool has_data() const { return (flags & kNoData) == 0; }
};
// Counters of one I2C bus (mlx90393_sequencer), saturating at 0xFFFF.
struct HallBusStatus {
  uint16_t nacks = 0, status_errors = 0, reply_errors = 0, recoveries = 0, bus_errors = 0;
};

// Status packet payload, all fields little endian on the wire in this order.
struct StatusBlock {
  uint16_t cmd_crc_errors = 0;    // command frames dropped for a bad CRC
  uint16_t cmd_frame_errors = 0;  // dropped: length/COBS/UART framing error
  uint16_t cmd_accepted = 0;
  uint16_t cmd_rejected = 0;      // well-formed commands with bad contents
  uint8_t last_reject_type = 0;   // command type of the last rejection
  uint8_t last_reject_reason = 0; // RejectReason
  uint8_t last_reject_seq = 0;    // its sequence number
  uint8_t output_mask = 0;        // current output enable mask
  uint16_t dropped_frames = 0;    // output packets dropped (no room in the output FIFO)
  uint16_t adc_overruns = 0;      // ADC samples lost to a stalled consumer
  uint16_t uart_rx_errors = 0;    // UART stop-bit / overrun errors
  uint16_t frame_overruns = 0;    // frames lost: the frame engine was still busy
  uint16_t spikes_dropped = 0;    // spike events beyond a packet's capacity
  uint16_t cmd_overflows = 0;     // command frames dropped: command FIFO full
  uint32_t samples = 0;           // ADC samples taken when the packet was built (t + 1)
};

struct Packet {
  uint8_t type = 0;
  uint8_t seq = 0;
  uint32_t t = 0;                  // sample counter timestamp
  std::vector<uint8_t> payload;    // raw payload bytes
  // Parsed per type (only the fields of `type` are filled):
  std::vector<uint16_t> amplitudes;            // kAmplitudes
  uint8_t rows = 0, cols = 0;                  // kTaxelsDense
  std::vector<uint16_t> taxels;                // kTaxelsDense, row-major
  std::vector<SparseTaxel> sparse;             // kTaxelsSparse
  std::vector<SpikeEvent> spikes;              // kSpikes
  StatusBlock status;                          // kStatus
  std::vector<HallSample> hall_samples;        // kHallSamples
  std::vector<HallBusStatus> hall_buses;       // kHallBusStatus
  uint8_t cmd_index = 0;                       // commands with an index
  uint32_t cmd_value = 0;                      // commands with a value (s32 as its bits)
  HallPayload hall;                            // Hall decoding packets 0x12..0x16, 0x98..0x9C
};

struct DecoderStats {
  uint64_t bytes = 0;
  uint64_t frames_ok = 0;
  uint64_t crc_errors = 0;      // well-formed frame, CRC mismatch
  uint64_t framing_errors = 0;  // COBS violation, too short/long, len mismatch
  uint64_t payload_errors = 0;  // CRC ok but payload malformed for its type
  uint64_t seq_gaps = 0;        // times the sequence number skipped
  uint64_t lost_packets = 0;    // sum of the skipped sequence numbers
  // The board restarted (a reset): a packet's t fell behind the last of its
  // type and its seq broke the numbering. Its seq then counts from 0 again:
  // lost_packets adds the packets since the restart that did not arrive,
  // not the old numbering's gap.
  uint64_t restarts = 0;
};

// Parses `p.payload` into the per-type fields. Returns false (with a reason
// in *why) when the payload does not fit its type.
bool parse_payload(Packet& p, std::string* why = nullptr);

class LinkDecoder {
 public:
  explicit LinkDecoder(size_t max_payload = 65535);
  void feed(const uint8_t* data, size_t n);
  void feed(const std::vector<uint8_t>& bytes) { feed(bytes.data(), bytes.size()); }
  // Decoded packets are queued; a callback, when set, receives each one
  // instead of the queue.
  bool pop(Packet& out);
  size_t pending() const { return queue_.size(); }
  void on_packet(std::function<void(const Packet&)> cb) { callback_ = std::move(cb); }
  const DecoderStats& stats() const { return stats_; }

 private:
  void end_of_frame();
  void check_sequence(uint8_t seq, uint8_t type, uint32_t t);

  size_t max_encoded_;
  std::vector<uint8_t> frame_;   // COBS bytes since the last delimiter
  bool overflow_ = false;        // frame_ exceeded max_encoded_
  bool have_seq_ = false;
  uint8_t last_seq_ = 0;
  std::array<int64_t, 256> last_t_;  // per packet type, -1: none yet
  std::deque<Packet> queue_;
  std::function<void(const Packet&)> callback_;
  DecoderStats stats_;
};

}  // namespace eskin::link
