// Dataset: opens and validates a dataset file field by field, then reads
// frame ranges lazily (hyperslabs), keeping only a few dataset handles open.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <vector>

#include "data/dataset_on_hdf5.hpp"
#include "data/h5_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace fs = std::filesystem;

namespace {
constexpr size_t kChunkCacheBytes = 4u << 20;  // per open sequence: ~14 chunks of 32 frames
constexpr size_t kOpenSequences = 16;          // dataset handles (each with its chunk cache) kept open
constexpr hsize_t kMaxFrames = 0x7fffffff;     // frames of one sequence (an int)
constexpr long kMaxCells = 1L << 24;           // cells of one mat frame

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

int member_index(const H5::CompType& type, const std::string& name) {
  for (int i = 0; i < type.getNmembers(); ++i)
    if (type.getMemberName(i) == name) return i;
  return -1;
}

// Reads one numeric column of a compound dataset as double.
std::vector<double> read_number_column(const H5::DataSet& ds, const std::string& name, size_t n) {
  std::vector<double> out(n);
  H5::CompType mem(sizeof(double));
  mem.insertMember(name, 0, H5::PredType::NATIVE_DOUBLE);
  if (n) ds.read(out.data(), mem);
  return out;
}

// Reads one string column (fixed-length or variable-length) of a compound dataset.
std::vector<std::string> read_string_column(const H5::DataSet& ds, const H5::CompType& file_type,
                                            int index, size_t n) {
  const std::string name = file_type.getMemberName(index);
  H5::StrType ftype = file_type.getMemberStrType(index);
  std::vector<std::string> out(n);
  if (!n) return out;
  if (ftype.isVariableStr()) {
    H5::StrType stype(H5::PredType::C_S1, H5T_VARIABLE);
    stype.setCset(ftype.getCset());  // HDF5 does not convert between ASCII and UTF-8
    H5::CompType mem(sizeof(char*));
    mem.insertMember(name, 0, stype);
    std::vector<char*> ptrs(n, nullptr);
    ds.read(ptrs.data(), mem);
    for (size_t i = 0; i < n; ++i) out[i] = ptrs[i] ? ptrs[i] : "";
    H5Dvlen_reclaim(mem.getId(), ds.getSpace().getId(), H5P_DEFAULT, ptrs.data());
  } else {
    const size_t len = ftype.getSize();
    H5::StrType stype(H5::PredType::C_S1, len);
    stype.setStrpad(ftype.getStrpad());
    stype.setCset(ftype.getCset());
    H5::CompType mem(len);
    mem.insertMember(name, 0, stype);
    std::vector<char> buf(n * len, 0);
    ds.read(buf.data(), mem);
    for (size_t i = 0; i < n; ++i) {
      std::string s(buf.data() + i * len, len);
      s.erase(std::find(s.begin(), s.end(), '\0'), s.end());
      while (!s.empty() && s.back() == ' ') s.pop_back();  // space-padded writers
      out[i] = s;
    }
  }
  return out;
}
}  // namespace

struct Dataset::Impl {
  std::string path;
  DatasetInfo info;
  std::vector<BodySpec> bodies;
  std::vector<SequenceMeta> sequences;
  std::map<std::string, size_t> body_index, sequence_index;
  H5::H5File file;
  mutable std::vector<std::pair<std::string, H5::DataSet>> open_sets;  // most recent last

  void read_structure();
  void read_root();
  void read_bodies();
  void read_sequences();
  void read_floors();
  const H5::DataSet& dataset(const std::string& name) const;
  void read_block(const H5::DataSet& ds, const std::string& what, int start, int count, float* out) const;
};

