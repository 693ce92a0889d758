#include "host/stream/record_hdf5.h"

#include <hdf5.h>

#include <stdexcept>

namespace eskin::stream {

namespace {

constexpr hsize_t kChunkRows = 1024;

std::runtime_error h5_error(const std::string& path, const std::string& what) {
  return std::runtime_error(path + ": HDF5: " + what);
}

void string_attribute(hid_t obj, const std::string& name, const std::string& value) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, value.empty() ? 1 : value.size());
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(obj, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, value.empty() ? "" : value.c_str());
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
}

// An empty extendible int64 dataset of `width` columns (0: 1-D).
hid_t create_set(hid_t group, const char* name, size_t width) {
  const int rank = width ? 2 : 1;
  const hsize_t dims[2] = {0, width};
  const hsize_t maxdims[2] = {H5S_UNLIMITED, width};
  const hsize_t chunk[2] = {width ? std::max<hsize_t>(1, kChunkRows / width * 8) : kChunkRows,
                            width};
  const hid_t space = H5Screate_simple(rank, dims, maxdims);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, rank, chunk);
  // Rows are only appended: the cache needs the last, partly written chunk
  // and the next, not HDF5's default 1 MiB per dataset, which a rare table
  // (STATUS: one row per thousand frames) would take hours to fill.
  const hid_t dapl = H5Pcreate(H5P_DATASET_ACCESS);
  H5Pset_chunk_cache(dapl, 11, 2 * chunk[0] * (width ? width : 1) * sizeof(int64_t), 1.0);
  const hid_t set = H5Dcreate2(group, name, H5T_STD_I64LE, space, H5P_DEFAULT, dcpl, dapl);
  H5Pclose(dapl);
  H5Pclose(dcpl);
  H5Sclose(space);
  return set;
}

// False when HDF5 refused (the caller names the file and table).
bool append_rows(hid_t set, const int64_t* data, hsize_t old_rows, hsize_t rows, size_t width) {
  const int rank = width ? 2 : 1;
  const hsize_t new_dims[2] = {old_rows + rows, width};
  if (H5Dset_extent(set, new_dims) < 0) return false;
  const hid_t fspace = H5Dget_space(set);
  const hsize_t start[2] = {old_rows, 0};
  const hsize_t count[2] = {rows, width};
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hid_t mspace = H5Screate_simple(rank, count, nullptr);
  const herr_t rc = H5Dwrite(set, H5T_NATIVE_INT64, mspace, fspace, H5P_DEFAULT, data);
  H5Sclose(mspace);
  H5Sclose(fspace);
  return rc >= 0;
}

// An empty extendible 1-D dataset of variable-length UTF-8 strings.
hid_t create_string_set(hid_t group, const char* name) {
  const hsize_t dims[1] = {0}, maxdims[1] = {H5S_UNLIMITED}, chunk[1] = {64};
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t space = H5Screate_simple(1, dims, maxdims);
  const hid_t dcpl = H5Pcreate(H5P_DATASET_CREATE);
  H5Pset_chunk(dcpl, 1, chunk);
  const hid_t set = H5Dcreate2(group, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT);
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Tclose(type);
  return set;
}

bool append_strings(hid_t set, const std::vector<const char*>& v, hsize_t old_rows) {
  const hsize_t rows = v.size();
  const hsize_t new_dims[1] = {old_rows + rows};
  if (H5Dset_extent(set, new_dims) < 0) return false;
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  const hid_t fspace = H5Dget_space(set);
  const hsize_t start[1] = {old_rows}, count[1] = {rows};
  H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start, nullptr, count, nullptr);
  const hid_t mspace = H5Screate_simple(1, count, nullptr);
  const herr_t rc = H5Dwrite(set, type, mspace, fspace, H5P_DEFAULT, v.data());
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Tclose(type);
  return rc >= 0;
}

}  // namespace

Hdf5Recorder::Hdf5Recorder(const std::string& path,
                           const std::map<std::string, std::string>& attributes)
    : path_(path) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5AC_cache_config_t mdc;
  mdc.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  H5Pget_mdc_config(fapl, &mdc);
  // Nothing leaves the metadata cache except in flush() (see header).
  mdc.evictions_enabled = false;
  // What flush() lets it keep: the chunk indexes' B-tree nodes take several
  // times their on-disk size (the size the cache counts) in memory, so
  // 256 KiB holds a few MiB; the appends touch only each index's last nodes.
  mdc.set_initial_size = true;
  mdc.initial_size = 256 * 1024;
  mdc.min_size = 64 * 1024;
  mdc.incr_mode = H5C_incr__off;
  mdc.flash_incr_mode = H5C_flash_incr__off;
  mdc.decr_mode = H5C_decr__off;
  H5Pset_mdc_config(fapl, &mdc);
  H5E_BEGIN_TRY { file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl); }
  H5E_END_TRY;
  H5Pclose(fapl);
  if (file_ < 0) throw h5_error(path, "cannot create the file");
  for (const auto& [k, v] : attributes) string_attribute(file_, k, v);
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
}

Hdf5Recorder::~Hdf5Recorder() {
  try {
    flush();
  } catch (...) {
  }
  for (auto& [name, t] : tables_) {
    for (hid_t s : t.scalar_sets) H5Dclose(s);
    if (t.vector_set >= 0) H5Dclose(t.vector_set);
    H5Gclose(t.group);
  }
  for (hid_t s : command_sets_) H5Dclose(s);
  if (commands_group_ >= 0) H5Gclose(commands_group_);
  if (file_ >= 0) H5Fclose(file_);
}

