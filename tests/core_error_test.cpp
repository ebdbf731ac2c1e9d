// ptnet::Error: messages name option fields as the library spells them, a
// front end spells them its own way (the CLI: flags), and the kind survives
// an Error that rewords another.
#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "data_test_util.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"

namespace ptnet {
namespace {

std::string as_flag(std::string_view field) {
  std::string flag = "--";
  for (char c : field) flag += c == '_' ? '-' : c;
  return flag;
}

TEST(CoreError, FieldsAreNamesInWhatAndSpelledByText) {
  const Error e(field_text("micro_batch") + ": must be >= 1, found 0; see " + field_text("batch"));
  EXPECT_STREQ(e.what(), "micro_batch: must be >= 1, found 0; see batch");
  EXPECT_EQ(e.text(as_flag), "--micro-batch: must be >= 1, found 0; see --batch");
  EXPECT_EQ(e.kind(), ErrorKind::invalid);
  // Without fields, text() is what().
  const Error plain("walk.bvh: no such file", ErrorKind::not_found);
  EXPECT_EQ(plain.text(as_flag), "walk.bvh: no such file");
  EXPECT_EQ(plain.message(), "walk.bvh: no such file");
}

TEST(CoreError, ARewordingKeepsFieldsAndKind) {
  const Error inner =
      Error::in("m", "exists; pass " + field_text("force") + " to overwrite", ErrorKind::exists);
  const Error outer("rank 1: " + inner.message(), inner.kind());
  EXPECT_STREQ(outer.what(), "rank 1: m: exists; pass force to overwrite");
  EXPECT_EQ(outer.text(as_flag), "rank 1: m: exists; pass --force to overwrite");
  EXPECT_EQ(outer.kind(), ErrorKind::exists);
}

TEST(CoreError, OnlyWellFormedMarksAreFields) {
  // A stray mark byte (say, in a file name) is left as it is.
  // (unclosed, not a field's characters, empty, unclosed at the end)
  const std::string odd = std::string("a\x1f") + "b c " + "\x1fNo\x1f " + "\x1f\x1f " + "\x1f";
  const Error e(odd);
  EXPECT_EQ(std::string(e.what()), odd);
  EXPECT_EQ(e.text(as_flag), odd);
}

TEST(CoreError, KindsOfTheFactories) {
  EXPECT_EQ(Error::at("walk.bvh", 3, "CHANNELS", "OFFSET").kind(), ErrorKind::format);
  EXPECT_STREQ(Error::at("walk.bvh", 3, "CHANNELS", "OFFSET").what(),
               "walk.bvh:3: expected CHANNELS, found OFFSET");
  EXPECT_EQ(Error::in("a.npy", "npy header truncated").kind(), ErrorKind::format);
  EXPECT_EQ(Error::in("a.npy", "cannot write", ErrorKind::io).kind(), ErrorKind::io);
}

TEST(CoreError, OutputsAndInputsSayTheirKind) {
  testing_util::TempDir d("core_error");
  const std::string path = d.file("a.txt");
  write_text_file(path, "x", false);
  try {
    write_text_file(path, "y", false);
    FAIL() << "overwrote without force";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::exists);
    EXPECT_EQ(std::string(e.what()), path + ": exists; pass force to overwrite");
    EXPECT_EQ(e.text(as_flag), path + ": exists; pass --force to overwrite");
  }
  try {
    read_text_file(d.file("missing.txt"));
    FAIL() << "read a missing file";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::not_found);
    EXPECT_EQ(std::string(e.what()), d.file("missing.txt") + ": no such file");
  }
  try {
    write_text_file(d.file("no/such/folder/b.txt"), "x", false);
    FAIL() << "wrote into a missing folder";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::not_found);
  }
}

}  // namespace
}  // namespace ptnet
