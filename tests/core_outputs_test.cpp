// Outputs never destroy what they must not (ptnet/io.hpp): no FIFO, folder or
// other non-regular file is replaced, with or without force; no input of the
// run is replaced (same inode, whatever the name); temporary files go away on
// SIGTERM and stale ones of dead processes are swept; a CommitGroup appears
// whole or not at all.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/io_internal.hpp"
#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

using namespace ptnet;
using ptnet::testing_util::TempDir;
using ptnet::testing_util::error_of;
namespace fs = std::filesystem;

namespace {

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

bool has_temp(const TempDir& d) {
  for (const auto& n : d.entries())
    if (n.find(".tmp") != std::string::npos) return true;
  return false;
}

// A process id that is certainly dead: a child that exited and was reaped.
pid_t dead_pid() {
  const pid_t p = ::fork();
  if (p == 0) ::_exit(0);
  ::waitpid(p, nullptr, 0);
  return p;
}

}  // namespace

TEST(Outputs, AFifoIsNeverReplacedEvenWithForce) {
  TempDir d("out_fifo");
  const std::string fifo = d.file("device");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (bool force : {false, true}) {
    EXPECT_EQ(error_of([&] { write_text_file(fifo, "x", force); }),
              fifo + ": is a FIFO, not a regular file; refusing to replace it (even with force)");
    struct stat st;
    ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
    EXPECT_TRUE(S_ISFIFO(st.st_mode));
  }
  // A symbolic link to it is followed, and refused the same way.
  const std::string link = d.file("link");
  fs::create_symlink(fifo, link);
  EXPECT_NE(error_of([&] { write_text_file(link, "x", true); }).find("is a FIFO"), std::string::npos);
  EXPECT_FALSE(has_temp(d));
}

TEST(Outputs, AFolderIsNeverReplaced) {
  TempDir d("out_folder");
  fs::create_directories(d.path / "sub");
  EXPECT_EQ(error_of([&] { write_text_file(d.file("sub"), "x", true); }),
            d.file("sub") +
                ": is a folder, not a regular file; refusing to replace it (even with force)");
  EXPECT_TRUE(fs::is_directory(d.path / "sub"));
}

TEST(Outputs, AnInputIsNeverReplacedWhateverItsName) {
  TempDir d("out_input");
  const std::string in = d.file("in.csv");
  write_text_file(in, "original", false);
  note_input(in);
  EXPECT_EQ(error_of([&] { write_text_file(in, "new", true); }),
            in + ": is the same file as the input " + in +
                "; refusing to replace it (even with force): write the output elsewhere");
  // A hard link and a symbolic link are the same file under another name.
  fs::create_hard_link(in, d.file("hard.csv"));
  fs::create_symlink(in, d.file("soft.csv"));
  EXPECT_NE(error_of([&] { write_text_file(d.file("hard.csv"), "new", true); }).find("same file as the input"),
            std::string::npos);
  EXPECT_NE(error_of([&] { check_output_path(d.file("soft.csv"), true); }).find("same file as the input"),
            std::string::npos);
  EXPECT_EQ(slurp(in), "original");
  // Another file of the same content is fine.
  write_text_file(d.file("other.csv"), "original", false);
  EXPECT_NO_THROW(write_text_file(d.file("other.csv"), "new", true));
}

TEST(Outputs, TheCheckIsRepeatedAtCommit) {
  // An output opened before its input was read is refused when it lands.
  TempDir d("out_commit");
  const std::string p = d.file("both.txt");
  write_text_file(p, "input", false);
  AtomicFile out(p, /*force=*/true);
  std::ofstream(out.temp_path()) << "output";
  note_input(p);
  EXPECT_NE(error_of([&] { out.commit(); }).find("same file as the input"), std::string::npos);
  EXPECT_EQ(slurp(p), "input");
}

TEST(Outputs, StaleTemporaryFilesOfDeadProcessesAreSwept) {
  TempDir d("out_stale");
  const std::string dead = d.file(".data.h5.tmp" + std::to_string(dead_pid()));
  const std::string alive = d.file(".data.h5.tmp" + std::to_string(::getppid()));
  const std::string other = d.file(".notes.txt.tmp" + std::to_string(dead_pid()));
  for (const auto& p : {dead, alive, other}) std::ofstream(p) << "partial";
  write_text_file(d.file("data.h5"), "complete", false);
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(alive));  // a live process may still be writing it
  EXPECT_TRUE(fs::exists(other));  // another target's: left to that target
}

