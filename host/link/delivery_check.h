// What a host delivered against what the FPGA sent (docs/vboard.md, "Line
// faults"): the FPGA's bytes as they left its pin (the virtual board's
// --tap-to-host, before the line's faults) decoded into the packets it
// sent, and the host's delivered packets matched to them in order by
// (seq, type, t), payloads compared by length and a 64-bit FNV-1a hash (a
// soak's million packets are not kept whole; two payloads that differ
// agree on it with probability 2^-64).
#pragma once

#include <cstdint>
#include <vector>

#include "host/link/link_decoder.h"

namespace eskin::link {

struct PacketKey {
  uint8_t type = 0, seq = 0;
  uint32_t t = 0;
  uint32_t len = 0;
  uint64_t hash = 0;  // FNV-1a over the payload
  bool operator==(const PacketKey& o) const {
    return type == o.type && seq == o.seq && t == o.t && len == o.len && hash == o.hash;
  }
};
PacketKey key_of(const Packet& p);

struct DeliveryCheck {
  uint64_t sent = 0;        // packets the FPGA sent
  uint64_t delivered = 0;   // packets the host delivered
  uint64_t intact = 0;      // delivered, equal to the next sent packets' one (order kept)
  uint64_t wrong = 0;       // delivered, but no sent packet at or after the last match
                            // with its seq, type and t, or its payload differs
  uint64_t lost = 0;        // sent, never delivered
  uint64_t recoveries = 0;  // runs of lost packets after which a packet was delivered again
  // Lost before the first or after the last packet delivered: no host can
  // tell these from its seq numbers, so its count of lost packets (seq
  // gaps) is lost - unseen (while no run of losses reaches 256).
  uint64_t unseen = 0;
  std::vector<size_t> match;  // per delivered packet: its sent index (SIZE_MAX: wrong)
};

DeliveryCheck check_delivery(const std::vector<PacketKey>& sent,
                             const std::vector<PacketKey>& delivered);

// The key of every packet in a byte stream, as LinkDecoder delivers them.
std::vector<PacketKey> packet_keys(const std::vector<uint8_t>& bytes, DecoderStats* stats = nullptr);

}  // namespace eskin::link
