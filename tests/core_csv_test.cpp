// The one CSV reader (RFC 4180) and the bodies and clips CSV written by Excel
// or pandas: a byte-order mark, CRLF, quoted fields, quoted commas and
// quotes, columns in any order.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/csv.hpp"
#include "data_test_util.hpp"
#include "ptnet/body_spec.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/simulate_dataset.hpp"

using namespace ptnet;
using ptnet::testing_util::TempDir;
using ptnet::testing_util::error_of;

TEST(Csv, Rfc4180QuotingAndLineEnds) {
  const CsvTable t = parse_csv(
      "\xEF\xBB\xBF" "Name, Note ,N\r\n"
      "\"a, b\",\"say \"\"hi\"\"\",1\r\n"
      "\r\n"
      "# a comment line\n"
      "\"two\nlines\",  plain  ,\"\"\n"
      "last,x,3",
      "t.csv");
  EXPECT_EQ(t.header, (std::vector<std::string>{"name", "note", "n"}));
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[0].fields, (std::vector<std::string>{"a, b", "say \"hi\"", "1"}));
  EXPECT_EQ(t.rows[0].line, 2);
  EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"two\nlines", "plain", ""}));
  EXPECT_EQ(t.rows[1].line, 5);
  EXPECT_EQ(t.rows[2].fields, (std::vector<std::string>{"last", "x", "3"}));
  EXPECT_EQ(t.rows[2].line, 7);  // the quoted line break counts
  EXPECT_EQ(t.column("note"), 1);
  EXPECT_EQ(t.column("missing"), -1);
}

TEST(Csv, MalformedInputIsOneLineNamingFileAndLine) {
  EXPECT_EQ(error_of([] { parse_csv("a,b\n1,\"open\n2,3\n", "t.csv"); }),
            "t.csv:2: expected a closing quote, found end of file");
  EXPECT_EQ(error_of([] { parse_csv("a,b\n1,2,3\n", "t.csv"); }), "t.csv:2: expected 2 fields (as the header), found 3");
  EXPECT_EQ(error_of([] { parse_csv("a,b\n1,\"x\"y\n", "t.csv"); }),
            "t.csv:2: expected a comma or line end after a closing quote, found 'y'");
  EXPECT_EQ(error_of([] { parse_csv("a,b\n1,x\"y\"\n", "t.csv"); }),
            "t.csv:2: expected a quote only at the start of a field, found 'x\"y\"'");
  EXPECT_EQ(error_of([] { parse_csv("\n# only a comment\n", "t.csv"); }), "t.csv: empty CSV file, expected a header line");
  EXPECT_EQ(error_of([] { parse_csv("a,b\n", "t.csv").required("c", "a,b,c"); }),
            "t.csv:1: expected a header with column c (a,b,c), found 'a,b'");
}

// Before: a second column of one name was never read (column() gives the
// first): a trials CSV "trial,markers,...,markers" ran on the first file.
TEST(Csv, AColumnIsNamedOnce) {
  EXPECT_EQ(error_of([] { parse_csv("trial,Markers,plates,markers\nw,a.trc,a.mot,b.trc\n", "t.csv"); }),
            "t.csv:1: expected each column named once, found 'markers' as columns 2 and 4");
  EXPECT_EQ(parse_csv("a,,b,\n1,2,3,4\n", "t.csv").rows.size(), 1u);  // empty names: no name to take twice
}

TEST(Csv, WrittenFieldsReadBack) {
  for (const std::string v : {"plain", "a, b", "say \"hi\"", " padded ", "#hash", "two\nlines", ""}) {
    const CsvTable t = parse_csv("h,x\n" + csv_field(v) + ",1\n", "t.csv");
    ASSERT_EQ(t.rows.size(), 1u) << v;
    EXPECT_EQ(t.rows[0].fields[0], v);
  }
}

TEST(BodiesCsv, ExcelAndPandasDialects) {
  TempDir d("csv_bodies");
  const std::string p = d.file("bodies.csv");
  // Excel: BOM, CRLF, quoted strings; pandas: another column order, an index column.
  std::ofstream(p, std::ios::binary) << "\xEF\xBB\xBF" ",weight_kg,\"sex\",id,height_cm,role\r\n"
                                        "0,60,\"female\",\"a, 1\",165,original\r\n"
                                        "1,\"80.5\",male,b2,180,\r\n";
  const auto bodies = read_bodies_csv(p);
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].id, "a, 1");
  EXPECT_EQ(bodies[0].sex, Sex::female);
  EXPECT_EQ(bodies[0].height_cm, 165);
  EXPECT_EQ(bodies[0].weight_kg, 60);
  EXPECT_EQ(bodies[0].role, "original");
  EXPECT_EQ(bodies[1].weight_kg, 80.5);
  EXPECT_EQ(bodies[1].role, "retargeted");
  // format_bodies_csv quotes what needs it, and reads back the same.
  write_text_file(d.file("again.csv"), format_bodies_csv(bodies), false);
  const auto again = read_bodies_csv(d.file("again.csv"));
  EXPECT_EQ(again[0].id, "a, 1");
  EXPECT_EQ(again[1].weight_kg, 80.5);
}

TEST(BodiesCsv, ErrorsEscapeWhatTheyEcho) {
  TempDir d("csv_bodies_bad");
  const std::string p = d.file("bodies.csv");
  std::ofstream(p) << "id,sex,height_cm,weight_kg\nb1,\x1b[2Jfemale,165,60\n";
  EXPECT_EQ(error_of([&] { read_bodies_csv(p); }), p + ":2: expected sex female or male, found '\\x1b[2Jfemale'");
  std::ofstream(p) << "id,sex,height_cm,weight_kg\nb1,female,1e308,60\n";
  EXPECT_EQ(error_of([&] { read_bodies_csv(p); }), p + ":2: expected height_cm in 100-230, found 1e+308");
  std::ofstream(p) << "id,sex,height\nb1,female,165\n";
  EXPECT_EQ(error_of([&] { read_bodies_csv(p); }),
            p + ":1: expected a header with column height_cm (id,sex,height_cm,weight_kg[,role]), found "
                "'id,sex,height'");
}

TEST(ClipsCsv, QuotedFieldsAnyOrderAndCrlf) {
  TempDir d("csv_clips");
  std::ofstream(d.file("walk, one.bvh")) << "x";
  std::ofstream(d.file("clips.csv"), std::ios::binary)
      << "\xEF\xBB\xBF" "Take,Category,Subject,File,UP\r\n2,\"Walking\",\"7\",\"walk, one.bvh\",Z\r\n";
  const auto rows = read_clips_csv(d.file("clips.csv"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].file, d.file("walk, one.bvh"));
  EXPECT_EQ(rows[0].subject, "7");
  EXPECT_EQ(rows[0].category, "walking");
  EXPECT_EQ(rows[0].take, 2);
  EXPECT_EQ(rows[0].up, "z");
  EXPECT_EQ(rows[0].line, 2);
}
