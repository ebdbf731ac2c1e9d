// DatasetWriter: writes the HDF5 dataset of docs/formats.md to a temporary
// file beside the target and renames it into place on commit().
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <set>
#include <vector>

#include "data/data_internal.hpp"
#include "data/deflate_chunks.hpp"
#include "data/h5_util.hpp"
#include "ptnet/strings.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {

namespace {
constexpr int kChunkFrames = 32;    // frames per chunk: a 30-frame window touches <= 2 chunks

void check_body(const std::string& file, const BodySpec& b) {
  auto where = "body '" + b.id + "'";
  if (b.id.empty()) throw Error::in(file, "a body has an empty id");
  const std::string problem = body_range_problem(b);
  if (!problem.empty()) throw Error::in(file, where + ": " + problem);
}

// /bodies: a packed compound of fixed-length UTF-8 strings and numbers, so
// that h5py reads it as a numpy structured array.
void write_bodies(H5::H5File& file, const std::vector<BodySpec>& bodies) {
  size_t id_len = 1, role_len = 1;
  for (const auto& b : bodies) {
    id_len = std::max(id_len, b.id.size());
    role_len = std::max(role_len, b.role.size());
  }
  H5::StrType id_type(H5::PredType::C_S1, id_len), role_type(H5::PredType::C_S1, role_len);
  for (H5::StrType* t : {&id_type, &role_type}) {
    t->setCset(H5T_CSET_UTF8);
    t->setStrpad(H5T_STR_NULLPAD);
  }
  const size_t off_sex = id_len, off_h = off_sex + 1, off_w = off_h + 8, off_role = off_w + 8;
  const size_t record = off_role + role_len;
  H5::CompType type(record);
  type.insertMember("id", 0, id_type);
  type.insertMember("sex", off_sex, H5::PredType::STD_I8LE);
  type.insertMember("height_cm", off_h, H5::PredType::IEEE_F64LE);
  type.insertMember("weight_kg", off_w, H5::PredType::IEEE_F64LE);
  type.insertMember("role", off_role, role_type);

  std::vector<unsigned char> buffer(record * std::max<size_t>(bodies.size(), 1), 0);
  for (size_t i = 0; i < bodies.size(); ++i) {
    unsigned char* r = buffer.data() + i * record;
    std::memcpy(r, bodies[i].id.data(), bodies[i].id.size());
    r[off_sex] = static_cast<unsigned char>(bodies[i].sex == Sex::male ? 1 : 0);
    std::memcpy(r + off_h, &bodies[i].height_cm, 8);
    std::memcpy(r + off_w, &bodies[i].weight_kg, 8);
    std::memcpy(r + off_role, bodies[i].role.data(), bodies[i].role.size());
  }
  hsize_t dims[1] = {bodies.size()};
  H5::DataSpace space(1, dims);
  H5::DSetCreatPropList plist;
  H5Pset_obj_track_times(plist.getId(), false);  // no timestamps: same input, same bytes
  H5::DataSet ds = file.createDataSet("bodies", type, space, plist);
  if (!bodies.empty()) ds.write(buffer.data(), type);
}

// A sequence's mat, fps, frame count and values, checked before writing.
void check_frames(const std::string& path, const std::string& where, const DatasetInfo& info,
                  const PressureSequence& seq) {
  const MatSpec& mat = info.mat;
  if (!(seq.mat == mat))
    throw Error::in(path, where + ": mat " + std::to_string(seq.mat.rows) + " x " +
                              std::to_string(seq.mat.cols) + " differs from the dataset's " +
                              std::to_string(mat.rows) + " x " + std::to_string(mat.cols));
  if (!same_rate(seq.fps, info.fps))
    throw Error::in(path, where + ": fps " + precise_text(seq.fps) + " differs from the dataset's " +
                              precise_text(info.fps));
  const int frames = seq.frames();
  if (frames <= 0 || seq.kpa.size() != size_t(frames) * mat.cells())
    throw Error::in(path, where + ": has no frames");
  // One pass over the values when they are all in range (NaN and the
  // infinities are not); a non-finite value is then looked for, to say where.
  try {
    check_pressure(seq.kpa.data(), seq.kpa.size(), mat.cells(), path, where);
  } catch (const Error&) {
    const size_t i = first_non_finite(seq.kpa.data(), seq.kpa.size());
    if (i < seq.kpa.size()) {
      size_t t = i / mat.cells(), r = (i % mat.cells()) / mat.cols, c = i % mat.cols;
      throw Error::in(path, where + ": non-finite value at frame " + std::to_string(t) + " row " +
                                std::to_string(r) + " col " + std::to_string(c));
    }
    throw;
  }
}

// float32 [T, rows, cols] in chunks of kChunkFrames frames, deflated by
// `deflater` (null: stored uncompressed, no filter). No shuffle filter: on
// this sparse data it costs time and ratio (docs/simulate.md).
H5::DataSet write_frames(H5::Group& group, const std::string& name, const PressureSequence& seq,
                         h5::ChunkDeflater* deflater) {
  const int frames = seq.frames();
  hsize_t dims[3] = {hsize_t(frames), hsize_t(seq.mat.rows), hsize_t(seq.mat.cols)};
  hsize_t chunk[3] = {hsize_t(std::min(frames, kChunkFrames)), dims[1], dims[2]};
  H5::DataSpace space(3, dims);
  H5::DSetCreatPropList plist;
  H5Pset_obj_track_times(plist.getId(), false);
  plist.setChunk(3, chunk);
  if (deflater) plist.setDeflate(unsigned(deflater->level()));  // recorded; HDF5 does not deflate itself
  H5::DataSet ds = group.createDataSet(name, H5::PredType::IEEE_F32LE, space, plist);
  if (deflater)
    deflater->write(ds, seq.kpa.data(), dims[0], chunk[0], seq.mat.cells());
  else
    ds.write(seq.kpa.data(), H5::PredType::NATIVE_FLOAT);
  return ds;
}
}  // namespace

