// taxel_packetizer: one frame's taxels -> the host-link packets that carry
// them, TAXELS_DENSE (0x02) and TAXELS_SPARSE (0x03) (layouts:
// docs/protocol.md section 4). Bit-exact spec of the packets
// hls/dtmf_chain.h makes of its taxels (which calls this) and of
// rtl/taxel_packetizer.v, the streaming block that writes them into the
// output FIFO.
//
//   dense:  rows u8, cols u8, then rows*cols x g u16 LE, row-major
//   sparse: {row u8, col u8, g u16 LE} for every taxel with
//           g >= max(1, sparse_min), row-major (len 0 when none is)
//
// Each packet carries t (the frame's newest ADC sample). Which of the two a
// frame gets (decimation, output mask) is the caller's choice; dense comes
// first when both do. FifoBytes() gives a packet as the output FIFO holds
// it (the frame engine's and the block's writes): type, t u32 LE, len u16
// LE, payload; rtl/link_framer.v adds seq, CRC and COBS.
//
// Widths: everything fixed width; no heap, no float.
#pragma once

#include <cstdint>

namespace eskin::hls {

// The DTMF top's packet types, FPGA -> host (docs/protocol.md section 4).
enum DtmfPacketType : uint8_t {
  kDtmfAmplitudes = 0x01,
  kDtmfTaxelsDense = 0x02,
  kDtmfTaxelsSparse = 0x03,
  kDtmfSpikes = 0x04,
  kDtmfStatus = 0x05,
};

template <int R, int C>
struct TaxelPacketizer {
  static_assert(R >= 1 && R <= 255 && C >= 1 && C <= 255, "rows and cols are u8 fields");
  static constexpr int T = R * C;
  static constexpr int kDenseLen = 2 + 2 * T;
  static constexpr int kSparseMaxLen = 4 * T;
  static constexpr int kHeaderBytes = 7;  // type, t, len in the FIFO

  // The sparse packet's threshold: g >= max(1, sparse_min) (an unlit taxel,
  // g = 0, is never listed).
  static uint16_t sparse_lo(uint16_t sparse_min) { return sparse_min > 1 ? sparse_min : 1; }

  // One frame's packets into out[0..1] (any type with type, t, len and
  // payload[] of at least kSparseMaxLen and kDenseLen bytes); returns how
  // many: dense first, then sparse.
  template <class Packet>
  static int frame(const uint16_t* g, uint32_t t, bool dense, bool sparse, uint16_t sparse_min,
                   Packet* out) {
    int n = 0;
    if (dense) {
      Packet& p = begin(out[n++], kDtmfTaxelsDense, t);
      p.payload[p.len++] = uint8_t(R);
      p.payload[p.len++] = uint8_t(C);
      for (int i = 0; i < T; ++i) put16(p, g[i]);
    }
    if (sparse) {
      Packet& p = begin(out[n++], kDtmfTaxelsSparse, t);
      const uint16_t lo = sparse_lo(sparse_min);
      for (int i = 0; i < T; ++i) {
        if (g[i] < lo) continue;
        p.payload[p.len++] = uint8_t(i / C);
        p.payload[p.len++] = uint8_t(i % C);
        put16(p, g[i]);
      }
    }
    return n;
  }

  // A packet as the output FIFO holds it; returns the byte count (7 + len).
  template <class Packet>
  static int fifo_bytes(const Packet& p, uint8_t* out) {
    int k = 0;
    out[k++] = p.type;
    for (int b = 0; b < 4; ++b) out[k++] = uint8_t(p.t >> (8 * b));
    out[k++] = uint8_t(p.len & 0xFFu);
    out[k++] = uint8_t(p.len >> 8);
    for (int b = 0; b < p.len; ++b) out[k++] = p.payload[b];
    return k;
  }

 private:
  template <class Packet>
  static Packet& begin(Packet& p, uint8_t type, uint32_t t) {
    p.type = type;
    p.t = t;
    p.len = 0;
    return p;
  }
  template <class Packet>
  static void put16(Packet& p, uint16_t v) {
    p.payload[p.len++] = uint8_t(v & 0xFFu);
    p.payload[p.len++] = uint8_t(v >> 8);
  }
};

}  // namespace eskin::hls
