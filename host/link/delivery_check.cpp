#include "host/link/delivery_check.h"

#include <algorithm>
#include <cstdint>

#include "eskin/fnv1a.h"

namespace eskin::link {

PacketKey key_of(const Packet& p) {
  PacketKey k;
  k.type = p.type;
  k.seq = p.seq;
  k.t = p.t;
  k.len = uint32_t(p.payload.size());
  k.hash = fnv1a(p.payload.data(), p.payload.size());
  return k;
}

DeliveryCheck check_delivery(const std::vector<PacketKey>& sent,
                             const std::vector<PacketKey>& delivered) {
  DeliveryCheck c;
  c.sent = sent.size();
  c.delivered = delivered.size();
  std::vector<bool> got(sent.size(), false);
  size_t next = 0;  // the first sent packet not yet passed
  for (const PacketKey& d : delivered) {
    size_t j = next;
    while (j < sent.size() && !(sent[j].seq == d.seq && sent[j].type == d.type && sent[j].t == d.t))
      ++j;
    if (j == sent.size() || !(sent[j] == d)) {
      ++c.wrong;  // keep `next`: a wrong packet says nothing of where the stream is
      c.match.push_back(SIZE_MAX);
      continue;
    }
    ++c.intact;
    got[j] = true;
    c.match.push_back(j);
    next = j + 1;
  }
  size_t first = sent.size(), last = 0;
  for (size_t j = 0; j < sent.size(); ++j)
    if (got[j]) {
      first = std::min(first, j);
      last = j;
    }
  c.unseen = first == sent.size() ? sent.size() : first + (sent.size() - 1 - last);
  bool in_loss = false;
  for (size_t j = 0; j < sent.size(); ++j) {
    if (!got[j]) {
      ++c.lost;
      in_loss = true;
    } else if (in_loss) {
      ++c.recoveries;
      in_loss = false;
    }
  }
  return c;
}

std::vector<PacketKey> packet_keys(const std::vector<uint8_t>& bytes, DecoderStats* stats) {
  std::vector<PacketKey> out;
  LinkDecoder dec;
  dec.on_packet([&](const Packet& p) { out.push_back(key_of(p)); });
  dec.feed(bytes);
  if (stats) *stats = dec.stats();
  return out;
}

}  // namespace eskin::link
