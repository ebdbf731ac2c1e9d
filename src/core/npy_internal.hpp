// core/npy_internal.hpp (private to the core stage; tests include it as
// "core/npy_internal.hpp"): a whole .npy array, read and written; the
// public side (ptnet/npy.hpp) is pressure sequences and headers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ptnet/npy.hpp"

namespace ptnet {

struct NpyArray {
  std::vector<std::int64_t> shape;
  std::vector<float> data;  // C order
};

// Throws Error naming the file: bad magic, dtype other than float32, Fortran
// order, data of another size than the shape's. Reads the header, then only
// the data the shape announces (checked against the available memory),
// straight into the array.
NpyArray read_npy(const std::string& path);
// The same on the bytes of a file (`name` names it in messages).
NpyArray parse_npy(const std::string& bytes, const std::string& name);
// Atomic write; refuses to overwrite unless force.
void write_npy(const std::string& path, const NpyArray& array, bool force);

}  // namespace ptnet
