// The evaluation protocol (issue 5): ordered pairs of different original
// bodies on the same motion, take 1 = seen, take 2 = unseen; model beside
// the copy and weight-ratio baselines.
#include <gtest/gtest.h>

#include <map>

#include "data_test_util.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "support/synthetic_walk.hpp"

namespace ptnet {
namespace {

using testing_util::TempDir;

// Three original bodies and one retargeted; motions m1 (take 1) and m2 (take 2).
std::string write_protocol_dataset(const TempDir& dir, bool with_originals = true) {
  const std::string path = dir.file("p.h5");
  std::vector<BodySpec> bodies{{"r1", Sex::female, 160, 55, "retargeted"},
                               {"o1", Sex::female, 162, 50, with_originals ? "original" : "retargeted"},
                               {"o2", Sex::male, 180, 100, with_originals ? "original" : "retargeted"},
                               {"o3", Sex::male, 175, 75, with_originals ? "original" : "retargeted"}};
  DatasetWriter w(path, DatasetInfo{}, bodies, false);
  for (const auto& [motion, take] : std::map<std::string, int>{{"m1", 1}, {"m2", 2}})
    for (const auto& b : bodies) {
      SequenceMeta meta = testing_util::meta_for(motion, b.id, take, take == 1 ? "walking" : "rom");
      w.add(meta, synthetic_walk(MatSpec{}, 40, 30, b.height_cm, b.weight_kg, 0));
    }
  w.commit();
  return path;
}

TEST(Protocol, OrderedPairsOfOriginalBodiesOnTheSameMotion) {
  TempDir dir("eval_pairs");
  const Dataset d = Dataset::open(write_protocol_dataset(dir));
  const auto pairs = test_pairs(d);
  ASSERT_EQ(pairs.size(), 12u);  // 2 motions x 3 x 2 ordered pairs; r1 never used
  for (const auto& p : pairs) {
    EXPECT_NE(p.source_sequence, p.target_sequence);
    EXPECT_EQ(p.source_sequence.find("r1"), std::string::npos);
    EXPECT_EQ(p.take, p.motion_id == "m1" ? 1 : 2);
  }
}

TEST(Protocol, OracleModelIsPerfectAndBaselinesAreNot) {
  TempDir dir("eval_oracle");
  const Dataset d = Dataset::open(write_protocol_dataset(dir));
  // An oracle returning the target body's ground truth (synthetic_walk depends
  // only on the body, so m1 and m2 share it).
  TransferFn oracle = [&](const PressureSequence&, const BodySpec&, const BodySpec& target) {
    return d.read("m1__" + target.id);
  };
  int calls = 0;
  EvaluateOptions options;
  options.progress = [&](const Progress& p) {
    ++calls;
    EXPECT_EQ(p.total, 12);
    EXPECT_EQ(p.done, calls);
    EXPECT_EQ(p.unit, "pairs");
  };
  const auto rows = evaluate_pairs(d, oracle, options);
  ASSERT_EQ(rows.size(), 48u);
  EXPECT_EQ(calls, 12);
  for (const auto& r : rows) {
    if (r.method == "model") {
      EXPECT_DOUBLE_EQ(r.metrics.rmse_kpa, 0.0);
      EXPECT_DOUBLE_EQ(r.metrics.binary_r2, 1.0);
    } else {
      // Different bodies leave different maps: the baselines are imperfect.
      EXPECT_GT(r.metrics.rmse_kpa, 0.0) << r.method << " " << r.source_sequence;
    }
  }
  const std::string table = format_table(rows);
  EXPECT_NE(table.find("Seen motions"), std::string::npos);
  EXPECT_NE(table.find("Unseen motions"), std::string::npos);
}

TEST(Protocol, NoOriginalBodiesIsAClearError) {
  TempDir dir("eval_none");
  const Dataset d = Dataset::open(write_protocol_dataset(dir, false));
  TransferFn copy = [](const PressureSequence& s, const BodySpec&, const BodySpec&) { return s; };
  try {
    evaluate_pairs(d, copy, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no test pairs"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ptnet
