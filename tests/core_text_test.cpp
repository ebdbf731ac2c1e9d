// Text inputs and names (ptnet/strings.hpp, ptnet/io.hpp): every text input
// is UTF-8 or refused in one line naming the file and line before any of it
// is used; a name that becomes a file name is one file name; numeric
// tables are read back as they are written (OpenSim storage, CSV),
// only the columns asked for parsed; list paths resolve as the filesystem
// does (through symbolic links), and an input that is no regular file is
// said as what it is.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <new>

#include "core/csv.hpp"
#include "core/io_internal.hpp"
#include "core/rate.hpp"
#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/strings.hpp"

using namespace ptnet;
using ptnet::testing_util::TempDir;
using ptnet::testing_util::error_of;
namespace fs = std::filesystem;

namespace {

void write(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

}  // namespace

TEST(Names, AUserNameThatBecomesAFileNameIsOneFileName) {
  EXPECT_EQ(name_problem("walk_s01"), "");
  EXPECT_EQ(name_problem("caf\xc3\xa9 2"), "");  // UTF-8 and blanks are fine
  EXPECT_EQ(name_problem(""), "is empty");
  EXPECT_EQ(name_problem("../escaped"), "holds '/'");
  EXPECT_EQ(name_problem("a/b"), "holds '/'");
  EXPECT_EQ(name_problem(".."), "is '.' or '..'");
  EXPECT_EQ(name_problem("."), "is '.' or '..'");
  EXPECT_EQ(name_problem("a\nb"), "holds a control byte");
  EXPECT_EQ(name_problem("caf\xe9"), "is not UTF-8");
  EXPECT_EQ(name_problem(std::string(kMaxNameBytes, 'a')), "");
  EXPECT_EQ(name_problem(std::string(kMaxNameBytes + 1, 'a')), "is longer than 200 bytes");
}

TEST(Utf8, ValidAndInvalidSequences) {
  EXPECT_EQ(utf8_invalid_at("plain ASCII"), std::string::npos);
  EXPECT_EQ(utf8_invalid_at("\xef\xbb\xbf" "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80"), std::string::npos);
  EXPECT_EQ(utf8_invalid_at("caf\xe9"), 3u);            // Latin-1 e acute
  EXPECT_EQ(utf8_invalid_at("ab\xc3"), 2u);             // cut short
  EXPECT_EQ(utf8_invalid_at("\xc0\xaf"), 0u);           // overlong '/'
  EXPECT_EQ(utf8_invalid_at("\xed\xa0\x80"), 0u);       // a surrogate
  EXPECT_EQ(utf8_invalid_at("\xf4\x90\x80\x80"), 0u);   // past U+10FFFF
  EXPECT_EQ(utf8_invalid_at("a\x80"), 1u);              // a lone continuation byte
  EXPECT_EQ(error_of([] { check_utf8("a,b\nc,d\ncaf\xe9,1\n", "t.csv"); }),
            "t.csv:3: expected UTF-8 text, found byte 0xE9 (Latin-1 or Windows-1252? save the file as UTF-8)");
}

// Before: read_text_file returned the bytes, and a Windows-1252 trials CSV
// ended in nlohmann's "[json.exception.type_error.316] incomplete UTF-8
// string" after the per-trial files were written.
TEST(Utf8, EveryTextFileIsCheckedWhenRead) {
  TempDir d("utf8");
  write(d.file("l1.csv"), "trial,markers\ncaf\xe9,x.trc\n");
  EXPECT_EQ(error_of([&] { read_text_file(d.file("l1.csv")); }),
            d.file("l1.csv") + ":2: expected UTF-8 text, found byte 0xE9 (Latin-1 or Windows-1252? save the file as UTF-8)");
  EXPECT_EQ(read_file_bytes(d.file("l1.csv")), "trial,markers\ncaf\xe9,x.trc\n");  // archives, digests: bytes
  write(d.file("ok.csv"), "\xef\xbb\xbftrial\r\ncaf\xc3\xa9\r\n");
  EXPECT_EQ(read_text_file(d.file("ok.csv")), "\xef\xbb\xbftrial\r\ncaf\xc3\xa9\r\n");
}

// A table file is text like any other (read_text_file, LineReader): a
// byte-order mark, CRLF and line numbers, a bad byte refused at its line.
TEST(Tables, AFileIsUtf8TextWithABomCrlfAndLineNumbers) {
  TempDir d("lines");
  write(d.file("a.csv"), "\xef\xbb\xbf" "time,fx\r\n0,1\r\n\r\n0.1,2");
  TableReader t(d.file("a.csv"));
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"time", "fx"}));
  EXPECT_EQ(t.rows_left(), 3u);
  std::vector<std::vector<double>> rows;
  for (std::vector<double> v; t.next({0, 1}, v);) rows.push_back(v);
  EXPECT_EQ(rows, (std::vector<std::vector<double>>{{0, 1}, {0.1, 2}}));
  EXPECT_EQ(t.line(), 4);
  std::string many = "time,fx\n";
  for (int i = 1; i <= 3000; ++i) many += std::to_string(i) + ",0\n";
  write(d.file("latin1.csv"), many + "caf\xe9,1\n");
  EXPECT_EQ(error_of([&] { TableReader bad(d.file("latin1.csv")); }),
            d.file("latin1.csv") + ":3002: expected UTF-8 text, found byte 0xE9 (Latin-1 or Windows-1252? save the file as UTF-8)");
}

