// ptnet/data.hpp: the HDF5 dataset file (see docs/formats.md).
//
//   ptnet::DatasetWriter w("data.h5", info, bodies, /*force=*/false);
//   w.add(meta, sequence);            // one per clip x body
//   w.commit();                       // temporary file renamed into place
//
//   ptnet::Dataset d = ptnet::Dataset::open("data.h5");   // validated
//   for (const auto& s : d.sequences()) d.read(s.name, 0, 30, buffer);
//
// Layout:
//   /                 attrs format="ptnet-dataset", version=1, fps, rows, cols,
//                     pitch_m, units="kPa", generator, config (JSON text)
//   /bodies           compound table: id, sex (0 female, 1 male), height_cm,
//                     weight_kg, role
//   /sequences/<name> float32 [T, rows, cols], chunked + compressed; attrs
//                     body_id, motion_id, performer, category, take, source
//   /floor/<name>     optional, float32 [T, rows, cols]: sequence <name>
//                     simulated again with another sensor seed (only the
//                     noise differs), for the noise floor of evaluations
// HDF5 is not thread-safe here: use a writer or reader from one thread.
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/io.hpp"
#include "ptnet/paper.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet {

inline constexpr const char* kDatasetFormat = "ptnet-dataset";
inline constexpr int kDatasetVersion = 1;

inline constexpr int kDefaultCompression = 1;  // deflate level of the sequences: zero runs only

struct DatasetInfo {
  MatSpec mat;
  double fps = kFps;
  std::string generator;    // "ptnet 0.1.0 simulate"
  std::string config_json = "{}";  // options that produced the file
  // Deflate level of the sequences (HDF5's deflate filter, no shuffle): 1,
  // the default, codes only the runs of zeros, several times faster than a
  // general deflater and as small on sparse pressure; 2-9 are libdeflate's
  // levels; 0 stores the sequences uncompressed (docs/simulate.md).
  int compression = kDefaultCompression;
};

struct SequenceMeta {
  std::string name;       // "<motion_id>__<body_id>" by convention
  std::string body_id;
  std::string motion_id;  // the same motion on two bodies shares this
  std::string performer;  // who performed the motion (CMU subject, procedural P)
  std::string category;   // walking | rom | freestyle | acting
  int take = 1;           // 1 = seen, 2 = unseen in the paper's protocol
  std::string source;     // BVH path or "procedural:..."
  int frames = 0;         // filled by Dataset::open
  bool floor = false;     // filled by Dataset::open: /floor/<name> exists
};

// What a dataset's writers check of `path`, for before the work: a .h5 or
// .hdf5 name (any case, as `ptnet info` reads datasets; Error "w.trc:
// expected a .h5 or .hdf5 file name (an HDF5 dataset is written), found
// '.trc'": check_output_name) and check_output_path (ptnet/io.hpp).
// DatasetWriter checks it again.
void check_dataset_output(const std::string& path, bool force);

class DatasetWriter {
 public:
  DatasetWriter(const std::string& path, const DatasetInfo& info,
                const std::vector<BodySpec>& bodies, bool force);
  ~DatasetWriter();  // without commit(), the temporary file is removed
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  // Checks the shape against the mat and the body_id against the bodies.
  void add(const SequenceMeta& meta, const PressureSequence& sequence);
  // /floor/<name>: the sequence `name` (added before, same shape) simulated
  // again with another sensor seed.
  void add_floor(const std::string& name, const PressureSequence& sequence);
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class Dataset {
 public:
  // Validates format, version, attributes, shapes; throws Error naming the file.
  // The file is noted as an input (no output of the run may replace it).
  static Dataset open(const std::string& path);
  Dataset(Dataset&&) noexcept;
  Dataset& operator=(Dataset&&) noexcept;
  ~Dataset();

  const std::string& path() const;
  const DatasetInfo& info() const;
  const std::vector<BodySpec>& bodies() const;
  const BodySpec& body(const std::string& id) const;  // throws if absent
  const std::vector<SequenceMeta>& sequences() const;
  const SequenceMeta& sequence(const std::string& name) const;  // throws if absent

  // Frames [start, start + count) of a sequence into out[count, rows, cols];
  // a non-finite value is an Error naming the sequence and frame.
  void read(const std::string& name, int start, int count, float* out) const;
  // The whole sequence; an Error if it needs more than the available memory.
  PressureSequence read(const std::string& name) const;
  // /floor/<name> (sequence(name).floor must be true; throws Error otherwise).
  PressureSequence read_floor(const std::string& name) const;

 private:
  Dataset();
  struct Impl;
  std::unique_ptr<Impl> impl_;
  friend struct DatasetOnHdf5;  // src/data/dataset_on_hdf5.hpp: an HDF5 file opened another way
};

// What each sequence's mat reads, as a force plate under it would (ptnet
// forces): per frame the vertical force in N and in body weights of the
// sequence's body, its centre of pressure in the mat's frame (frame_load,
// ptnet/pressure.hpp) and the contact area above `contact_kpa`, written as
// `dir`/<name>.<format> (TableFormat: OpenSim storage or CSV; columns
// time, ground_force_vy, ground_force_bw, mat_cop_x, mat_cop_y,
// contact_area_cm2). `names` empty: every sequence. `contact_kpa` in
// kPressureRangeKpa (check_range). Every output is checked
// before any is written (existing files need `force`); each is atomic.
// Returns the paths written. A mat reads only what stands on it: a foot off
// the mat is missing from its force, unlike the simulator's own ground
// reaction (SimulateDatasetOptions::forces_dir).
std::vector<std::string> write_mat_forces(const Dataset& dataset, const std::vector<std::string>& names,
                                          const std::string& dir, TableFormat format, bool force,
                                          double contact_kpa = kContactKpa);

// Merges datasets into one at `out_path` (atomically; an existing file needs
// `force`): the shards of one `ptnet simulate --shard K/N` run, or any
// datasets with the same mat, fps, generator, bodies and config. Shards must
// all be present, once each (any order), of one run (the same options and
// the same clips: "run" in their config records the clips' digest and the
// run's sequence count) and complete (each the sequences of its block);
// "shard" and "run" are removed from the config, so the result has the
// unsharded run's sequences (with their /floor copies), attributes and
// bodies. A sequence name in two inputs is an Error naming both. Returns
// the number of sequences written.
int merge_datasets(const std::vector<std::string>& inputs, const std::string& out_path, bool force);

// A shard "K/N" (decimal, 0 <= K < N < 2^31, nothing else: "1/2x", "0x1/2"
// and "1/4294967298" are not): true and K, N; false otherwise.
bool parse_shard(std::string_view text, int& index, int& count);

// What `ptnet info FILE` prints for a dataset: mat, fps, bodies (table),
// sequences, frames, per-category and per-take counts, file size and
// compression ratio; with json, the same plus every sequence as JSON.
std::string describe_dataset(const Dataset& dataset, bool json);

}  // namespace ptnet
