// Inputs found by `make fuzz` (fuzz_dataset) that made libhdf5 1.10.8 itself
// misbehave under ASan: a 76 TB allocation request for an object header, an
// out-of-bounds read while decoding an attribute message, a leak on a bad
// datatype message. The real tool turns each into one line naming the file
// and exit status 1. (Smoke, not unit: `make asan` would flag the library's
// own over-read. Inputs that make libhdf5 loop forever are not here: see
// docs/formats.md.)
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

TEST(FuzzRegressions, DamagedHdf5FilesAreOneLineErrors) {
  const fs::path scratch = fs::temp_directory_path() / ("ptnet_fuzz_regressions_" + std::to_string(::getpid()));
  for (const char* name : {"hdf5_huge_object_header.h5", "hdf5_attribute_overread.h5", "hdf5_bad_datatype.h5"}) {
    const std::string path = std::string(PTNET_TEST_DATA) + "/fuzz_regressions/" + name;
    const auto r = ptnet::testing_cli::run_ptnet("info '" + path + "'", scratch);
    EXPECT_EQ(r.status, 1) << name << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ptnet: error: " + path + ": damaged HDF5 file: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}
