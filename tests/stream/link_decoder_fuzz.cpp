// libFuzzer target (clang -fsanitize=fuzzer,address,undefined; built and
// run for a bounded time by tests/stream/CMakeLists.txt): the host-link
// decoder and the packet table on arbitrary bytes. No crash, no hang, no
// sanitizer report, and the counters add up:
//  * every frame (a non-empty run of bytes ended by 0x00, counted here
//    independently of the decoder) is exactly one of: ok, CRC error,
//    framing error, payload error;
//  * every ok frame reached the callback, and every byte was counted;
//  * each sequence gap loses 1..255 packets;
//  * an ok packet re-encoded by the independent encoder decodes to itself.
// Input layout: byte 0 selects the mode and the feed() chunk size. Mode
// "frame" wraps the rest as a valid frame (type = byte 1) and then changes
// byte (byte 2) of the wire frame, so CRC-valid frames with arbitrary
// payloads reach parse_payload; mode "raw" feeds the bytes as they are.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "host/link/link_decoder.h"
#include "host/link/link_encoder.h"
#include "host/stream/packet_table.h"

using namespace eskin::link;

namespace {

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  const size_t chunk = size_t(data[0] & 0x1F) + 1;
  std::vector<uint8_t> wire;
  if (data[0] & 0x80) {
    std::vector<uint8_t> payload(data + 3, data + size);
    wire = cobs_encode(raw_frame(data[1], uint8_t(size), uint32_t(size * 35), payload));
    wire.push_back(0);
    if (data[0] & 0x40) wire[data[2] % wire.size()] ^= uint8_t(data[1] | 1);
  } else {
    wire.assign(data + 1, data + size);
  }

  size_t frames = 0, run = 0;
  for (uint8_t b : wire) {
    if (b == 0) {
      frames += run > 0;
      run = 0;
    } else {
      ++run;
    }
  }
  LinkDecoder dec(data[0] & 0x20 ? 64 : 65535);  // small bound: overflow path too
  size_t delivered = 0;
  std::vector<eskin::stream::Row> rows;
  dec.on_packet([&](const Packet& p) {
    ++delivered;
    if (const auto* kind = eskin::stream::find_kind(p.type)) {
      rows.clear();
      kind->rows(p, rows);
      for (const auto& r : rows) check(!eskin::stream::ndjson_line(*kind, r).empty(), "ndjson");
    }
    LinkDecoder again;
    auto w = cobs_encode(raw_frame(p.type, p.seq, p.t, p.payload));
    w.push_back(0);
    again.feed(w);
    Packet q;
    check(again.pop(q) && q.type == p.type && q.seq == p.seq && q.t == p.t &&
              q.payload == p.payload,
          "re-encoded packet decodes to itself");
  });
  for (size_t i = 0; i < wire.size(); i += chunk)
    dec.feed(wire.data() + i, std::min(chunk, wire.size() - i));

  const DecoderStats& s = dec.stats();
  check(s.bytes == wire.size(), "every byte counted");
  check(s.frames_ok + s.crc_errors + s.framing_errors + s.payload_errors == frames,
        "every frame counted exactly once");
  check(s.frames_ok == delivered, "every ok frame delivered");
  check(s.lost_packets >= s.seq_gaps && s.lost_packets <= 255 * s.seq_gaps,
        "each gap loses 1..255 packets");
  return 0;
}