void Dataset::Impl::read_root() {
  H5::Group root = file.openGroup("/");
  const std::string where = "root group";
  if (!h5::has_attr(root, "format"))
    throw Error::in(path, "not a ptnet dataset (HDF5 file without a 'format' attribute)");
  std::string format = h5::read_string_attr(root, "format", path, where);
  if (format != kDatasetFormat)
    throw Error::in(path, "not a ptnet dataset (format " + escaped(format) + ", expected '" +
                              kDatasetFormat + "')");
  long version = h5::read_integer_attr(root, "version", path, where);
  if (version != kDatasetVersion)
    throw Error::in(path, "unsupported dataset version " + std::to_string(version) +
                              " (this ptnet reads version " + std::to_string(kDatasetVersion) + ")");
  info.fps = h5::read_number_attr(root, "fps", path, where);
  if (!(info.fps > 0)) throw Error::in(path, "root attribute 'fps' must be positive");
  long rows = h5::read_integer_attr(root, "rows", path, where);
  long cols = h5::read_integer_attr(root, "cols", path, where);
  if (rows <= 0 || cols <= 0 || rows > 100000 || cols > 100000)
    throw Error::in(path, "root attributes rows " + std::to_string(rows) + ", cols " +
                              std::to_string(cols) + " must be positive");
  if (rows * cols > kMaxCells)
    throw Error::in(path, "root attributes rows " + std::to_string(rows) + " x cols " + std::to_string(cols) +
                              ": more than the " + std::to_string(kMaxCells) + " cells a mat may have");
  info.mat.rows = int(rows);
  info.mat.cols = int(cols);
  info.mat.pitch_m = h5::read_number_attr(root, "pitch_m", path, where);
  if (!(info.mat.pitch_m > 0)) throw Error::in(path, "root attribute 'pitch_m' must be positive");
  std::string units = h5::read_string_attr(root, "units", path, where);
  if (units != "kPa")
    throw Error::in(path, "root attribute 'units' is " + escaped(units) + ", expected 'kPa'");
  info.generator = h5::has_attr(root, "generator")
                       ? h5::read_string_attr(root, "generator", path, where) : "";
  info.config_json = h5::has_attr(root, "config")
                         ? h5::read_string_attr(root, "config", path, where) : "{}";
}

void Dataset::Impl::read_bodies() {
  if (!file.nameExists("bodies") || file.childObjType("bodies") != H5O_TYPE_DATASET)
    throw Error::in(path, "missing /bodies table");
  H5::DataSet ds = file.openDataSet("bodies");
  h5::check_local_storage(ds, path, "/bodies");
  if (ds.getTypeClass() != H5T_COMPOUND)
    throw Error::in(path, "/bodies is not a table (compound dataset)");
  H5::CompType type = ds.getCompType();
  H5::DataSpace space = ds.getSpace();
  if (space.getSimpleExtentNdims() != 1) throw Error::in(path, "/bodies must be one-dimensional");
  const size_t n = size_t(space.getSimpleExtentNpoints());
  for (const char* field : {"id", "sex", "height_cm", "weight_kg"}) {
    int i = member_index(type, field);
    if (i < 0) throw Error::in(path, std::string("/bodies has no field '") + field + "'");
    H5T_class_t cls = type.getMemberClass(i);
    bool is_string = std::string(field) == "id";
    if (is_string ? cls != H5T_STRING : (cls != H5T_INTEGER && cls != H5T_FLOAT))
      throw Error::in(path, std::string("/bodies field '") + field + "' is not a " +
                                (is_string ? "string" : "number"));
  }
  auto ids = read_string_column(ds, type, member_index(type, "id"), n);
  auto sex = read_number_column(ds, "sex", n);
  auto height = read_number_column(ds, "height_cm", n);
  auto weight = read_number_column(ds, "weight_kg", n);
  int role_i = member_index(type, "role");
  std::vector<std::string> roles(n, "retargeted");
  if (role_i >= 0 && type.getMemberClass(role_i) == H5T_STRING)
    roles = read_string_column(ds, type, role_i, n);
  for (size_t i = 0; i < n; ++i) {
    const std::string where = "/bodies row " + std::to_string(i) + " (" + escaped(ids[i]) + ")";
    if (ids[i].empty()) throw Error::in(path, "/bodies row " + std::to_string(i) + ": empty id");
    if (utf8_invalid_at(ids[i]) != std::string::npos || utf8_invalid_at(roles[i]) != std::string::npos)
      throw Error::in(path, where + ": id or role is not UTF-8");
    if (sex[i] != 0 && sex[i] != 1)
      throw Error::in(path, where + ": sex " + number_text(sex[i]) + ", expected 0 (female) or 1 (male)");
    const BodySpec b{ids[i], sex[i] == 1 ? Sex::male : Sex::female, height[i], weight[i], roles[i]};
    const std::string problem = body_range_problem(b);
    if (!problem.empty()) throw Error::in(path, where + ": " + problem);
    if (!body_index.emplace(ids[i], bodies.size()).second)
      throw Error::in(path, where + ": id appears twice");
    bodies.push_back(b);
  }
}

