// ptnet validate-har end to end: bad input gives one line on stderr and
// exit status 1 before any work is done.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "ptnet/data.hpp"
#include "ptnet/model_config.hpp"

namespace fs = std::filesystem;
using namespace ptnet;

namespace {

struct Outcome {
  int status;
  std::string err;
};

Outcome run(const std::string& args) {
  const fs::path err = fs::temp_directory_path() / ("ptnet_har_smoke_" + std::to_string(::getpid()));
  const std::string cmd = std::string(PTNET_BINARY) + " " + args + " 2>" + err.string() + " >/dev/null";
  const int rc = std::system(cmd.c_str());
  std::ifstream f(err);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  fs::remove(err);
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, text};
}

// A 3-subject dataset of 40-frame sequences and a model folder whose
// config.json says 64 x 32 (no weights are needed to reject it).
struct Fixture {
  fs::path dir = fs::temp_directory_path() /
                 (std::string("ptnet_har_smoke_") +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::string data, model;
  Fixture() {
    fs::remove_all(dir);
    fs::create_directories(dir / "model");
    data = (dir / "real.h5").string();
    model = (dir / "model").string();
    DatasetInfo info;
    info.generator = "har_smoke_test";
    std::vector<BodySpec> bodies;
    for (int s = 1; s <= 3; ++s)
      bodies.push_back(BodySpec{"s" + std::to_string(s), Sex::female, 165, 60, "original"});
    DatasetWriter w(data, info, bodies, true);
    for (int s = 1; s <= 3; ++s) {
      SequenceMeta m;
      m.motion_id = "m" + std::to_string(s);
      m.body_id = "s" + std::to_string(s);
      m.name = m.motion_id + "__" + m.body_id;
      m.performer = "P1";
      m.category = "walking";
      m.source = "test";
      PressureSequence seq(info.mat, 40, 30);
      seq.at(3, 10, 10) = 5;
      w.add(m, seq);
    }
    w.commit();
    ModelDir md;
    md.path = model;
    md.mat = MatSpec{64, 32, 0.02};
    md.model.rows = 64;
    md.model.cols = 32;
    std::ofstream(dir / "model" / "config.json") << to_json(md).dump(2);
  }
  ~Fixture() { fs::remove_all(dir); }
};

}  // namespace

TEST(HarSmoke, OverlappingSubjectsAreAnError) {
  Fixture f;
  const Outcome r = run("validate-har --real " + f.data + " --model " + f.model +
                    " --train-subjects 1,2 --test-subjects 2,3 --out " + (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + f.data +
                       ": subject s2 is in both the training and the test subjects\n");
}

TEST(HarSmoke, UnknownSubjectsAreAnError) {
  Fixture f;
  const Outcome r = run("validate-har --real " + f.data + " --model " + f.model +
                    " --train-subjects 1 --test-subjects 7 --out " + (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + f.data + ": no subject '7' (bodies: s1,s2,s3)\n");
}

TEST(HarSmoke, EmptySubjectListIsAnError) {
  Fixture f;
  const Outcome r = run("validate-har --real " + f.data + " --model " + f.model +
                    " --train-subjects , --test-subjects 3 --out " + (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: --train-subjects: no subjects given\n");
}

TEST(HarSmoke, NeedsAModelOrABaseline) {
  Fixture f;
  Outcome r = run("validate-har --real " + f.data + " --train-subjects 1,2 --test-subjects 3 --out " +
                  (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: validate-har: give --model (a trained model) or --baseline (copy | weight-ratio)\n");
  r = run("validate-har --real " + f.data + " --baseline shuffle --train-subjects 1,2 --test-subjects 3 --out " +
          (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: --baseline: expected copy or weight-ratio, found 'shuffle'\n");
}

TEST(HarSmoke, ModelOfAnotherMatSizeIsAnError) {
  Fixture f;
  const Outcome r = run("validate-har --real " + f.data + " --model " + f.model +
                    " --train-subjects 1,2 --test-subjects 3 --out " + (f.dir / "har").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "ptnet: error: " + f.model + "/config.json: model mat 64x32 (0.02 m) differs from " +
                       f.data + "'s 80x28 (0.02 m)\n");
}
