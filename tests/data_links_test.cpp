// Datasets that reach outside their file (tests/data/hdf5_links, README
// there): an external link, a soft link, external storage or a virtual
// dataset anywhere a reader looks is refused in one line naming the object,
// even with the link's target present (a ptnet dataset of its own that HDF5
// would otherwise have read as part of this one). A good dataset beside
// them still opens. (The targets as FIFOs, which HDF5 would block on:
// cli_links_smoke_test.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"

namespace ptnet {
namespace {
namespace fs = std::filesystem;
using testing_util::error_of;
using testing_util::TempDir;

const fs::path kFixtures = fs::path(PTNET_TEST_DATA) / "hdf5_links";

// Each fixture and the start of what follows "FILE: " in its error.
const std::pair<const char*, const char*> kRefused[] = {
    {"external_link.h5", "/sequences/walk__b2 is an external link to 'target.h5:/sequences/walk__b1'; "},
    {"external_group.h5", "/sequences is an external link to 'target.h5:/sequences'; "},
    {"external_elsewhere.h5", "/notes is an external link to 'target.h5:/'; "},
    {"soft_link.h5", "/sequences/walk__b2 is a soft link to '/sequences/walk__b1'; "},
    {"soft_bodies.h5", "/bodies is a soft link to '/table'; "},
    {"hard_link_twice.h5", "/sequences/walk__b2 is a second name of /sequences/walk__b1; "},
    {"hard_link_loop.h5", "/sequences/all is a second name of / (the root group); "},
    {"external_storage.h5", "sequence 'walk__b2' keeps its data in the external file 'raw.f32'; "},
    {"virtual.h5", "sequence 'walk__b2' is a virtual dataset (its data are in other files); "},
    {"virtual_unlimited.h5", "sequence 'walk__b2' is a virtual dataset (its data are in other files); "},
};

// `dir` with the targets the fixtures' links name: target.h5 a good dataset
// (the fixtures' own, so that the links resolve) and raw.f32 the bytes of
// a sequence (source.h5 of the virtual datasets is absent: HDF5 reads fill
// values for it).
void write_targets(const TempDir& dir) {
  fs::copy_file(kFixtures / "good.h5", dir.file("target.h5"));
  std::ofstream(dir.file("raw.f32"), std::ios::binary) << std::string(3 * 4 * 2 * 4, '\0');
}

TEST(DatasetLinks, EveryLinkOrForeignStorageIsRefusedInOneLine) {
  TempDir dir("links");
  write_targets(dir);
  for (const auto& [fixture, problem] : kRefused) {
    SCOPED_TRACE(fixture);
    const std::string path = dir.file(fixture);
    fs::copy_file(kFixtures / fixture, path);
    const std::string e = error_of([&] { Dataset::open(path); });
    EXPECT_EQ(e.rfind(path + ": " + problem, 0), 0u) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST(DatasetLinks, TheSameDatasetWithoutLinksOpens) {
  const Dataset d = Dataset::open((kFixtures / "good.h5").string());
  ASSERT_EQ(d.sequences().size(), 1u);
  EXPECT_EQ(d.read("walk__b1").kpa, std::vector<float>(3 * 4 * 2, 1.0f));
}

}  // namespace
}  // namespace ptnet
