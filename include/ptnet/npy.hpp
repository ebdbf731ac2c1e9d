// ptnet/npy.hpp: a tiny NumPy .npy reader/writer for float32 arrays (the
// `--in x.npy` / `--out y.npy` form of `ptnet transfer`).
//
//   ptnet::PressureSequence s = ptnet::read_npy_sequence("walk.npy", mat, 30);
//   ptnet::write_npy_sequence("out.npy", s, /*force=*/false);  // [T, rows, cols]
//
// Format: "\x93NUMPY", version 1.0/2.0/3.0, a header dict with descr '<f4',
// fortran_order False and the shape, then the raw little-endian data.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ptnet/pressure.hpp"

namespace ptnet {

// Largest .npy file read (the available memory is checked too).
inline constexpr std::uint64_t kMaxNpyBytes = std::uint64_t(64) << 30;  // 64 GiB
// Largest .npy header (numpy writes 64-128 bytes).
inline constexpr std::size_t kMaxNpyHeaderBytes = std::size_t(1) << 20;  // 1 MiB

// The header of a .npy file or stream: its shape and where the data start.
// `bytes` holds at least the header (the data need not follow: a stream's
// shape may promise more frames than will come). Throws Error naming the
// file: bad magic, dtype other than float32, Fortran order.
struct NpyHeader {
  std::vector<std::int64_t> shape;
  std::size_t data_offset = 0;  // header bytes, magic included
};
NpyHeader parse_npy_header(const std::string& bytes, const std::string& name);
// The header's size in bytes from the file's first 12 bytes (10 suffice for
// version 1). Throws Error for a missing magic or an unknown version.
std::size_t npy_header_size(const std::string& first_bytes, const std::string& name);

// A [T, rows, cols] float32 array as a sequence on `mat` (rows/cols must
// match: "x.npy: expected shape [T, 80, 28], found [100, 64, 28]"); NaN or
// Inf is an Error, as in a dataset.
PressureSequence read_npy_sequence(const std::string& path, const MatSpec& mat, double fps);
void write_npy_sequence(const std::string& path, const PressureSequence& seq, bool force);

}  // namespace ptnet