struct DatasetWriter::Impl {
  AtomicFile out;  // declared first: destroyed last, after the file is closed
  DatasetInfo info;
  std::set<std::string> body_ids;
  std::map<std::string, int> frames;  // sequence name -> frames
  std::set<std::string> floors;
  H5::H5File file;
  H5::Group sequences, floor;
  std::unique_ptr<h5::ChunkDeflater> deflater;  // null: compression 0
  bool committed = false;

  Impl(const std::string& path, bool force) : out(path, force) {}
  const std::string& path() const { return out.path(); }
};

void check_dataset_output(const std::string& path, bool force) {
  check_output_name(path, {".h5", ".hdf5"}, "an HDF5 dataset");
  check_output_path(path, force);
}

DatasetWriter::DatasetWriter(const std::string& path, const DatasetInfo& info,
                             const std::vector<BodySpec>& bodies, bool force) {
  check_dataset_output(path, force);
  h5::quiet();
  auto impl = std::make_unique<Impl>(path, force);
  impl->info = info;
  if (info.mat.rows <= 0 || info.mat.cols <= 0 || !(info.mat.pitch_m > 0))
    throw Error::in(path, "mat must have positive rows, cols and pitch");
  if (!(info.fps > 0)) throw Error::in(path, "fps must be positive");
  if (info.compression < 0 || info.compression > 9)
    throw Error::in(path, "compression must be a deflate level 0-9, found " + std::to_string(info.compression));
  if (info.compression > 0) impl->deflater = std::make_unique<h5::ChunkDeflater>(info.compression);
  for (const auto& b : bodies) {
    check_body(path, b);
    if (!impl->body_ids.insert(b.id).second)
      throw Error::in(path, "body id '" + b.id + "' appears twice");
  }
  try {
    impl->file = H5::H5File(impl->out.temp_path(), H5F_ACC_TRUNC);
    H5::Group root = impl->file.openGroup("/");
    h5::write_attr(root, "format", std::string(kDatasetFormat));
    h5::write_attr(root, "version", kDatasetVersion);
    h5::write_attr(root, "fps", info.fps);
    h5::write_attr(root, "rows", info.mat.rows);
    h5::write_attr(root, "cols", info.mat.cols);
    h5::write_attr(root, "pitch_m", info.mat.pitch_m);
    h5::write_attr(root, "units", std::string("kPa"));
    h5::write_attr(root, "generator", info.generator);
    h5::write_attr(root, "config", info.config_json);
    write_bodies(impl->file, bodies);
    impl->sequences = h5::create_group(impl->file, "sequences");
  } catch (const H5::Exception& e) {
    throw Error::in(path, "cannot write HDF5 file: " + h5::error_stack_text(), ErrorKind::io);
  }
  impl_ = std::move(impl);
}

