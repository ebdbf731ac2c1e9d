// open_dataset_image (support/dataset_image.hpp): HDF5's core driver on a
// file image, then the data stage's reader (data/dataset_on_hdf5.hpp).
#include "support/dataset_image.hpp"

#include <H5Cpp.h>

#include "data/dataset_on_hdf5.hpp"
#include "data/h5_util.hpp"
#include "ptnet/error.hpp"

namespace ptnet {

Dataset open_dataset_image(const std::string& bytes, const std::string& name) {
  h5::quiet();
  H5::H5File file;
  try {
    H5::FileAccPropList fapl;
    if (H5Pset_fapl_core(fapl.getId(), 1 << 16, /*backing_store=*/0) < 0 ||
        H5Pset_file_image(fapl.getId(), const_cast<char*>(bytes.data()), bytes.size()) < 0)
      throw Error::in(name, "cannot set up an in-memory HDF5 file");
    file = H5::H5File(name, H5F_ACC_RDONLY, H5::FileCreatPropList::DEFAULT, fapl);
  } catch (const H5::Exception&) {
    const std::string why = h5::error_stack_text();
    throw Error::in(name, "damaged HDF5 file: " + (why.empty() ? "cannot open" : why));
  }
  return DatasetOnHdf5::open(file, name);
}

}  // namespace ptnet
