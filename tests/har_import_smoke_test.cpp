// ptnet import against hostile manifests, through the real binary: an entry
// that is a symbolic link to /dev/zero or a FIFO is a one-line error at
// once (not a read without end, not a wait without end), and a recording
// is held in memory once (the peak grows by its size, not twice it).
//
// Each run is bounded: `timeout` kills it after kBound s and `ulimit -v`
// caps its address space (before the fix /dev/zero was read until the
// 64 GiB .npy limit).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_test_util.hpp"
#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/npy.hpp"

using namespace ptnet;
using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::run_program;
using ptnet::testing_cli::spawn_ptnet;
using ptnet::testing_cli::wait_within;
using ptnet::testing_cli::slurp;
namespace fs = std::filesystem;

namespace {

constexpr int kBound = 90;  // s: the longest an import here may take (well under 1 s unloaded, or ~2 s for 128 MB)

class ImportCli : public ::testing::Test {
 protected:
  // A manifest of one recording, file `file`.
  std::string manifest(const std::string& file) const {
    const fs::path m = dir_ / "m.csv";
    std::ofstream(m) << "subject,sex,height_cm,weight_kg,file\ns1,female,160,55," << file << "\n";
    return m.string();
  }
  // `ptnet import` of a manifest of `file`, bounded in time and address space.
  RunResult import(const std::string& file) const {
    const std::string cmd = "ulimit -v 2000000; exec timeout -s KILL " + std::to_string(kBound) + " '" +
                            std::string(PTNET_BINARY) + "' import --manifest '" + manifest(file) + "' --out '" +
                            (dir_ / "out.h5").string() + "'";
    return run_program("/bin/sh", "-c \"" + cmd + "\"", dir_ / "run");
  }
  ptnet::testing_util::TempDir tmp_{"import_smoke"};
  const fs::path dir_ = tmp_.path;
};

}  // namespace

TEST_F(ImportCli, DeviceEntriesAreRefused) {
  for (const std::string name : {"zero.npy", "zero.csv"}) {
    fs::create_symlink("/dev/zero", dir_ / name);
    const RunResult r = import(name);
    EXPECT_EQ(r.status, 1) << name << ": " << r.err;
    EXPECT_EQ(r.err, "ptnet: error: " + (dir_ / name).string() + ": is a character device, expected a regular file\n");
    EXPECT_FALSE(fs::exists(dir_ / "out.h5"));
  }
}

TEST_F(ImportCli, FifoEntryIsRefusedWithoutWaiting) {
  ASSERT_EQ(::mkfifo((dir_ / "live.npy").c_str(), 0600), 0);
  const RunResult r = import("live.npy");  // nobody writes: opening it would wait forever
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err, "ptnet: error: " + (dir_ / "live.npy").string() + ": is a FIFO, expected a regular file\n");
}

// The manifest itself /dev/zero or a FIFO: refused at once (before, a
// /dev/zero manifest was read to the 1 GiB text limit, 2.26 GB for 4 s, and
// a FIFO without a writer waited for ever).
TEST_F(ImportCli, AManifestThatIsNoFileIsRefusedAtOnce) {
  fs::create_symlink("/dev/zero", dir_ / "zero.csv");
  ASSERT_EQ(::mkfifo((dir_ / "fifo.csv").c_str(), 0600), 0);
  for (const auto& [name, kind] : {std::pair{"zero.csv", "a character device"}, std::pair{"fifo.csv", "a FIFO"}}) {
    const pid_t p = spawn_ptnet("import --manifest '" + (dir_ / name).string() + "' --out '" +
                                    (dir_ / "out.h5").string() + "'",
                                dir_ / "manifest.err");
    long kb = 0;
    EXPECT_EQ(wait_within(p, kBound, &kb), 1) << name << ": " << slurp(dir_ / "manifest.err");
    EXPECT_EQ(slurp(dir_ / "manifest.err"),
              "ptnet: error: " + (dir_ / name).string() + ": is " + kind + ", expected a regular file\n");
    EXPECT_LT(kb, 1024L * 1024) << name << ": peak " << kb / 1024 << " MiB";  // LibTorch itself: ~300 MiB
  }
  EXPECT_FALSE(fs::exists(dir_ / "out.h5"));
}

TEST_F(ImportCli, ARecordingIsHeldOnce) {
  // Peak resident memory of an import of `frames` frames of 80 x 28.
  const auto peak_kb = [&](int frames) {
    PressureSequence s(MatSpec{80, 28, 0.02}, frames, 30);
    for (int t = 0; t < frames; ++t) s.at(t, 40, 14) = 1.0f + float(t % 7);  // compresses well: fast
    fs::remove(dir_ / "rec.npy");
    fs::remove(dir_ / "out.h5");
    write_npy_sequence((dir_ / "rec.npy").string(), s, true);
    const pid_t p = spawn_ptnet("import --manifest '" + manifest("rec.npy") + "' --out '" + (dir_ / "out.h5").string() + "'",
                                dir_ / "peak.err");
    long kb = 0;
    EXPECT_EQ(wait_within(p, kBound, &kb), 0) << slurp(dir_ / "peak.err");
    EXPECT_EQ(Dataset::open((dir_ / "out.h5").string()).sequences().at(0).frames, frames);
    return kb;
  };
  const long small = peak_kb(30);
  const int frames = 15000;  // 134 MB
  const long big = peak_kb(frames), size_kb = long(frames) * 80 * 28 * 4 / 1024;
  // Held once: the peak grows by the recording's size (plus the writer's
  // chunk buffers); held twice (file bytes, then the array) it grew by 2x.
  EXPECT_LT(big - small, size_kb * 3 / 2) << "peak " << small / 1024 << " MiB for 30 frames, " << big / 1024
                                          << " MiB for " << size_kb / 1024 << " MiB of frames";
}
