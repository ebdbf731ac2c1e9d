// Fine-tuning on real recordings (paper 4.2): the fine-tuning set holds the
// training subjects only, marked for the training protocol, and trains as
// identity pairs since each recording is on one body.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/train.hpp"
#include "train/window_index.hpp"

namespace fs = std::filesystem;
using namespace ptnet;

namespace {

// Three subjects s1..s3, each with its own two recordings of 40 frames
// (one marked take 2), role "original" like imported recordings.
std::string write_real(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "real.h5").string();
  DatasetInfo info;
  info.mat = MatSpec{16, 8, 0.02};
  info.generator = "har_finetune_test";
  std::vector<BodySpec> bodies;
  for (int s = 1; s <= 3; ++s)
    bodies.push_back(BodySpec{"s" + std::to_string(s), Sex::female, 150.0 + 10 * s, 50.0 + 5 * s, "original"});
  DatasetWriter w(path, info, bodies, true);
  for (int s = 1; s <= 3; ++s)
    for (int take = 1; take <= 2; ++take) {
      SequenceMeta m;
      m.motion_id = "rec" + std::to_string(take) + "_s" + std::to_string(s);
      m.body_id = "s" + std::to_string(s);
      m.name = m.motion_id + "__" + m.body_id;
      m.performer = m.body_id;
      m.category = take == 1 ? "walking" : "rom";
      m.take = take;
      m.source = "test";
      PressureSequence seq(info.mat, 40, 30);
      for (int t = 0; t < 40; ++t) seq.at(t, t % 16, s) = float(s * 10 + take);
      w.add(m, seq);
    }
  w.commit();
  return path;
}

}  // namespace

TEST(HarFinetune, SetHoldsOnlyTheTrainingSubjectsReadyForTraining) {
  const fs::path dir = fs::temp_directory_path() / ("ptnet_har_finetune_set_" + std::to_string(::getpid()));
  const std::string real = write_real(dir), out = (dir / "finetune.h5").string();
  har::write_finetune_set(real, {"1", "s2"}, out, false);
  const Dataset d = Dataset::open(out);
  ASSERT_EQ(d.bodies().size(), 2u);
  EXPECT_EQ(d.bodies()[0].id, "s1");
  EXPECT_EQ(d.bodies()[1].id, "s2");
  EXPECT_EQ(d.bodies()[1].height_cm, 170);
  for (const auto& b : d.bodies()) EXPECT_EQ(b.role, "retargeted");
  ASSERT_EQ(d.sequences().size(), 4u);  // 2 subjects x 2 recordings; nothing of s3
  for (const auto& m : d.sequences()) {
    EXPECT_NE(m.body_id, "s3");
    EXPECT_EQ(m.take, 1);
  }
  EXPECT_EQ(d.read("rec2_s2__s2").at(5, 5, 2), 22.0f);  // the recording itself, unchanged
  EXPECT_THROW(har::write_finetune_set(real, {"1"}, out, false), Error);  // exists

  // Training: one body per recording gives no pairs, unless identity pairs.
  const auto source = open_dataset_source(out);
  try {
    WindowIndex::build(*source, {});
    FAIL() << "expected no training pairs";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no training pairs"), std::string::npos) << e.what();
  }
  WindowOptions wo;
  wo.identity_pairs = true;
  const WindowIndex index = WindowIndex::build(*source, wo);
  ASSERT_EQ(index.pairs().size(), 4u);  // one (a, a) pair per recording
  for (const Pair& p : index.pairs()) EXPECT_EQ(p.source, p.target);
  EXPECT_GT(index.train_size(), 0);
  fs::remove_all(dir);
}

TEST(HarFinetune, BadSubjectListsAreOneLineErrors) {
  const fs::path dir = fs::temp_directory_path() / ("ptnet_har_finetune_bad_" + std::to_string(::getpid()));
  const std::string real = write_real(dir), out = (dir / "finetune.h5").string();
  auto message = [&](const std::vector<std::string>& subjects) {
    try {
      har::write_finetune_set(real, subjects, out, true);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"9"}), real + ": no subject '9' (bodies: s1,s2,s3)");
  EXPECT_EQ(message({"1", "s1"}), real + ": subject s1 listed twice");
  EXPECT_EQ(message({}), real + ": no fine-tuning subjects given");
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(dir);
}