DatasetWriter::~DatasetWriter() {
  if (!impl_) return;
  try {
    impl_->sequences.close();
    impl_->floor.close();
    impl_->file.close();
  } catch (...) {
  }
}

void DatasetWriter::add(const SequenceMeta& meta, const PressureSequence& seq) {
  const std::string& path = impl_->path();
  if (impl_->committed) throw Error::in(path, "add() after commit()");
  const std::string where = "sequence '" + meta.name + "'";
  if (const std::string problem = name_problem(meta.name); !problem.empty())
    throw Error::in(path, "invalid sequence name " + escaped(meta.name) + ": it " + problem);
  for (const std::string* text : {&meta.body_id, &meta.motion_id, &meta.performer, &meta.category, &meta.source})
    if (utf8_invalid_at(*text) != std::string::npos)  // HDF5 declares the attributes UTF-8
      throw Error::in(path, where + ": " + escaped(*text, 80) + " is not UTF-8");
  if (impl_->frames.count(meta.name)) throw Error::in(path, where + " added twice");
  if (!impl_->body_ids.count(meta.body_id))
    throw Error::in(path, where + ": body_id '" + meta.body_id + "' not in the bodies table");
  check_frames(path, where, impl_->info, seq);
  try {
    H5::DataSet ds = write_frames(impl_->sequences, meta.name, seq, impl_->deflater.get());
    h5::write_attr(ds, "body_id", meta.body_id);
    h5::write_attr(ds, "motion_id", meta.motion_id);
    h5::write_attr(ds, "performer", meta.performer);
    h5::write_attr(ds, "category", meta.category);
    h5::write_attr(ds, "take", meta.take);
    h5::write_attr(ds, "source", meta.source);
  } catch (const H5::Exception&) {
    throw Error::in(path, where + ": cannot write: " + h5::error_stack_text(), ErrorKind::io);
  }
  impl_->frames[meta.name] = seq.frames();
}

void DatasetWriter::add_floor(const std::string& name, const PressureSequence& seq) {
  const std::string& path = impl_->path();
  if (impl_->committed) throw Error::in(path, "add_floor() after commit()");
  const std::string where = "floor of sequence '" + name + "'";
  const auto it = impl_->frames.find(name);
  if (it == impl_->frames.end()) throw Error::in(path, where + ": no such sequence (add it first)");
  if (impl_->floors.count(name)) throw Error::in(path, where + " added twice");
  check_frames(path, where, impl_->info, seq);
  if (seq.frames() != it->second)
    throw Error::in(path, where + ": " + std::to_string(seq.frames()) + " frames, the sequence has " +
                              std::to_string(it->second));
  try {
    if (impl_->floors.empty()) impl_->floor = h5::create_group(impl_->file, "floor");
    write_frames(impl_->floor, name, seq, impl_->deflater.get());
  } catch (const H5::Exception&) {
    throw Error::in(path, where + ": cannot write: " + h5::error_stack_text(), ErrorKind::io);
  }
  impl_->floors.insert(name);
}

void DatasetWriter::commit() {
  const std::string& path = impl_->path();
  if (impl_->committed) return;
  try {
    impl_->sequences.close();
    impl_->floor.close();
    impl_->file.close();
  } catch (const H5::Exception&) {
    throw Error::in(path, "cannot finish HDF5 file (disk full?): " + h5::error_stack_text(),
                    ErrorKind::io);
  }
  impl_->out.commit();
  impl_->committed = true;
}

}  // namespace ptnet