void Dataset::Impl::read_sequences() {
  if (!file.nameExists("sequences") || file.childObjType("sequences") != H5O_TYPE_GROUP)
    throw Error::in(path, "missing /sequences group");
  H5::Group group = file.openGroup("sequences");
  const hsize_t n = group.getNumObjs();
  for (hsize_t i = 0; i < n; ++i) {
    SequenceMeta m;
    m.name = group.getObjnameByIdx(i);
    const std::string where = "sequence " + escaped(m.name, 80);
    if (utf8_invalid_at(m.name) != std::string::npos) throw Error::in(path, where + ": the name is not UTF-8");
    if (group.childObjType(m.name) != H5O_TYPE_DATASET)
      throw Error::in(path, "/sequences/" + m.name + " is not a dataset");
    H5::DataSet ds = group.openDataSet(m.name);
    h5::check_local_storage(ds, path, where);
    H5::DataSpace space = ds.getSpace();
    const int rank = space.getSimpleExtentNdims();
    std::vector<hsize_t> dims(std::max(rank, 0));
    space.getSimpleExtentDims(dims.data());
    if (rank != 3 || dims[1] != hsize_t(info.mat.rows) || dims[2] != hsize_t(info.mat.cols))
      throw Error::in(path, where + " has shape " + shape_text(dims) + ", expected [T, " +
                                std::to_string(info.mat.rows) + ", " +
                                std::to_string(info.mat.cols) + "] (root attributes rows, cols)");
    if (dims[0] == 0) throw Error::in(path, where + " has no frames");
    if (dims[0] > hsize_t(kMaxFrames))
      throw Error::in(path, where + " has " + std::to_string(dims[0]) + " frames, more than the " +
                                std::to_string(kMaxFrames) + " a sequence may have");
    if (ds.getTypeClass() != H5T_FLOAT || ds.getFloatType().getSize() != 4)
      throw Error::in(path, where + " is not float32");
    m.frames = int(dims[0]);
    m.body_id = h5::read_string_attr(ds, "body_id", path, where);
    if (!body_index.count(m.body_id))
      throw Error::in(path, where + ": body_id " + escaped(m.body_id) + " not in /bodies");
    m.motion_id = h5::read_string_attr(ds, "motion_id", path, where);
    m.category = h5::read_string_attr(ds, "category", path, where);
    m.take = int(h5::read_integer_attr(ds, "take", path, where));
    if (h5::has_attr(ds, "performer")) m.performer = h5::read_string_attr(ds, "performer", path, where);
    if (h5::has_attr(ds, "source")) m.source = h5::read_string_attr(ds, "source", path, where);
    sequence_index[m.name] = sequences.size();
    sequences.push_back(std::move(m));
  }
}

