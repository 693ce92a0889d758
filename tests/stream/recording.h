// What a stream recording must hold, for the CLI tests: the NDJSON lines
// the user must see for the packets a test sent (derived from the payload
// bytes, not from the code under test), and the HDF5 file read back with
// the HDF5 C API and compared table by table.
#pragma once

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "host/link/link_decoder.h"
#include "tests/stream/frames.h"

namespace eskin::testing {

using nlohmann::json;

inline uint16_t le16(const std::vector<uint8_t>& b, size_t i) { return uint16_t(b[i] | (b[i + 1] << 8)); }

// What the user must see for `sent`, derived from the payload bytes (the
// wire layout of docs/protocol.md §4), one entry per NDJSON line.
inline std::vector<json> expected_lines(const std::vector<Sent>& sent) {
  std::vector<json> v;
  for (const Sent& s : sent) {
    if (s.type == eskin::link::kAmplitudes) {
      json amp = json::array();
      for (size_t i = 0; i < s.payload.size(); i += 2) amp.push_back(le16(s.payload, i));
      v.push_back({{"type", "amplitudes"}, {"seq", s.seq}, {"t", s.t}, {"amp", amp}});
    } else if (s.type == eskin::link::kTaxelsDense) {
      json tax = json::array();
      for (size_t i = 2; i < s.payload.size(); i += 2) tax.push_back(le16(s.payload, i));
      v.push_back({{"type", "taxels"}, {"seq", s.seq}, {"t", s.t}, {"rows", s.payload[0]},
                   {"cols", s.payload[1]}, {"taxel", tax}});
    } else if (s.type == eskin::link::kTaxelsSparse) {
      for (size_t i = 0; i < s.payload.size(); i += 4)
        v.push_back({{"type", "taxels_sparse"}, {"seq", s.seq}, {"t", s.t}, {"row", s.payload[i]},
                     {"col", s.payload[i + 1]}, {"value", le16(s.payload, i + 2)}});
    } else if (s.type == eskin::link::kSpikes) {
      for (size_t i = 0; i < s.payload.size(); i += 5)
        v.push_back({{"type", "spikes"}, {"seq", s.seq}, {"t", s.t + le16(s.payload, i)},
                     {"layer", s.payload[i + 2]}, {"neuron", le16(s.payload, i + 3)}});
    } else if (s.type == eskin::link::kStatus) {
      // The 28-byte block: u16 fields, the four u8 fields at 8..11, u32 samples at 24.
      json j = {{"type", "status"}, {"seq", s.seq}, {"t", s.t}};
      const char* u16[] = {"cmd_crc_errors", "cmd_frame_errors", "cmd_accepted", "cmd_rejected"};
      for (size_t k = 0; k < 4; ++k) j[u16[k]] = le16(s.payload, 2 * k);
      const char* u8[] = {"last_reject_type", "last_reject_reason", "last_reject_seq",
                          "output_mask"};
      for (size_t k = 0; k < 4; ++k) j[u8[k]] = s.payload[8 + k];
      const char* more[] = {"dropped_frames", "adc_overruns",   "uart_rx_errors",
                            "frame_overruns", "spikes_dropped", "cmd_overflows"};
      for (size_t k = 0; k < 6; ++k) j[more[k]] = le16(s.payload, 12 + 2 * k);
      j["samples"] = uint32_t(le16(s.payload, 24) | uint32_t(le16(s.payload, 26)) << 16);
      v.push_back(j);
    }
  }
  return v;
}

// NDJSON lines `sent` makes, all types (docs/streaming.md: one row per
// packet, per active sparse taxel, per spike): what to wait for on stdout.
inline size_t ndjson_rows(const std::vector<Sent>& sent) {
  size_t n = 0;
  for (const Sent& s : sent)
    n += s.type == eskin::link::kTaxelsSparse ? s.payload.size() / 4
         : s.type == eskin::link::kSpikes     ? s.payload.size() / 5
                                              : 1;
  return n;
}

inline std::vector<json> parse_ndjson(const std::string& text) {
  std::vector<json> v;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) v.push_back(json::parse(line));
  return v;
}

// Reads an int64 dataset (1-D or 2-D) of an HDF5 file, with its dims.
inline std::vector<int64_t> read_set(hid_t file, const std::string& name, std::vector<hsize_t>& dims) {
  const hid_t d = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  if (d < 0) return {};
  const hid_t sp = H5Dget_space(d);
  dims.assign(size_t(H5Sget_simple_extent_ndims(sp)), 0);
  H5Sget_simple_extent_dims(sp, dims.data(), nullptr);
  hsize_t n = 1;
  for (hsize_t x : dims) n *= x;
  std::vector<int64_t> v(n);
  if (n) H5Dread(d, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(sp);
  H5Dclose(d);
  return v;
}

inline std::string read_attr(hid_t file, const char* name) {
  const hid_t a = H5Aopen(file, name, H5P_DEFAULT);
  if (a < 0) return "<missing>";
  const hid_t t = H5Aget_type(a);
  std::string s(H5Tget_size(t), '\0');
  H5Aread(a, t, s.data());
  H5Tclose(t);
  H5Aclose(a);
  return std::string(s.c_str());
}

// The HDF5 file holds exactly the expected lines' values, table by table.
inline void expect_hdf5_matches(const std::string& path, const std::vector<json>& want) {
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0) << path << " does not open";
  std::vector<hsize_t> dims;
  for (const char* table : {"amplitudes", "taxels", "taxels_sparse", "spikes", "status"}) {
    std::vector<const json*> rows;
    for (const json& j : want)
      if (j["type"] == table) rows.push_back(&j);
    if (rows.empty()) {  // no packet of the type: no group
      EXPECT_LE(H5Lexists(f, table, H5P_DEFAULT), 0) << table;
      continue;
    }
    // Every scalar column of the expected rows, by name.
    for (const auto& [column, value] : rows[0]->items()) {
      if (column == "type" || value.is_array()) continue;
      const auto got = read_set(f, std::string("/") + table + "/" + column, dims);
      ASSERT_EQ(got.size(), rows.size()) << table << "/" << column;
      for (size_t i = 0; i < rows.size(); ++i)
        ASSERT_EQ(got[i], (*rows[i])[column].get<int64_t>()) << table << "/" << column << " row " << i;
    }
    const char* vec = std::string(table) == "amplitudes" ? "amp"
                      : std::string(table) == "taxels"   ? "taxel"
                                                         : nullptr;
    if (!vec || rows.empty()) continue;
    const auto v = read_set(f, std::string("/") + table + "/" + vec, dims);
    ASSERT_EQ(dims.size(), 2u);
    ASSERT_EQ(dims[0], rows.size());
    for (size_t i = 0; i < rows.size(); ++i)
      for (size_t k = 0; k < dims[1]; ++k)
        ASSERT_EQ(v[i * dims[1] + k], (*rows[i])[vec][k].get<int64_t>()) << table << " " << i;
  }
  H5Fclose(f);
}

inline size_t lines(const std::string& s) { return size_t(std::count(s.begin(), s.end(), '\n')); }

}  // namespace eskin::testing
