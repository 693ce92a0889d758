#include "host/link/link_encoder.h"

#include <array>
#include <stdexcept>

namespace eskin::link {

namespace {

std::array<uint16_t, 256> make_table() {
  std::array<uint16_t, 256> t{};
  for (int i = 0; i < 256; ++i) {
    uint16_t c = uint16_t(i << 8);
    for (int b = 0; b < 8; ++b) c = (c & 0x8000) ? uint16_t((c << 1) ^ 0x1021) : uint16_t(c << 1);
    t[size_t(i)] = c;
  }
  return t;
}

void put16(std::vector<uint8_t>& v, uint16_t x) {
  v.push_back(uint8_t(x));
  v.push_back(uint8_t(x >> 8));
}
void put32(std::vector<uint8_t>& v, uint32_t x) {
  for (int i = 0; i < 4; ++i) v.push_back(uint8_t(x >> (8 * i)));
}

}  // namespace

uint16_t crc16_table(const uint8_t* data, size_t n, uint16_t crc) {
  static const std::array<uint16_t, 256> table = make_table();
  for (size_t i = 0; i < n; ++i)
    crc = uint16_t((crc << 8) ^ table[((crc >> 8) ^ data[i]) & 0xFF]);
  return crc;
}

std::vector<uint8_t> cobs_encode(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> out;
  out.reserve(raw.size() + raw.size() / 254 + 2);
  size_t code_pos = out.size();
  out.push_back(0);  // placeholder for the first code byte
  uint8_t code = 1;
  for (uint8_t b : raw) {
    if (b == 0) {
      out[code_pos] = code;
      code_pos = out.size();
      out.push_back(0);
      code = 1;
      continue;
    }
    out.push_back(b);
    if (++code == 0xFF) {
      out[code_pos] = code;
      code_pos = out.size();
      out.push_back(0);
      code = 1;
    }
  }
  out[code_pos] = code;
  return out;
}

std::vector<uint8_t> raw_frame(uint8_t type, uint8_t seq, uint32_t t,
                               const std::vector<uint8_t>& payload) {
  if (payload.size() > 0xFFFF)
    throw std::invalid_argument("payload: at most 65535 bytes, got " +
                                std::to_string(payload.size()));
  std::vector<uint8_t> raw{type, seq};
  put32(raw, t);
  put16(raw, uint16_t(payload.size()));
  raw.insert(raw.end(), payload.begin(), payload.end());
  const uint16_t crc = crc16_table(raw.data(), raw.size());
  raw.push_back(uint8_t(crc >> 8));  // big endian: residue 0 over the frame
  raw.push_back(uint8_t(crc));
  return raw;
}

std::vector<uint8_t> LinkEncoder::frame(uint8_t type, uint32_t t,
                                        const std::vector<uint8_t>& payload) {
  std::vector<uint8_t> wire = cobs_encode(raw_frame(type, seq_++, t, payload));
  wire.push_back(0);
  return wire;
}

std::vector<uint8_t> LinkEncoder::amplitudes(uint32_t t, const std::vector<uint16_t>& mags) {
  std::vector<uint8_t> p;
  for (uint16_t m : mags) put16(p, m);
  return frame(kAmplitudes, t, p);
}

std::vector<uint8_t> LinkEncoder::taxels_dense(uint32_t t, uint8_t rows, uint8_t cols,
                                               const std::vector<uint16_t>& values) {
  if (values.size() != size_t(rows) * cols)
    throw std::invalid_argument("taxels_dense: values must hold rows*cols entries");
  std::vector<uint8_t> p{rows, cols};
  for (uint16_t v : values) put16(p, v);
  return frame(kTaxelsDense, t, p);
}

std::vector<uint8_t> LinkEncoder::taxels_sparse(uint32_t t, const std::vector<SparseTaxel>& taxels) {
  std::vector<uint8_t> p;
  for (const SparseTaxel& x : taxels) {
    p.push_back(x.row);
    p.push_back(x.col);
    put16(p, x.value);
  }
  return frame(kTaxelsSparse, t, p);
}

std::vector<uint8_t> LinkEncoder::spikes(uint32_t t, const std::vector<SpikeEvent>& events) {
  std::vector<uint8_t> p;
  for (const SpikeEvent& e : events) {
    put16(p, e.dt);
    p.push_back(e.layer);
    put16(p, e.neuron);
  }
  return frame(kSpikes, t, p);
}

std::vector<uint8_t> LinkEncoder::status(uint32_t t, const StatusBlock& s) {
  std::vector<uint8_t> p;
  put16(p, s.cmd_crc_errors);
  put16(p, s.cmd_frame_errors);
  put16(p, s.cmd_accepted);
  put16(p, s.cmd_rejected);
  p.push_back(s.last_reject_type);
  p.push_back(s.last_reject_reason);
  p.push_back(s.last_reject_seq);
  p.push_back(s.output_mask);
  put16(p, s.dropped_frames);
  put16(p, s.adc_overruns);
  put16(p, s.uart_rx_errors);
  put16(p, s.frame_overruns);
  put16(p, s.spikes_dropped);
  put16(p, s.cmd_overflows);
  put32(p, s.samples);
  return frame(kStatus, t, p);
}

std::vector<uint8_t> LinkEncoder::command(uint8_t type, uint32_t index, uint32_t value) {
  const DtmfCommand* c = find_dtmf_command(type);
  if (!c) throw std::invalid_argument("LinkEncoder::command: no command of type " + std::to_string(type));
  return frame(type, 0, dtmf_command_payload(*c, index, value));
}

std::vector<uint8_t> LinkEncoder::set_carrier_inc(uint8_t k, uint32_t inc) {
  return command(kCmdSetCarrierInc, k, inc);
}
std::vector<uint8_t> LinkEncoder::set_threshold(uint8_t id, uint16_t value) {
  return command(kCmdSetThreshold, id, value);
}
std::vector<uint8_t> LinkEncoder::set_neuron(uint8_t id, int32_t value) {
  return command(kCmdSetNeuron, id, uint32_t(value));
}
std::vector<uint8_t> LinkEncoder::set_output_mask(uint8_t mask) {
  return command(kCmdSetOutputMask, 0, mask);
}
std::vector<uint8_t> LinkEncoder::set_decimation(uint8_t stream, uint16_t value) {
  return command(kCmdSetDecimation, stream, value);
}
std::vector<uint8_t> LinkEncoder::request_status() { return command(kCmdRequestStatus, 0, 0); }
std::vector<uint8_t> LinkEncoder::clear_counters() { return command(kCmdClearCounters, 0, 0); }
std::vector<uint8_t> LinkEncoder::set_weight(uint8_t id, int16_t value) {
  return command(kCmdSetWeight, id, uint16_t(value));
}
std::vector<uint8_t> LinkEncoder::set_demix_coef(uint16_t index, int16_t value) {
  return command(kCmdSetDemixCoef, index, uint16_t(value));
}

}  // namespace eskin::link