// /floor/<name>: optional; each must be float32 of its sequence's shape.
void Dataset::Impl::read_floors() {
  if (!file.nameExists("floor")) return;
  if (file.childObjType("floor") != H5O_TYPE_GROUP) throw Error::in(path, "/floor is not a group");
  H5::Group group = file.openGroup("floor");
  const hsize_t n = group.getNumObjs();
  for (hsize_t i = 0; i < n; ++i) {
    const std::string name = group.getObjnameByIdx(i);
    const std::string where = "/floor/" + name;
    const auto it = sequence_index.find(name);
    if (it == sequence_index.end()) throw Error::in(path, where + ": no sequence '" + name + "'");
    if (group.childObjType(name) != H5O_TYPE_DATASET) throw Error::in(path, where + " is not a dataset");
    H5::DataSet ds = group.openDataSet(name);
    h5::check_local_storage(ds, path, where);
    H5::DataSpace space = ds.getSpace();
    const int rank = space.getSimpleExtentNdims();
    std::vector<hsize_t> dims(std::max(rank, 0));
    space.getSimpleExtentDims(dims.data());
    SequenceMeta& m = sequences[it->second];
    if (rank != 3 || dims[0] != hsize_t(m.frames) || dims[1] != hsize_t(info.mat.rows) ||
        dims[2] != hsize_t(info.mat.cols))
      throw Error::in(path, where + " has shape " + shape_text(dims) + ", expected that of its sequence [" +
                                std::to_string(m.frames) + ", " + std::to_string(info.mat.rows) + ", " +
                                std::to_string(info.mat.cols) + "]");
    if (ds.getTypeClass() != H5T_FLOAT || ds.getFloatType().getSize() != 4)
      throw Error::in(path, where + " is not float32");
    m.floor = true;
  }
}

const H5::DataSet& Dataset::Impl::dataset(const std::string& name) const {
  for (size_t i = 0; i < open_sets.size(); ++i) {
    if (open_sets[i].first == name) {
      if (i + 1 != open_sets.size()) std::rotate(open_sets.begin() + i, open_sets.begin() + i + 1, open_sets.end());
      return open_sets.back().second;
    }
  }
  if (open_sets.size() >= kOpenSequences) open_sets.erase(open_sets.begin());
  H5::DSetAccPropList dapl;
  dapl.setChunkCache(521, kChunkCacheBytes, 1.0);
  open_sets.emplace_back(name, file.openDataSet("sequences/" + name, dapl));
  return open_sets.back().second;
}

Dataset::Dataset() : impl_(std::make_unique<Impl>()) {}
Dataset::Dataset(Dataset&&) noexcept = default;
Dataset& Dataset::operator=(Dataset&&) noexcept = default;
Dataset::~Dataset() = default;

// Reads and validates everything but the frames from the open file. Links
// first: the reads after them resolve names, which follows links.
void Dataset::Impl::read_structure() {
  try {
    h5::check_hard_links(file, path);
    read_root();
    read_bodies();
    read_sequences();
    read_floors();
  } catch (const H5::Exception& e) {
    std::string why = h5::error_stack_text();
    throw Error::in(path, "damaged HDF5 file: " + (why.empty() ? e.getFuncName() + ": " + e.getDetailMsg() : why));
  }
}

Dataset Dataset::open(const std::string& path) {
  h5::quiet();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error::in(path, "no such file", ErrorKind::not_found);
  if (fs::is_directory(path, ec)) throw Error::in(path, "is a folder, expected an HDF5 dataset file");
  if (!fs::is_regular_file(path, ec)) throw Error::in(path, "is not a regular file, expected an HDF5 dataset file");
  note_input(path);
  bool is_hdf5 = false;
  try {
    is_hdf5 = H5::H5File::isHdf5(path);
  } catch (const H5::Exception&) {
    is_hdf5 = false;
  }
  if (!is_hdf5) throw Error::in(path, "not an HDF5 file (no HDF5 signature)");
  Dataset d;
  d.impl_->path = path;
  try {
    d.impl_->file = H5::H5File(path, H5F_ACC_RDONLY);
  } catch (const H5::Exception&) {
    std::string why = h5::error_stack_text();
    if (why.find("truncated") != std::string::npos) {
      auto size = fs::file_size(path, ec);
      throw Error::in(path, "truncated HDF5 file (" + std::to_string(size) +
                                " bytes; the end of the file is missing)");
    }
    throw Error::in(path, "damaged HDF5 file: " + (why.empty() ? "cannot open" : why));
  }
  d.impl_->read_structure();
  return d;
}

Dataset DatasetOnHdf5::open(const H5::H5File& file, const std::string& name) {
  Dataset d;
  d.impl_->path = name;
  d.impl_->file = file;
  d.impl_->read_structure();
  return d;
}

