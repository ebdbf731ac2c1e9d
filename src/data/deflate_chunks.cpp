#include "data/deflate_chunks.hpp"

#include <libdeflate.h>

#include <algorithm>
#include <string>

#include "ptnet/error.hpp"

namespace ptnet::h5 {

ChunkDeflater::ChunkDeflater(int level)
    : level_(level), compressor_(level >= 2 ? libdeflate_alloc_compressor(level) : nullptr) {
  if (level >= 2 && !compressor_)  // levels are checked by the writer: only memory fails
    throw Error("libdeflate: cannot allocate a compressor at level " + std::to_string(level));
}

ChunkDeflater::~ChunkDeflater() { libdeflate_free_compressor(compressor_); }

void ChunkDeflater::write(const H5::DataSet& dataset, const float* data, std::size_t frames,
                          std::size_t chunk_frames, std::size_t frame_values) {
  const std::size_t chunk_values = chunk_frames * frame_values, chunk_bytes = chunk_values * sizeof(float);
  out_.resize(compressor_ ? libdeflate_zlib_compress_bound(compressor_, chunk_bytes) : RunDeflater::bound(chunk_bytes));
  for (std::size_t t0 = 0; t0 < frames; t0 += chunk_frames) {
    const float* chunk = data + t0 * frame_values;
    if (t0 + chunk_frames > frames) {  // the edge chunk: whole, zero-padded
      const std::size_t have = (frames - t0) * frame_values;
      edge_.assign(chunk_values, 0.0f);
      std::copy(chunk, chunk + have, edge_.begin());
      chunk = edge_.data();
    }
    const auto* bytes = reinterpret_cast<const unsigned char*>(chunk);
    const std::size_t n = compressor_ ? libdeflate_zlib_compress(compressor_, bytes, chunk_bytes, out_.data(), out_.size())
                                      : runs_.compress(bytes, chunk_bytes, out_.data());
    if (n == 0) throw Error("deflate: a chunk of " + std::to_string(chunk_bytes) + " bytes exceeded its bound");
    const hsize_t offset[3] = {hsize_t(t0), 0, 0};
    if (H5Dwrite_chunk(dataset.getId(), H5P_DEFAULT, 0, offset, n, out_.data()) < 0)
      throw H5::DataSetIException("ChunkDeflater::write", "H5Dwrite_chunk failed");
  }
}

}  // namespace ptnet::h5
