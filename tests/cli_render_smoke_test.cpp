// ptnet render end to end: a dataset written here, a PNG and a GIF, a bad
// sequence name (exit 1, one line), refusing to overwrite.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "data_test_util.hpp"

namespace {
using ptnet::testing_util::TempDir;

int run(const std::string& args, std::string* out) {
  FILE* p = popen((std::string(PTNET_BINARY) + " " + args + " 2>&1").c_str(), "r");
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out->append(buf, n);
  int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CliRender, PngAndGifFromADataset) {
  TempDir dir("cli_render");
  const auto data = dir.file("data.h5");
  ptnet::testing_util::write_small_dataset(data, 40, 5);
  std::string out;
  ASSERT_EQ(run("-q render " + data + " -s walk_a__b1 -s walk_a__b2 --out " + dir.file("f.png") +
                    " --frames 4 --cop",
                &out), 0) << out;
  EXPECT_EQ(out, "");
  EXPECT_GT(std::filesystem::file_size(dir.file("f.png")), 2000u);
  out.clear();
  ASSERT_EQ(run("-q render " + data + " -s walk_a__b1 --out " + dir.file("f.gif") + " --frame-list 0,10,20", &out), 0) << out;
  EXPECT_GT(std::filesystem::file_size(dir.file("f.gif")), 1000u);

  out.clear();
  EXPECT_EQ(run("render " + data + " -s nope --out " + dir.file("g.png"), &out), 1);
  EXPECT_EQ(out, "ptnet: error: " + data + ": no sequence 'nope' (e.g. 'walk_a__b1'; `ptnet info` lists them)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("g.png")));

  out.clear();
  EXPECT_EQ(run("render " + data + " -s walk_a__b1 --out " + dir.file("f.png"), &out), 1);
  EXPECT_EQ(out, "ptnet: error: " + dir.file("f.png") + ": exists; pass --force to overwrite\n");
  out.clear();
  EXPECT_EQ(run("-q render " + data + " -s walk_a__b1 --out " + dir.file("f.png") + " --force", &out), 0) << out;

  out.clear();
  EXPECT_EQ(run("render " + data + " -s walk_b__b1 --out " + dir.file("h.png") + " --frame-list 7", &out), 1);
  EXPECT_EQ(out, "ptnet: error: " + data + ": frame 7 outside the sequence (5 frames: 0-4)\n");
  out.clear();
  EXPECT_EQ(run("render " + data + " -s walk_b__b1 --out " + dir.file("h.jpg"), &out), 1);
  EXPECT_EQ(out, "ptnet: error: " + dir.file("h.jpg") + ": expected a .png or .gif file name (a PNG strip or a GIF animation is written), found '.jpg'\n");
}

TEST(CliInfo, DescribesADataset) {
  TempDir dir("cli_info");
  const auto data = dir.file("data.h5");
  ptnet::testing_util::write_small_dataset(data, 40, 5);
  std::string out;
  ASSERT_EQ(run("info " + data, &out), 0) << out;
  EXPECT_NE(out.find("  sequences  4 (2 motions), 90 frames"), std::string::npos) << out;
  EXPECT_NE(out.find("  bodies     2 (1 female, 1 male; 1 original, 1 retargeted)"), std::string::npos) << out;
  EXPECT_NE(out.find("  b2          male        186.0       94.0  original"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(run("info --json " + data, &out), 0) << out;
  EXPECT_NE(out.find("\"frames\": 90,"), std::string::npos) << out;
  out.clear();
  EXPECT_EQ(run("info " + dir.file("none.h5"), &out), 1);
  EXPECT_EQ(out, "ptnet: error: " + dir.file("none.h5") + ": no such file\n");
}

}  // namespace