const std::string& Dataset::path() const { return impl_->path; }
const DatasetInfo& Dataset::info() const { return impl_->info; }
const std::vector<BodySpec>& Dataset::bodies() const { return impl_->bodies; }
const std::vector<SequenceMeta>& Dataset::sequences() const { return impl_->sequences; }

const BodySpec& Dataset::body(const std::string& id) const {
  auto it = impl_->body_index.find(id);
  if (it == impl_->body_index.end()) throw Error::in(impl_->path, "no body '" + id + "'");
  return impl_->bodies[it->second];
}

const SequenceMeta& Dataset::sequence(const std::string& name) const {
  auto it = impl_->sequence_index.find(name);
  if (it == impl_->sequence_index.end()) {
    std::string hint;
    if (!impl_->sequences.empty()) hint = " (e.g. '" + impl_->sequences.front().name + "'; `ptnet info` lists them)";
    throw Error::in(impl_->path, "no sequence '" + name + "'" + hint);
  }
  return impl_->sequences[it->second];
}

// out[count, rows, cols] (kPa) <- frames [start, start + count) of sequence `name`.
void Dataset::read(const std::string& name, int start, int count, float* out) const {
  const SequenceMeta& m = sequence(name);
  if (start < 0 || count < 0 || start > m.frames - count)
    throw Error::in(impl_->path, "sequence '" + name + "': frames [" + std::to_string(start) + ", " +
                                     std::to_string(long(start) + count) + ") outside its " +
                                     std::to_string(m.frames) + " frames");
  if (count == 0) return;
  const std::string what = "sequence '" + name + "'";
  try {
    impl_->read_block(impl_->dataset(name), what, start, count, out);
  } catch (const H5::Exception&) {
    throw Error::in(impl_->path,
                    what + ": cannot read frames (damaged file?): " + h5::error_stack_text(),
                    ErrorKind::io);
  }
}

// out[count, rows, cols] <- frames [start, start + count) of ds, checked finite and in range.
void Dataset::Impl::read_block(const H5::DataSet& ds, const std::string& what, int start, int count,
                               float* out) const {
  const MatSpec& mat = info.mat;
  H5::DataSpace fspace = ds.getSpace();
  hsize_t offset[3] = {hsize_t(start), 0, 0};
  hsize_t dims[3] = {hsize_t(count), hsize_t(mat.rows), hsize_t(mat.cols)};
  fspace.selectHyperslab(H5S_SELECT_SET, dims, offset);
  H5::DataSpace mspace(3, dims);
  ds.read(out, H5::PredType::NATIVE_FLOAT, mspace, fspace);
  check_pressure(out, size_t(count) * mat.cells(), mat.cells(), path, what, size_t(start));
}

PressureSequence Dataset::read(const std::string& name) const {
  const SequenceMeta& m = sequence(name);
  check_memory(checked_mul(std::uint64_t(m.frames), std::uint64_t(impl_->info.mat.cells()) * sizeof(float),
                           impl_->path, "sequence '" + name + "'"),
               impl_->path, "sequence '" + name + "'");
  PressureSequence seq(impl_->info.mat, m.frames, impl_->info.fps);
  read(name, 0, m.frames, seq.kpa.data());
  return seq;
}

PressureSequence Dataset::read_floor(const std::string& name) const {
  const SequenceMeta& m = sequence(name);
  if (!m.floor)
    throw Error::in(impl_->path, "sequence '" + name + "' has no noise-floor copy (/floor/" + name + ")");
  PressureSequence seq(impl_->info.mat, m.frames, impl_->info.fps);
  const std::string what = "/floor/" + name;
  try {
    impl_->read_block(impl_->file.openDataSet(what), what, 0, m.frames, seq.kpa.data());
  } catch (const H5::Exception&) {
    throw Error::in(impl_->path,
                    what + ": cannot read frames (damaged file?): " + h5::error_stack_text(),
                    ErrorKind::io);
  }
  return seq;
}

}  // namespace ptnet