TEST(Tables, StorageAndCsvReadBackAsWritten) {
  TempDir d("tables");
  const std::vector<std::string> columns{"time", "a", "b"};
  const std::vector<std::vector<double>> rows{{0, 1.5, -2}, {0.01, 3, 4e-7}};
  for (const char* name : {"t.mot", "t.sto", "t.csv"}) {
    write_table_file(d.file(name), columns, rows, "a note", false);
    TableReader t(d.file(name));
    EXPECT_EQ(t.columns(), columns) << name;
    EXPECT_EQ(t.column("b"), 2);
    EXPECT_EQ(t.column("nope"), -1);
    std::vector<std::vector<double>> back;
    for (std::vector<double> v; t.next({0, 1, 2}, v);) back.push_back(v);
    EXPECT_EQ(back, rows) << name;
  }
  EXPECT_EQ(error_of([&] { TableReader t(d.file("t.txt")); }), d.file("t.txt") + ": expected a .mot, .sto or .csv file name");
  write_table_file(d.file("UPPER.MOT"), columns, rows, "", false);
  EXPECT_EQ(TableReader(d.file("UPPER.MOT")).columns(), columns);
  EXPECT_EQ(parse_table_format("csv"), TableFormat::csv);
  EXPECT_STREQ(table_format_name(TableFormat::mot), "mot");
  EXPECT_EQ(error_of([] { parse_table_format("txt"); }), "table format: expected mot or csv, found 'txt'");
}

// Before: the storage reader kept every value of every column as a double
// (a row a vector) beside the whole text, and refused a file whose first
// line was "endheader" after a byte-order mark.
TEST(Tables, OnlyTheColumnsAskedForAreParsedAndABomIsAccepted) {
  const std::string text = "\xef\xbb\xbf" "endheader\ntime\tlabel\tfx\n0\tleft\t1\n0.1\tright\t2\n";
  TableReader t(text, "t.mot", TableFormat::mot);
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"time", "label", "fx"}));
  std::vector<double> v;
  ASSERT_TRUE(t.next({2, 0}, v));
  EXPECT_EQ(v, (std::vector<double>{1, 0}));
  ASSERT_TRUE(t.next({2, 0}, v));
  EXPECT_EQ(t.line(), 4);
  EXPECT_FALSE(t.next({2, 0}, v));
  TableReader bad("endheader\ntime\tfx\n0\tabc\n0.1\n", "b.mot", TableFormat::mot);
  EXPECT_EQ(error_of([&] { bad.next({0, 1}, v); }), "b.mot:3: expected a number in column fx, found 'abc'");
  EXPECT_EQ(error_of([&] { bad.next({0}, v); }), "b.mot:4: expected 2 values (one per column), found 1");
  EXPECT_EQ(error_of([] { TableReader("time\tx\n0\t1\n", "n.mot", TableFormat::mot); }),
            "n.mot: expected an OpenSim storage header ending in 'endheader', found none");
}

