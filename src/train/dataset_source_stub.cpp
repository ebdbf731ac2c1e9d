// Used when the data stage (HDF5 dataset) is not part of the build.
#include "ptnet/error.hpp"
#include "ptnet/train.hpp"

namespace ptnet {

std::unique_ptr<PressureSource> open_dataset_source(const std::string& path) {
  throw Error::in(path, "this ptnet was built without the data stage (HDF5 dataset support)");
}

}  // namespace ptnet
