// data/dataset_on_hdf5.hpp (private to the data stage; tools that open an
// HDF5 file their own way include it through the stages' private include
// path): a Dataset on an HDF5 file the caller has opened, validated as
// Dataset::open validates a file on disk. tests/support/dataset_image.cpp
// opens an in-memory file image with it (the dataset fuzzer).
//
//   H5::H5File file(name, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, fapl);
//   ptnet::Dataset d = ptnet::DatasetOnHdf5::open(file, name);
#pragma once

#include <H5Cpp.h>

#include <string>

#include "ptnet/data.hpp"

namespace ptnet {

struct DatasetOnHdf5 {
  // Reads the structure (format, version, attributes, bodies, sequences) of
  // `file`; throws Error naming `name` as Dataset::open does.
  static Dataset open(const H5::H5File& file, const std::string& name);
};

}  // namespace ptnet