// Before: physics-bench joined a CSV's folder and a name as text
// (lexically_normal), so "link/../x.trc" through a linked folder was "not
// found"; the filesystem resolves ".." after the link, as the shell does.
TEST(Paths, AListsPathsResolveThroughSymbolicLinks) {
  TempDir d("paths");
  fs::create_directories(d.path / "real" / "deep");
  fs::create_directories(d.path / "top");
  fs::create_symlink(d.path / "real" / "deep", d.path / "top" / "link");
  write(d.file("real/x.trc"), "x");
  const std::string p = resolved_path(d.file("top"), "link/../x.trc");
  EXPECT_TRUE(fs::is_regular_file(p)) << p;
  EXPECT_EQ(input_file_problem(p), "");
  EXPECT_EQ(resolved_path("any", "/abs/x.trc"), "/abs/x.trc");
  EXPECT_EQ(resolved_path("any", ""), "");
}

TEST(Paths, AnInputThatIsNoRegularFileIsSaidAsWhatItIs) {
  TempDir d("kinds");
  ASSERT_EQ(::mkfifo(d.file("f.mot").c_str(), 0600), 0);
  ErrorKind kind{};
  EXPECT_EQ(input_file_problem(d.file("f.mot"), &kind), "is a FIFO, expected a regular file");
  EXPECT_EQ(input_file_problem(d.path.string()), "is a folder, expected a file");
  EXPECT_EQ(input_file_problem(d.file("gone.mot"), &kind), "no such file");
  EXPECT_EQ(kind, ErrorKind::not_found);
}

// Before: check_outputs_in_folder only asked for `force`, so an output that
// was an input of the run was found only when written, after the work.
TEST(Paths, OutputsInAFolderAreCheckedAsEveryOutputIs) {
  TempDir d("outs");
  write(d.file("in.csv"), "x\n");
  note_input(d.file("in.csv"));
  EXPECT_NE(error_of([&] { check_outputs_in_folder(d.path.string(), {"in.csv"}, true); })
                .find("is the same file as the input"),
            std::string::npos);
  ASSERT_EQ(::mkfifo(d.file("p.mot").c_str(), 0600), 0);
  EXPECT_NE(error_of([&] { check_outputs_in_folder(d.path.string(), {"p.mot"}, true); }).find("is a FIFO"),
            std::string::npos);
}

TEST(Rates, OneToleranceForTheSameFrameRate) {
  EXPECT_TRUE(same_rate(1 / 0.016667, 60));  // a header's Frame Time, rounded
  EXPECT_TRUE(same_rate(30 * (1 + 0.5 * kSameRateTolerance), 30));
  EXPECT_FALSE(same_rate(30 * (1 + 2 * kSameRateTolerance), 30));
  EXPECT_FALSE(same_rate(59.9, 60));
}

namespace {

// Runs f with this process's address space limited to what it uses now
// plus `room` bytes (ulimit -v), the limit restored after.
template <typename F>
void with_address_space_room(std::uint64_t room, F f) {
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_AS, &old), 0);
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  rlimit tight = old;
  tight.rlim_cur = rlim_t(pages * std::uint64_t(::sysconf(_SC_PAGE_SIZE)) + room);
  ASSERT_EQ(::setrlimit(RLIMIT_AS, &tight), 0);
  try {
    f();
  } catch (...) {
    ::setrlimit(RLIMIT_AS, &old);
    throw;
  }
  ::setrlimit(RLIMIT_AS, &old);
}

}  // namespace

// Before: a CSV's table was only bounded by the file's size (1 GiB), and
// grew to ~13 times it (a 105 MB clips CSV of short fields: 1.41 GB); under
// `ulimit -v` the reader ended in std::bad_alloc. What the table holds at
// most is now checked against the memory the process may still use.
TEST(Memory, ACsvTableIsCheckedAgainstTheMemoryLeftBeforeItIsParsed) {
  const std::string text = "a\n" + std::string(20000000, ',');  // 20 M empty fields: 640 MB of strings
  std::string message;
  with_address_space_room(std::uint64_t(256) << 20, [&] {
    EXPECT_LE(available_memory_bytes(), std::uint64_t(256) << 20);
    try {
      parse_csv(text, "wide.csv");
    } catch (const Error& e) {
      message = e.what();
    } catch (const std::bad_alloc&) {
      message = "std::bad_alloc";
    }
  });
  EXPECT_EQ(message.rfind("wide.csv: the CSV's 20000002 fields needs ", 0), 0u) << message;
  EXPECT_NE(message.find("of available memory"), std::string::npos) << message;
  EXPECT_EQ(parse_csv("a,b\n1,2\n", "small.csv").rows.size(), 1u);
}