Hdf5Recorder::Table& Hdf5Recorder::table(const PacketKind& kind, size_t width) {
  auto it = tables_.find(kind.table);
  if (it != tables_.end()) return it->second;
  Table t;
  t.group = H5Gcreate2(file_, kind.table, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (t.group < 0) throw h5_error(path_, std::string("cannot create group /") + kind.table);
  for (const char* c : kind.scalars) t.scalar_sets.push_back(create_set(t.group, c, 0));
  if (kind.vector_name) {
    t.width = width;
    t.vector_set = create_set(t.group, kind.vector_name, width ? width : 1);
  }
  t.pending_scalars.resize(kind.scalars.size());
  return tables_.emplace(kind.table, std::move(t)).first->second;
}

void Hdf5Recorder::write(const PacketKind& kind, const std::vector<Row>& rows) {
  for (const Row& r : rows) {
    Table& t = table(kind, r.values.size());
    if (t.vector_set >= 0 && r.values.size() != (t.width ? t.width : 0)) {
      ++rejected_;
      continue;
    }
    for (size_t i = 0; i < t.pending_scalars.size(); ++i)
      t.pending_scalars[i].push_back(i < r.scalars.size() ? r.scalars[i] : 0);
    t.pending_values.insert(t.pending_values.end(), r.values.begin(), r.values.end());
    ++t.pending_rows;
    ++pending_;
  }
  if (pending_ >= kFlushRows) flush();
}

void Hdf5Recorder::append(const std::string& name, Table& t) {
  if (t.pending_rows == 0) return;
  bool ok = true;
  for (size_t i = 0; i < t.scalar_sets.size(); ++i) {
    ok &= append_rows(t.scalar_sets[i], t.pending_scalars[i].data(), t.rows_on_disk,
                      t.pending_rows, 0);
    t.pending_scalars[i].clear();
  }
  if (t.vector_set >= 0 && t.width > 0)
    ok &= append_rows(t.vector_set, t.pending_values.data(), t.rows_on_disk, t.pending_rows,
                      t.width);
  if (!ok) throw h5_error(path_, "cannot append " + std::to_string(t.pending_rows) + " rows to /" + name);
  t.pending_values.clear();
  t.rows_on_disk += t.pending_rows;
  t.pending_rows = 0;
}

void Hdf5Recorder::command(const CommandRecord& c) { pending_commands_.push_back(c); }

void Hdf5Recorder::append_commands() {
  if (pending_commands_.empty()) return;
  const auto& cols = command_columns();
  if (commands_group_ < 0) {
    commands_group_ = H5Gcreate2(file_, "commands", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (commands_group_ < 0) throw h5_error(path_, "cannot create group /commands");
    for (const char* c : cols) {
      const std::string n = c;
      const bool text = n == "command" || n == "args" || n == "ack" || n == "message";
      command_sets_.push_back(text ? create_string_set(commands_group_, c)
                                   : create_set(commands_group_, c, 0));
    }
  }
  std::vector<std::string> args;
  for (const CommandRecord& r : pending_commands_) {
    std::string a;
    for (const std::string& x : r.args) a += (a.empty() ? "" : " ") + x;
    args.push_back(a);
  }
  bool ok = true;
  for (size_t i = 0; i < cols.size(); ++i) {
    const std::string n = cols[i];
    std::vector<const char*> text;
    std::vector<int64_t> ints;
    for (size_t k = 0; k < pending_commands_.size(); ++k) {
      const CommandRecord& r = pending_commands_[k];
      if (n == "command") text.push_back(r.command.c_str());
      else if (n == "args") text.push_back(args[k].c_str());
      else if (n == "ack") text.push_back(r.ack.c_str());
      else if (n == "message") text.push_back(r.message.c_str());
      else if (n == "host_ms") ints.push_back(r.host_ms);
      else if (n == "samples") ints.push_back(r.samples);
      else if (n == "cmd_type") ints.push_back(r.cmd_type);
      else ints.push_back(r.seq);
    }
    ok &= text.empty() ? append_rows(command_sets_[i], ints.data(), commands_on_disk_,
                                     ints.size(), 0)
                       : append_strings(command_sets_[i], text, commands_on_disk_);
  }
  if (!ok) throw h5_error(path_, "cannot append to /commands");
  commands_on_disk_ += pending_commands_.size();
  pending_commands_.clear();
}

void Hdf5Recorder::flush() {
  if (file_ < 0) return;
  // The metadata cache may evict (and so write) only in here, where the
  // file changes anyway: without evictions it would keep every chunk index
  // node the recording ever touched, growing with the file.
  set_evictions(true);
  for (auto& [name, t] : tables_) append(name, t);
  append_commands();
  pending_ = 0;
  const bool flushed = H5Fflush(file_, H5F_SCOPE_GLOBAL) >= 0;
  set_evictions(false);
  if (!flushed) throw h5_error(path_, "flush failed");
}

void Hdf5Recorder::set_evictions(bool on) {
  H5AC_cache_config_t mdc;
  mdc.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Fget_mdc_config(file_, &mdc) < 0) return;
  mdc.evictions_enabled = on;
  H5Fset_mdc_config(file_, &mdc);
}

}  // namespace eskin::stream
