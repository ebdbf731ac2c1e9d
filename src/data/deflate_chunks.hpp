// deflate_chunks.hpp (internal to the data stage): float32 frames written to
// a chunked HDF5 dataset as chunks we deflate ourselves (zlib format: level
// 1 with RunDeflater, run_deflate.hpp; 2-9 with libdeflate at that level)
// and hand to HDF5 with H5Dwrite_chunk. The dataset's filter pipeline is
// HDF5's standard deflate filter alone, so every reader (h5py, h5dump,
// DatasetReader) inflates the chunks with no plugin.
#pragma once

#include <H5Cpp.h>

#include <cstddef>
#include <vector>

#include "data/run_deflate.hpp"

struct libdeflate_compressor;

namespace ptnet::h5 {

// One compressor at one level (1: zero runs only, 2-9: libdeflate's),
// reused for every chunk. Not thread-safe: one per writing thread. Throws
// Error if libdeflate cannot allocate its compressor.
class ChunkDeflater {
 public:
  explicit ChunkDeflater(int level);
  ~ChunkDeflater();
  ChunkDeflater(const ChunkDeflater&) = delete;
  ChunkDeflater& operator=(const ChunkDeflater&) = delete;
  int level() const { return level_; }

  // Writes `frames` frames of `frame_values` floats each ([frames,
  // frame_values], row-major) into the 3-d `dataset` [frames, rows, cols]
  // (rows x cols = frame_values) chunked [chunk_frames, rows, cols], whose
  // filter pipeline is deflate alone (every chunk: filter mask 0). The last chunk is padded with zeros (the fill
  // value) to a whole chunk, as HDF5 stores edge chunks. Throws
  // H5::DataSetIException when HDF5 refuses a chunk (its error stack says
  // why).
  void write(const H5::DataSet& dataset, const float* data, std::size_t frames, std::size_t chunk_frames,
             std::size_t frame_values);

 private:
  int level_;
  libdeflate_compressor* compressor_;  // null at level 1
  RunDeflater runs_;                   // level 1
  std::vector<unsigned char> out_;  // compressed chunk
  std::vector<float> edge_;         // the last chunk, zero-padded
};

}  // namespace ptnet::h5
