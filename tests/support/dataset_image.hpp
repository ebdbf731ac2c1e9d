// support/dataset_image.hpp (test support: the dataset fuzzer, not the
// library): the dataset reader on an HDF5 file image held in memory.
//
//   ptnet::Dataset d = ptnet::open_dataset_image(bytes, "fuzz.h5");
#pragma once

#include <string>

#include "ptnet/data.hpp"

namespace ptnet {

// The HDF5 file image `bytes` opened with HDF5's core driver and validated
// as Dataset::open validates a file; `name` names it in messages. Throws
// Error.
Dataset open_dataset_image(const std::string& bytes, const std::string& name);

}  // namespace ptnet
