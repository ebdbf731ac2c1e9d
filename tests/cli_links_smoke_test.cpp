// A shared dataset file whose links lead elsewhere (tests/data/hdf5_links)
// cannot hang the tools nor make them read another file: with every target
// its links name a FIFO (which HDF5 would block on for ever, even for
// another sequence), `ptnet info`, `render` and `merge` each end with one
// line naming the file and exit 1 (before the fix `info` of an external
// link and `render` of external storage or a virtual dataset never ended).
//
// Every run is bounded (generously: the machine may be loaded) and reaped.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "cli_test_util.hpp"

using ptnet::testing_cli::slurp;
using ptnet::testing_cli::spawn_ptnet;
using ptnet::testing_cli::wait_within;
namespace fs = std::filesystem;

namespace {

constexpr double kBound = 60;  // s: a light command ends in well under a second

const char* const kFixtures[] = {"external_link.h5", "external_group.h5", "external_elsewhere.h5",
                                 "soft_link.h5",     "soft_bodies.h5",    "hard_link_twice.h5",
                                 "hard_link_loop.h5", "external_storage.h5", "virtual.h5",
                                 "virtual_unlimited.h5"};

}  // namespace

TEST(CliLinks, LinkedDatasetsAreOneLineErrorsWithoutOpeningTheTargets) {
  const fs::path dir = fs::temp_directory_path() / ("ptnet_links_smoke_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* target : {"target.h5", "raw.f32", "source.h5"})
    ASSERT_EQ(::mkfifo((dir / target).c_str(), 0600), 0) << target;
  const fs::path good = dir / "good.h5";
  fs::copy_file(fs::path(PTNET_TEST_DATA) / "hdf5_links" / "good.h5", good);
  for (const char* fixture : kFixtures) {
    const fs::path path = dir / fixture;
    fs::copy_file(fs::path(PTNET_TEST_DATA) / "hdf5_links" / fixture, path);
    for (const std::string& args :
         {"info '" + path.string() + "'", "render '" + path.string() + "' -s walk__b2 --out '" +
                                               (dir / "x.png").string() + "'",
          "merge '" + good.string() + "' '" + path.string() + "' --out '" + (dir / "m.h5").string() + "'"}) {
      SCOPED_TRACE(args);
      const fs::path err = dir / "err";
      const pid_t p = spawn_ptnet(args, err);
      const int status = wait_within(p, kBound);
      const std::string e = slurp(err);
      EXPECT_EQ(status, 1) << "-1: still running after " << kBound << " s\n" << e;
      EXPECT_EQ(e.rfind("ptnet: error: " + path.string() + ": /", 0) == 0 ||
                    e.rfind("ptnet: error: " + path.string() + ": sequence 'walk__b2' ", 0) == 0,
                true)
          << e;
      EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 1) << e;
    }
    EXPECT_FALSE(fs::exists(dir / "x.png"));
    EXPECT_FALSE(fs::exists(dir / "m.h5"));
  }
  fs::remove_all(dir);
}
