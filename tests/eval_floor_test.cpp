// On small simulated datasets (embedded motions on the demo's four original
// bodies): the noise-floor row of the evaluation (issue 10, item 2) and the
// unseen freestyle pairs of the body-scale baseline once placement is
// shared per motion (item 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "data_test_util.hpp"
#include "eval/eval_internal.hpp"
#include "ptnet/body.hpp"
#include "ptnet/data.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/simulate_dataset.hpp"

namespace ptnet {
namespace {

using testing_util::TempDir;

// Simulates `clips` on `bodies` (seed 1) and evaluates every test pair with
// the copy baseline standing in for the model.
struct Evaluated {
  TempDir dir{"eval_floor"};
  Dataset dataset;
  std::vector<EvalRow> rows;
  Evaluated(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies, bool floor)
      : dataset(simulated(clips, bodies, floor, dir)) {
    const TransferFn copy = [](const PressureSequence& s, const BodySpec&, const BodySpec&) { return s; };
    rows = evaluate_pairs(dataset, copy, {});
  }
  static Dataset simulated(const std::vector<ClipSource>& clips, const std::vector<BodySpec>& bodies, bool floor,
                           const TempDir& dir) {
    SimulateDatasetOptions o;
    o.seed = 1;
    o.threads = 2;
    o.noise_floor = floor;
    simulate_dataset(clips, bodies, dir.file("d.h5"), o);
    return Dataset::open(dir.file("d.h5"));
  }
};

std::vector<ClipSource> embedded(int performers, double seconds, const std::string& only = "") {
  std::vector<ClipSource> out;
  for (const ClipSource& c : embedded_clips(performers, 2, seconds, 1))
    if (only.empty() || c.meta.category == only) out.push_back(c);
  return out;
}

TEST(Floor, StoredForOriginalBodiesAndReportedInEveryCategory) {
  // 2 performers x 4 categories x 2 takes of 4 s on the demo's original
  // bodies and one retargeted body.
  const Evaluated e(embedded(2, 4.0), sample_bodies(0, 1, 2, 2, 1), true);
  int floors = 0;
  for (const auto& s : e.dataset.sequences()) {
    const bool original = e.dataset.body(s.body_id).role == "original";
    EXPECT_EQ(s.floor, original) << s.name;
    if (!s.floor) {
      EXPECT_NE(testing_util::error_of([&] { e.dataset.read_floor(s.name); }).find("no noise-floor copy"),
                std::string::npos);
      continue;
    }
    ++floors;
    // Same physics, another sensor seed: the readings differ, but only by
    // noise (0.2 kPa SD): same total force and centre of pressure.
    const SequenceMetrics m = compare(e.dataset.read_floor(s.name), e.dataset.read(s.name), {});
    EXPECT_GT(m.rmse_kpa, 0.0) << s.name;
    EXPECT_LT(m.rmse_kpa, 0.2) << s.name;
    EXPECT_LT(m.force_error_pct, 0.5) << s.name;
    EXPECT_LT(m.cop_error_cm, 0.1) << s.name;
  }
  EXPECT_EQ(floors, 16 * 4);

  int floor_rows = 0;
  for (const auto& r : e.rows) floor_rows += r.method == "floor";
  EXPECT_EQ(floor_rows * 5, int(e.rows.size()));  // one per pair, beside model and three baselines
  int groups = 0;
  for (const GroupSummary& g : summarise(e.rows)) {
    if (g.method != "floor") continue;
    ++groups;
    std::printf("[floor] %-9s %-6s RMSE %.4f kPa  binary R^2 %.4f  (%d pairs)\n", g.group.c_str(),
                g.seen ? "seen" : "unseen", g.mean.rmse_kpa, g.mean.binary_r2, g.rows);
    EXPECT_GT(g.mean.rmse_kpa, 0.0) << g.group;
    EXPECT_LT(g.mean.rmse_kpa, 0.2) << g.group;  // sensor noise 0.2 kPa SD on loaded cells only
    EXPECT_LT(g.mean.binary_r2, 1.0) << g.group;
    EXPECT_GT(g.mean.binary_r2, 0.85) << g.group;
    // Far below what any baseline achieves.
    for (const GroupSummary& b : summarise(e.rows))
      if (b.method == "body_scale" && b.group == g.group && b.seen == g.seen)
        EXPECT_LT(g.mean.rmse_kpa, 0.2 * b.mean.rmse_kpa) << g.group;
  }
  EXPECT_EQ(groups, 2 * 5);  // 4 categories and the average, seen and unseen
  const std::string table = format_table(e.rows);
  EXPECT_NE(table.find("RMSE floor (kPa)"), std::string::npos) << table;
  EXPECT_EQ(table.find("n/a"), std::string::npos) << table;
  std::printf("%s", table.c_str());
}

TEST(Placement, NoUnseenFreestyleMotionFallsFarBelowItsBodyPairForBodyScale) {
  // Copies of one motion on two bodies lie along the same axis, so the
  // body-scale baseline does about as well on every unseen freestyle motion
  // for a given (source, target) body pair. (Placed per copy, p3 and p5
  // take 2 were laid across the mat for the 134 cm body only: binary R^2
  // -0.6 to -1.5 against ~0.25 to 0.85 on the other motions.) The level
  // itself depends on the pair: from the stout 134 cm body (67.7 kg) the
  // zoomed feet are much too wide for every taller body, in every category.
  // The embedded freestyle clips of `ptnet demo` (5 performers x 2 takes,
  // 8 s) on its original bodies.
  const Evaluated e(embedded(5, 8.0, "freestyle"), sample_bodies(0, 0, 2, 2, 1), false);
  std::map<std::pair<std::string, std::string>, std::vector<double>> by_pair;
  for (const auto& r : e.rows)
    if (r.method == "body_scale" && r.category == "freestyle" && r.take == 2)
      by_pair[{r.source_body, r.target_body}].push_back(r.metrics.binary_r2);
  ASSERT_EQ(by_pair.size(), 4u * 3);
  for (const auto& [bodies, r2] : by_pair) {
    ASSERT_EQ(r2.size(), 5u);
    double mean = 0;
    for (double v : r2) mean += v / double(r2.size());
    const double worst = *std::min_element(r2.begin(), r2.end());
    EXPECT_GE(worst, mean - 0.15) << bodies.first << " -> " << bodies.second;
    std::printf("[freestyle unseen, body scale] %s -> %s mean binary R^2 %.3f, worst motion %.3f\n",
                bodies.first.c_str(), bodies.second.c_str(), mean, worst);
  }
  // Simulated without floor copies: the table says so instead of a number.
  EXPECT_NE(format_table(e.rows).find(kNoFloorNote), std::string::npos);
}

TEST(FloorTable, MissingFloorIsSaidNotInvented) {
  EvalRow r;
  r.method = "body_scale";
  r.category = "walking";
  r.metrics.rmse_kpa = 2;
  r.metrics.binary_r2 = 0.8;
  const std::string table = format_table({r});
  EXPECT_NE(table.find("| walking | 1 | 2.00 | 0.800 | n/a | n/a |"), std::string::npos) << table;
  EXPECT_NE(table.find(kNoFloorNote), std::string::npos) << table;
}

}  // namespace
}  // namespace ptnet