TEST(Outputs, SigtermRemovesTheLiveTemporaryFile) {
  for (int sig : {SIGTERM, SIGINT}) {
    TempDir d("out_signal");
    const std::string target = d.file("big.h5");
    const pid_t child = ::fork();
    if (child == 0) {
      AtomicFile out(target, false);
      std::ofstream(out.temp_path()) << "half written";
      ::raise(sig);
      ::_exit(3);  // not reached
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), sig);  // the process still dies of the signal
    EXPECT_FALSE(fs::exists(target));
    EXPECT_FALSE(has_temp(d)) << "signal " << sig;
  }
}

TEST(Outputs, ACommitGroupAppearsWholeOrNotAtAll) {
  TempDir d("out_group");
  write_text_file(d.file("metrics.csv"), "previous", false);
  EXPECT_THROW(
      {
        CommitGroup g;
        write_text_file(d.file("metrics.csv"), "new", true);
        write_text_file(d.file("figure.png"), "new", true);
        throw std::runtime_error("figure failed");
      },
      std::runtime_error);
  EXPECT_EQ(slurp(d.file("metrics.csv")), "previous");  // the previous state
  EXPECT_FALSE(fs::exists(d.file("figure.png")));
  EXPECT_FALSE(has_temp(d));
  {
    CommitGroup g;
    write_text_file(d.file("metrics.csv"), "new", true);
    write_text_file(d.file("figure.png"), "new", true);
    EXPECT_EQ(slurp(d.file("metrics.csv")), "previous");  // not yet
    g.commit();
  }
  EXPECT_EQ(slurp(d.file("metrics.csv")), "new");
  EXPECT_EQ(slurp(d.file("figure.png")), "new");
  EXPECT_FALSE(has_temp(d));
}

TEST(Inputs, SizesBeyondTheLimitAreOneLineNamingTheFile) {
  TempDir d("in_limit");
  write_text_file(d.file("big.csv"), std::string(5000, 'x'), false);
  EXPECT_EQ(error_of([&] { read_text_file(d.file("big.csv"), 1000); }),
            d.file("big.csv") + ": 5 kB, more than the 1 kB this kind of file may have");
  // Anything but a regular file is refused at once, unread: a FIFO (even
  // one without a writer, which a read would wait on for ever), a device
  // (/dev/zero would be read to the limit), a folder.
  const std::string fifo = d.file("fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(error_of([&] { read_text_file(fifo); }), fifo + ": is a FIFO, expected a regular file");
  EXPECT_EQ(error_of([&] { read_text_file("/dev/zero"); }), "/dev/zero: is a character device, expected a regular file");
  EXPECT_EQ(error_of([&] { read_text_file(d.path.string()); }), d.path.string() + ": is a folder, expected a file");
  std::filesystem::create_symlink(d.file("big.csv"), d.file("link.csv"));  // a link to a regular file is one
  EXPECT_EQ(read_text_file(d.file("link.csv")).size(), 5000u);
}

TEST(Inputs, OverflowAndMemoryChecks) {
  EXPECT_EQ(checked_mul(1u << 20, 1u << 20, "f", "x"), std::uint64_t(1) << 40);
  EXPECT_EQ(error_of([] { checked_mul(std::uint64_t(1) << 40, std::uint64_t(1) << 30, "a.npy", "shape"); }),
            "a.npy: shape overflows 64 bits");
  EXPECT_GT(available_memory_bytes(), 0u);
  EXPECT_NE(error_of([] { check_memory(std::uint64_t(1) << 62, "a.h5", "sequence 'x'"); })
                .find("a.h5: sequence 'x' needs 4.61e+09 GB, more than the"),
            std::string::npos);
  EXPECT_EQ(bytes_text(512), "512 B");
  EXPECT_EQ(bytes_text(3100000), "3.1 MB");
}

TEST(Messages, FileContentIsEscapedAndCut) {
  EXPECT_EQ(escaped("walk"), "'walk'");
  EXPECT_EQ(escaped("\x1b[31mred"), "'\\x1b[31mred'");
  EXPECT_EQ(escaped(std::string(100, 'a'), 10), "'aaaaaaaaaa...'");
  EXPECT_EQ(number_text(1.7976931348623157e308), "1.79769e+308");
}
