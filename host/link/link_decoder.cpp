#include "host/link/link_decoder.h"

namespace eskin::link {

uint16_t crc16_ccitt_false(const uint8_t* data, size_t n, uint16_t crc) {
  for (size_t i = 0; i < n; ++i) {
    crc = uint16_t(crc ^ (uint16_t(data[i]) << 8));
    for (int b = 0; b < 8; ++b)
      crc = (crc & 0x8000) ? uint16_t((crc << 1) ^ 0x1021) : uint16_t(crc << 1);
  }
  return crc;
}

namespace {

uint16_t le16(const uint8_t* p) { return uint16_t(p[0] | (p[1] << 8)); }
uint32_t le32(const uint8_t* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) |
         (uint32_t(p[3]) << 24);
}

// COBS decoding of one frame (delimiter already removed). Each block is a
// code byte c (1..255) and c-1 data bytes; a block with c < 255 is followed
// by an implied zero unless it ends the frame. A zero byte inside the frame
// or a block running past the end is a framing error.
bool cobs_decode(const std::vector<uint8_t>& in, std::vector<uint8_t>& out) {
  out.clear();
  size_t i = 0;
  while (i < in.size()) {
    const uint8_t code = in[i++];
    if (code == 0) return false;
    if (i + code - 1 > in.size()) return false;
    for (int j = 1; j < code; ++j) {
      if (in[i] == 0) return false;
      out.push_back(in[i++]);
    }
    if (code != 0xFF && i < in.size()) out.push_back(0);
  }
  return true;
}

bool fail(std::string* why, const char* msg) {
  if (why) *why = msg;
  return false;
}

uint32_t le(const uint8_t* p, int bytes) {
  uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= uint32_t(p[i]) << (8 * i);
  return v;
}

// A command by its definition (common/eskin/dtmf_commands.h): cmd_index is
// the index field's low byte, cmd_value the value field's bits; for
// SET_DEMIX_COEF, whose index is 16 bits, cmd_value keeps both fields
// (index | value << 16).
bool parse_command(const DtmfCommand& c, const uint8_t* b, size_t n, Packet& p,
                   std::string* why) {
  if (n != size_t(c.payload_bytes())) {
    if (why)
      *why = std::string(c.name) + ": payload length must be " +
             std::to_string(c.payload_bytes());
    return false;
  }
  if (c.index.bytes) p.cmd_index = b[0];
  p.cmd_value = c.type == dtmf_cmd::kSetDemixCoef ? le(b, 4) : le(b + c.index.bytes, c.value.bytes);
  return true;
}

}  // namespace

bool parse_payload(Packet& p, std::string* why) {
  const std::vector<uint8_t>& b = p.payload;
  const size_t n = b.size();
  switch (p.type) {
    case kAmplitudes:
      if (n % 2) return fail(why, "amplitudes: payload length must be even");
      for (size_t i = 0; i < n; i += 2) p.amplitudes.push_back(le16(&b[i]));
      return true;
    case kTaxelsDense:
      if (n < 2) return fail(why, "taxels: payload needs rows and cols bytes");
      p.rows = b[0];
      p.cols = b[1];
      if (n != 2 + 2 * size_t(p.rows) * p.cols)
        return fail(why, "taxels: payload length must be 2 + 2*rows*cols");
      for (size_t i = 2; i < n; i += 2) p.taxels.push_back(le16(&b[i]));
      return true;
    case kTaxelsSparse:
      if (n % 4) return fail(why, "sparse taxels: payload length must be a multiple of 4");
      for (size_t i = 0; i < n; i += 4) p.sparse.push_back({b[i], b[i + 1], le16(&b[i + 2])});
      return true;
    case kSpikes:
      if (n % 5) return fail(why, "spikes: payload length must be a multiple of 5");
      for (size_t i = 0; i < n; i += 5)
        p.spikes.push_back({le16(&b[i]), b[i + 2], le16(&b[i + 3])});
      return true;
    case kStatus: {
      if (n != kStatusBytes) return fail(why, "status: payload length must be 28");
      StatusBlock& s = p.status;
      s.cmd_crc_errors = le16(&b[0]);
      s.cmd_frame_errors = le16(&b[2]);
      s.cmd_accepted = le16(&b[4]);
      s.cmd_rejected = le16(&b[6]);
      s.last_reject_type = b[8];
      s.last_reject_reason = b[9];
      s.last_reject_seq = b[10];
      s.output_mask = b[11];
      s.dropped_frames = le16(&b[12]);
      s.adc_overruns = le16(&b[14]);
      s.uart_rx_errors = le16(&b[16]);
      s.frame_overruns = le16(&b[18]);
      s.spikes_dropped = le16(&b[20]);
      s.cmd_overflows = le16(&b[22]);
      s.samples = le32(&b[24]);
      return true;
    }
    case kHallSamples:
      if (n % 10) return fail(why, "hall samples: payload length must be a multiple of 10");
      for (size_t i = 0; i < n; i += 10)
        p.hall_samples.push_back(
            {b[i], b[i + 1], le16(&b[i + 2]), le16(&b[i + 4]), le16(&b[i + 6]), le16(&b[i + 8])});
      return true;
    case kHallBusStatus:
      if (n % 10) return fail(why, "hall bus status: payload length must be a multiple of 10");
      for (size_t i = 0; i < n; i += 10)
        p.hall_buses.push_back({le16(&b[i]), le16(&b[i + 2]), le16(&b[i + 4]), le16(&b[i + 6]),
                                le16(&b[i + 8])});
      return true;
    default: {
      if (const DtmfCommand* c = find_dtmf_command(p.type)) return parse_command(*c, b.data(), n, p, why);
      bool known = false;
      const bool ok = parse_hall_payload(p.type, b, p.hall, known, why);
      return known ? ok : fail(why, "unknown packet type");
    }
  }
}

