// Sharded simulation: the N shards of `simulate --shard K/N`, merged (in any
// order), hold the unsharded run's sequences, attributes, bodies and noise
// floors, field by field; merge refuses missing, repeated or foreign parts.
#include <gtest/gtest.h>

#include "data_test_util.hpp"
#include <filesystem>

#include "ptnet/data.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet {
namespace {

using testing_util::error_of;
using testing_util::TempDir;

const std::vector<BodySpec> kBodies{{"f1", Sex::female, 158, 55, "retargeted"},
                                    {"m1", Sex::male, 181, 84, "retargeted"},
                                    {"m2", Sex::male, 188, 90, "original"}};

SimulateDatasetOptions options(int k = 0, int n = 1) {
  SimulateDatasetOptions o;
  o.seed = 5;
  o.threads = 2;
  o.shard_index = k;
  o.shard_count = n;
  return o;
}

void expect_same_dataset(const Dataset& a, const Dataset& b) {
  EXPECT_EQ(a.info().mat, b.info().mat);
  EXPECT_EQ(a.info().fps, b.info().fps);
  EXPECT_EQ(a.info().generator, b.info().generator);
  EXPECT_EQ(a.info().config_json, b.info().config_json);
  ASSERT_EQ(a.bodies().size(), b.bodies().size());
  for (std::size_t i = 0; i < a.bodies().size(); ++i) {
    const BodySpec &x = a.bodies()[i], &y = b.bodies()[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.sex, y.sex);
    EXPECT_EQ(x.height_cm, y.height_cm);
    EXPECT_EQ(x.weight_kg, y.weight_kg);
    EXPECT_EQ(x.role, y.role);
  }
  ASSERT_EQ(a.sequences().size(), b.sequences().size());
  for (const SequenceMeta& x : a.sequences()) {
    const SequenceMeta& y = b.sequence(x.name);
    EXPECT_EQ(x.body_id, y.body_id) << x.name;
    EXPECT_EQ(x.motion_id, y.motion_id) << x.name;
    EXPECT_EQ(x.performer, y.performer) << x.name;
    EXPECT_EQ(x.category, y.category) << x.name;
    EXPECT_EQ(x.take, y.take) << x.name;
    EXPECT_EQ(x.source, y.source) << x.name;
    EXPECT_EQ(x.frames, y.frames) << x.name;
    ASSERT_EQ(x.floor, y.floor) << x.name;
    EXPECT_EQ(a.read(x.name).kpa, b.read(x.name).kpa) << x.name;
    if (x.floor) EXPECT_EQ(a.read_floor(x.name).kpa, b.read_floor(x.name).kpa) << x.name;
  }
}

TEST(SimulateShard, MergedShardsEqualTheUnshardedRun) {
  TempDir dir("simulate_shard");
  const auto clips = embedded_clips(1, 1, 1.5, 3);  // 4 clips x 3 bodies = 12 sequences
  const auto whole = simulate_dataset(clips, kBodies, dir.file("whole.h5"), options());
  EXPECT_EQ(whole.sequences, 12);
  int total = 0;
  for (int k = 0; k < 5; ++k)  // 12 jobs in 5 uneven blocks
    total += simulate_dataset(clips, kBodies, dir.file("part" + std::to_string(k) + ".h5"), options(k, 5)).sequences;
  EXPECT_EQ(total, 12);
  EXPECT_EQ(Dataset::open(dir.file("part1.h5")).bodies().size(), 3u);  // every shard has every body
  const std::vector<std::string> parts{dir.file("part3.h5"), dir.file("part0.h5"), dir.file("part4.h5"),
                                       dir.file("part2.h5"), dir.file("part1.h5")};
  EXPECT_EQ(merge_datasets(parts, dir.file("merged.h5"), false), 12);
  expect_same_dataset(Dataset::open(dir.file("whole.h5")), Dataset::open(dir.file("merged.h5")));
}

TEST(SimulateShard, MergeRefusesIncompleteRepeatedOrForeignParts) {
  TempDir dir("simulate_shard_bad");
  const auto clips = embedded_clips(1, 1, 1.0, 3);
  for (int k = 0; k < 2; ++k)
    simulate_dataset(clips, kBodies, dir.file("p" + std::to_string(k) + ".h5"), options(k, 2));
  SimulateDatasetOptions other = options(1, 2);
  other.seed = 6;
  simulate_dataset(clips, kBodies, dir.file("other.h5"), other);
  simulate_dataset(clips, kBodies, dir.file("whole.h5"), options());
  const auto merge = [&](std::vector<std::string> names) {
    std::vector<std::string> paths;
    for (const auto& n : names) paths.push_back(dir.file(n));
    return error_of([&] { merge_datasets(paths, dir.file("out.h5"), false); });
  };
  EXPECT_EQ(merge({"p0.h5"}), "merge: shard 1/2 is missing (1 of 2 given)");
  EXPECT_EQ(merge({"p0.h5", "p0.h5"}), dir.file("p0.h5") + ": is shard 0/2, as is " + dir.file("p0.h5"));
  EXPECT_NE(merge({"p0.h5", "other.h5"}).find("the config differs"), std::string::npos);
  EXPECT_NE(merge({"p0.h5", "whole.h5"}).find("is not a shard"), std::string::npos);
  EXPECT_NE(merge({"whole.h5", "whole.h5"}).find("is also in"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.h5")));
  EXPECT_EQ(merge({"p0.h5", "p1.h5"}), "(no error)");
  EXPECT_NE(merge({"p0.h5", "p1.h5"}).find("exists"), std::string::npos);  // never overwritten without force
  EXPECT_EQ(error_of([&] { simulate_dataset(clips, kBodies, dir.file("x.h5"), options(2, 2)); }),
            "shard: expected K/N with 0 <= K < N, found 2/2");
}

// Shards of different runs do not merge though their options and counts
// agree: other clip lengths (--seconds), other BVH files; nor does a shard
// that lost a sequence.
TEST(SimulateShard, MergeRefusesShardsOfOtherRunsOrIncompleteShards) {
  TempDir dir("simulate_shard_runs");
  const auto merge = [&](std::vector<std::string> names) {
    std::vector<std::string> paths;
    for (const auto& n : names) paths.push_back(dir.file(n));
    return error_of([&] { merge_datasets(paths, dir.file("out.h5"), false); });
  };
  simulate_dataset(embedded_clips(1, 1, 1.0, 3), kBodies, dir.file("a0.h5"), options(0, 2));
  simulate_dataset(embedded_clips(1, 1, 1.5, 3), kBodies, dir.file("b1.h5"), options(1, 2));
  EXPECT_NE(merge({"a0.h5", "b1.h5"}).find(dir.file("b1.h5") + ": is a shard of another run than " + dir.file("a0.h5")),
            std::string::npos)
      << merge({"a0.h5", "b1.h5"});
  // Two folders of as many BVH files, the files' bytes differing.
  for (const std::string folder : {"x", "y"}) {
    std::filesystem::create_directories(dir.file(folder));
    for (int i = 0; i < 2; ++i) {
      GenerateOptions g;
      g.performer = 1 + i;
      g.seconds = folder == "x" ? 1.0 : 1.2;
      write_bvh(motion_to_bvh(generate_motion(g)), dir.file(folder + "/clip" + std::to_string(i) + ".bvh"), false);
    }
  }
  simulate_dataset(clips_from_files({dir.file("x")}, "", {}), kBodies, dir.file("x0.h5"), options(0, 2));
  simulate_dataset(clips_from_files({dir.file("y")}, "", {}), kBodies, dir.file("y1.h5"), options(1, 2));
  EXPECT_NE(merge({"x0.h5", "y1.h5"}).find("is a shard of another run"), std::string::npos) << merge({"x0.h5", "y1.h5"});
  // A shard that lost its last sequence (copied without it).
  simulate_dataset(embedded_clips(1, 1, 1.0, 3), kBodies, dir.file("a1.h5"), options(1, 2));
  {
    const Dataset full = Dataset::open(dir.file("a1.h5"));
    DatasetWriter w(dir.file("a1_short.h5"), full.info(), full.bodies(), false);
    for (std::size_t i = 0; i + 1 < full.sequences().size(); ++i) {
      const SequenceMeta& m = full.sequences()[i];
      w.add(m, full.read(m.name));
      if (m.floor) w.add_floor(m.name, full.read_floor(m.name));
    }
    w.commit();
  }
  EXPECT_EQ(merge({"a0.h5", "a1_short.h5"}),
            dir.file("a1_short.h5") + ": shard 1/2 of a run of 12 sequences holds 5 sequences, expected 6: an incomplete shard");
  EXPECT_FALSE(std::filesystem::exists(dir.file("out.h5")));
  EXPECT_EQ(merge({"a1.h5", "a0.h5"}), "(no error)");
}

}  // namespace
}  // namespace ptnet
