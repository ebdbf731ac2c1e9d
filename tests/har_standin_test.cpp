// The stand-in for real recordings: its degraded sensor (gain spread, dead
// cells) and the dataset it writes.
#include <gtest/gtest.h>

#ifdef PTNET_HAR_STANDIN
#include <algorithm>
#include <filesystem>

#include "ptnet/data.hpp"
#include "ptnet/har.hpp"

using namespace ptnet;
using namespace ptnet::har;

TEST(HarStandin, GainMapIsSeededWithTheRequestedDeadCells) {
  StandinOptions o;
  const MatSpec mat;
  const auto a = standin_gain_map(mat, o), b = standin_gain_map(mat, o);
  EXPECT_EQ(a, b);
  EXPECT_EQ(std::count(a.begin(), a.end(), 0.0f), 22);  // 1 % of 2240 cells
  std::vector<float> live;
  for (float g : a)
    if (g > 0) live.push_back(g);
  std::nth_element(live.begin(), live.begin() + live.size() / 2, live.end());
  EXPECT_NEAR(live[live.size() / 2], 1.0, 0.03);  // log-normal median 1
  const auto [lo, hi] = std::minmax_element(live.begin(), live.end());
  EXPECT_LT(*lo, 0.75f);  // sigma 0.15 over 2218 cells reaches beyond +-2 sigma
  EXPECT_GT(*hi, 1.3f);
  o.seed = 2;
  EXPECT_NE(standin_gain_map(mat, o), a);
}

TEST(HarStandin, WritesSubjectsOnTheirOwnBodiesWithDeadCellsSilent) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "ptnet_har_standin_test.h5").string();
  StandinOptions o;
  o.subjects = 2;
  o.seconds = 2;
  o.threads = 1;
  write_standin(path, o, /*force=*/true);
  const Dataset d = Dataset::open(path);
  ASSERT_EQ(d.bodies().size(), 2u);
  EXPECT_EQ(d.bodies()[0].id, "s1");
  EXPECT_EQ(d.bodies()[1].role, "original");
  EXPECT_NE(d.bodies()[0].height_cm, d.bodies()[1].height_cm);
  EXPECT_NE(d.info().config_json.find("stand-in"), std::string::npos);
  ASSERT_EQ(d.sequences().size(), 8u);  // 2 subjects x 4 categories
  const auto gain = standin_gain_map(d.info().mat, o);
  double total = 0;
  for (const auto& m : d.sequences()) {
    EXPECT_FALSE(m.category.empty());
    const PressureSequence s = d.read(m.name);
    for (int t = 0; t < s.frames(); ++t)
      for (int i = 0; i < s.mat.cells(); ++i) {
        if (gain[i] == 0) EXPECT_EQ(s.frame(t)[i], 0.0f);
        total += s.frame(t)[i];
      }
  }
  EXPECT_GT(total, 0.0);  // the subjects do press on the mat
  std::filesystem::remove(path);
}
#else
TEST(HarStandin, NeedsTheSimulator) { GTEST_SKIP() << "simulator stage not built yet"; }
#endif