LinkDecoder::LinkDecoder(size_t max_payload)
    // COBS adds one code byte per 254 bytes plus one.
    : max_encoded_(kHeaderBytes + max_payload + kCrcBytes +
                   (kHeaderBytes + max_payload + kCrcBytes) / 254 + 2) {
  last_t_.fill(-1);
}

void LinkDecoder::feed(const uint8_t* data, size_t n) {
  stats_.bytes += n;
  for (size_t i = 0; i < n; ++i) {
    if (data[i] == 0) {
      end_of_frame();
    } else if (frame_.size() < max_encoded_) {
      frame_.push_back(data[i]);
    } else {
      overflow_ = true;  // keep discarding until the next delimiter
    }
  }
}

void LinkDecoder::end_of_frame() {
  const bool overflow = overflow_;
  overflow_ = false;
  if (frame_.empty() && !overflow) return;  // back-to-back delimiters: idle
  std::vector<uint8_t> raw;
  const bool cobs_ok = cobs_decode(frame_, raw);
  frame_.clear();
  if (overflow || !cobs_ok || raw.size() < kHeaderBytes + kCrcBytes) {
    ++stats_.framing_errors;
    return;
  }
  const size_t len = le16(&raw[6]);
  if (raw.size() != kHeaderBytes + len + kCrcBytes) {
    ++stats_.framing_errors;
    return;
  }
  // Residue check: the CRC over the frame including its big-endian CRC is 0.
  if (crc16_ccitt_false(raw.data(), raw.size()) != 0) {
    ++stats_.crc_errors;
    return;
  }
  Packet p;
  p.type = raw[0];
  p.seq = raw[1];
  p.t = le32(&raw[2]);
  p.payload.assign(raw.begin() + kHeaderBytes, raw.begin() + kHeaderBytes + len);
  check_sequence(p.seq, p.type, p.t);  // a valid frame advances the sequence even if unparsable
  if (!parse_payload(p)) {
    ++stats_.payload_errors;
    return;
  }
  ++stats_.frames_ok;
  if (callback_)
    callback_(p);
  else
    queue_.push_back(std::move(p));
}

void LinkDecoder::check_sequence(uint8_t seq, uint8_t type, uint32_t t) {
  // A restarted board numbers its packets and its time from 0 again: t
  // behind the last packet of its type (by less than half the 32-bit range:
  // not a wrap of t) with the numbering broken. A t behind with the seq
  // going on is no restart (t is the sender's business then); a restart
  // whose first delivered packet happens to continue the old numbering
  // (1 in 256) counts as none and loses nothing, which is what the seq
  // says.
  const int64_t last = last_t_[type];
  if (have_seq_ && seq != uint8_t(last_seq_ + 1) && last >= 0 && t < uint32_t(last) &&
      uint32_t(last) - t < 0x80000000u) {
    ++stats_.restarts;
    last_t_.fill(-1);
    if (seq) {
      ++stats_.seq_gaps;
      stats_.lost_packets += seq;
    }
    have_seq_ = false;
  }
  last_t_[type] = t;
  if (have_seq_) {
    const uint8_t gap = uint8_t(seq - last_seq_ - 1);
    if (gap) {
      ++stats_.seq_gaps;
      stats_.lost_packets += gap;
    }
  }
  have_seq_ = true;
  last_seq_ = seq;
}

bool LinkDecoder::pop(Packet& out) {
  if (queue_.empty()) return false;
  out = std::move(queue_.front());
  queue_.pop_front();
  return true;
}

}  // namespace eskin::link
