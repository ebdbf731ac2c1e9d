// The lazy window index: the paper's protocol (retargeted bodies, take 1),
// pairs, the leak-free 9:1 split, determinism; normalisation; the cache.
#include <gtest/gtest.h>

#include <set>

#include "ptnet/error.hpp"
#include "support/memory_source.hpp"
#include "train_synthetic.hpp"
#include "train/window_index.hpp"

using namespace ptnet;
using ptnet::testing::synth_source;

TEST(TrainPairs, ProtocolPairsAndCounts) {
  MemorySource src = synth_source(6, 3, 120);
  WindowOptions wo;
  wo.stride = 1;
  WindowIndex idx = WindowIndex::build(src, wo);
  EXPECT_EQ(idx.motions().size(), 3u);   // m3 is take 2: never used
  EXPECT_EQ(idx.pairs().size(), 3u * 6 * 5);  // ordered pairs of distinct bodies
  for (const auto& p : idx.pairs()) {
    const auto& a = src.sequences()[p.source];
    const auto& b = src.sequences()[p.target];
    EXPECT_EQ(a.motion_id, b.motion_id);
    EXPECT_NE(a.body_id, b.body_id);
    EXPECT_EQ(a.take, 1);
    EXPECT_EQ(src.body(a.body_id).role, "retargeted");
    EXPECT_EQ(src.body(b.body_id).role, "retargeted");
  }
  // 120 frames -> 91 starts; 9 validation starts; up to 2 x 29 starts dropped as gap.
  EXPECT_EQ(idx.val_size(), 90 * 9);
  EXPECT_GE(idx.train_size(), 90 * (91 - 9 - 58));
  EXPECT_LE(idx.train_size(), 90 * (91 - 9 - 29));
}

TEST(TrainPairs, ValidationWindowsNeverOverlapTrainingFrames) {
  MemorySource src = synth_source(4, 3, 150);
  WindowOptions wo;
  wo.stride = 3;
  WindowIndex idx = WindowIndex::build(src, wo);
  std::map<int, std::set<int>> val_frames;  // motion -> frames seen in validation
  for (std::int64_t i = 0; i < idx.val_size(); ++i) {
    WindowRef r = idx.val(i);
    for (int f = r.start; f < r.start + wo.window; ++f) val_frames[idx.pairs()[r.pair].motion].insert(f);
  }
  ASSERT_EQ(val_frames.size(), 3u);
  for (std::int64_t i = 0; i < idx.train_size(); ++i) {
    WindowRef r = idx.train(i);
    EXPECT_EQ(r.start % 1, 0);
    EXPECT_LE(r.start + wo.window, 150);
    const auto& vf = val_frames[idx.pairs()[r.pair].motion];
    for (int f = r.start; f < r.start + wo.window; ++f) ASSERT_EQ(vf.count(f), 0u) << "frame " << f;
  }
  EXPECT_THROW(idx.train(idx.train_size()), Error);
}

TEST(TrainPairs, SplitIsDeterministicInTheSeed) {
  MemorySource src = synth_source(4, 3, 200);
  WindowOptions a, b;
  a.seed = b.seed = 5;
  auto i1 = WindowIndex::build(src, a), i2 = WindowIndex::build(src, b);
  ASSERT_EQ(i1.val_size(), i2.val_size());
  for (std::int64_t i = 0; i < i1.val_size(); i += 7) EXPECT_EQ(i1.val(i).start, i2.val(i).start);
  std::set<int> starts;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    WindowOptions c;
    c.seed = seed;
    starts.insert(WindowIndex::build(src, c).val(0).start);
  }
  EXPECT_GT(starts.size(), 1u);  // the seed moves the validation block
}

TEST(TrainPairs, NoPairsIsAClearError) {
  MemorySource src = synth_source(1, 2, 100);  // one retargeted body: nothing to pair
  try {
    WindowIndex::build(src, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "synthetic: no training pairs: need one motion_id (take 1) on at least two retargeted "
              "bodies, with at least 30 frames; found 6 sequences, 2 retargeted take-1");
  }
  MemorySource short_src = synth_source(3, 2, 20);  // shorter than the window
  try {
    WindowIndex::build(short_src, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("2 motions too short"), std::string::npos) << e.what();
  }
}

TEST(TrainPairs, NormalisationUsesTrainingBodiesOnly) {
  MemorySource src = synth_source(4, 2, 90);
  WindowIndex idx = WindowIndex::build(src, {});
  Normalisation n = fit_normalisation(src, idx);
  double h = 0;
  for (int b = 0; b < 4; ++b) h += src.bodies()[b].height_cm;
  EXPECT_NEAR(n.height_mean_cm, h / 4, 1e-9);
  EXPECT_GT(n.pressure_scale_kpa, 1.0);
  auto a = n.attributes(src.bodies()[1]);
  EXPECT_EQ(a[0], 1.0f);  // r1 is male
  EXPECT_NEAR(a[1], (src.bodies()[1].height_cm - n.height_mean_cm) / n.height_std_cm, 1e-5);
}

TEST(TrainPairs, CacheReturnsTheSameFramesWithinItsBudget) {
  MemorySource src = synth_source(2, 2, 60);
  const int cells = src.mat().cells();
  std::vector<float> direct(std::size_t(30) * cells), cached(direct.size());
  const double one_seq_mb = 60.0 * cells * 4 / (1024 * 1024);
  for (double budget : {0.0, one_seq_mb * 1.5, 100.0}) {
    SequenceCache cache(src, budget);
    for (int seq : {0, 1, 2, 0, 3}) {
      src.read(src.sequences()[seq].name, 17, 30, direct.data());
      cache.read(seq, 17, 30, cached.data());
      EXPECT_EQ(direct, cached);
      EXPECT_LE(cache.resident_mb(), budget + 1e-9);
    }
  }
}

// The options' rules live in the library (check_options), not in a front end:
// what the CLI's flags would refuse, a caller of train() is refused too.
TEST(TrainPairs, OptionRulesAreTheLibrarys) {
  const auto error_of = [](const TrainOptions& o) -> std::string {
    try {
      check_options(o);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  TrainOptions o = TrainOptions::from_preset("paper");
  EXPECT_EQ(error_of(o), "");
  o.resume = true;
  o.init = "other_model";
  EXPECT_EQ(error_of(o), "resume and init exclude each other");
  o = TrainOptions::from_preset("paper");
  o.contact_weight = 0.1;  // a weight without a head (the CLI sets both)
  EXPECT_EQ(error_of(o), "contact_weight: 0.1 trains a contact head, which model.contact leaves out");
  o.model.contact = true;  // a head on a window network
  EXPECT_EQ(error_of(o), "model: a contact head needs the frame architecture, found faithful");
  o = TrainOptions::from_preset("fast");
  o.epochs = 0;
  EXPECT_EQ(error_of(o), "epochs: 0 is not in [1, 1000000]");
  // Overrides: the architecture first, then the contact head exactly when contact_weight > 0.
  TrainOverrides v;
  v.arch = Arch::faithful;
  const TrainOptions window_net = TrainOptions::from_preset("fast", v);
  EXPECT_FALSE(window_net.model.contact);
  EXPECT_EQ(window_net.contact_weight, 0);
  EXPECT_EQ(window_net.model.window, kWindowFrames);
  v = TrainOverrides{};
  v.contact_weight = 0;
  EXPECT_FALSE(TrainOptions::from_preset("fast", v).model.contact);
  EXPECT_TRUE(TrainOptions::from_preset("fast").model.contact);
  EXPECT_EQ(error_of(TrainOptions::from_preset("fast", v)), "");
}
