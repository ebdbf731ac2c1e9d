// Weights as a PyTorch state dict (ptnet/state_dict.hpp) without Python:
// export then import gives a model folder that transfers exactly as the
// original; bad files and folders are one-line errors. (The PyTorch side:
// python/tests/test_torch.py, test_roundtrip.py.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/state_dict.hpp"
#include "ptnet/transfer.hpp"
#include "data_test_util.hpp"
#include "train_synthetic.hpp"

using namespace ptnet;
using namespace ptnet::testing;
using ptnet::testing_util::error_of;
namespace fs = std::filesystem;

namespace {

class StateDictTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp_ = new testing_util::TempDir("state_dict_test");
    dir_ = temp_->path;
    MemorySource src = synth_source(3, 2, 90);
    train(src, (dir_ / "faithful").string(), synth_options(1));
    train(src, (dir_ / "frame").string(), synth_options(1, Arch::frame, Align::zoom));
  }
  static void TearDownTestSuite() { delete temp_; }  // removes the folder
  static inline testing_util::TempDir* temp_ = nullptr;
  static inline fs::path dir_;
};

TEST_F(StateDictTest, ExportThenImportTransfersTheSame) {
  for (const char* model : {"faithful", "frame"}) {
    SCOPED_TRACE(model);
    const std::string pt = (dir_ / (std::string(model) + ".pt")).string();
    const std::string back = (dir_ / (std::string(model) + "_back")).string();
    export_state_dict((dir_ / model).string(), pt, /*force=*/false);
    import_state_dict(pt, (dir_ / model).string(), back, /*force=*/false);
    const BodySpec a{"a", Sex::female, 160, 55}, b{"b", Sex::male, 185, 90};
    const PressureSequence in = synth_sequence(1, a, 40, MatSpec{kSynthRows, kSynthCols, 0.02});
    const PressureSequence x = Transfer((dir_ / model).string()).run(in, a, b);
    const PressureSequence y = Transfer(back).run(in, a, b);
    EXPECT_EQ(x.kpa, y.kpa);
    const ModelDir d = read_model_dir(back);
    EXPECT_EQ(d.metrics.at("imported_from"), pt);
    EXPECT_FALSE(recorded_digest(d, "model.pt").empty());
    EXPECT_FALSE(fs::exists(fs::path(back) / "checkpoint.pt"));
    // Refuses to overwrite either output without force.
    EXPECT_NE(error_of([&] { export_state_dict((dir_ / model).string(), pt, false); }).find(pt), std::string::npos);
    EXPECT_NE(error_of([&] { import_state_dict(pt, (dir_ / model).string(), back, false); }).find("--force"),
              std::string::npos);
  }
}

TEST_F(StateDictTest, WrongArchitectureOrFileIsOneLine) {
  const std::string pt = (dir_ / "faithful_wrong.pt").string();
  export_state_dict((dir_ / "faithful").string(), pt, /*force=*/true);
  const std::string out = (dir_ / "wrong").string();
  const std::string e1 = error_of([&] { import_state_dict(pt, (dir_ / "frame").string(), out, false); });
  EXPECT_EQ(e1.rfind(pt + ": missing tensor \"frame.conv0.weight\"", 0), 0u) << e1;
  EXPECT_FALSE(fs::exists(fs::path(out) / "model.pt"));

  const std::string junk = (dir_ / "junk.pt").string();
  std::ofstream(junk) << "not a zip";
  const std::string e2 = error_of([&] { import_state_dict(junk, (dir_ / "faithful").string(), out, false); });
  EXPECT_EQ(e2.rfind(junk + ":", 0), 0u) << e2;
  EXPECT_EQ(e2.find('\n'), std::string::npos);

  const std::string none = (dir_ / "none.pt").string();
  EXPECT_NE(error_of([&] { import_state_dict(none, (dir_ / "faithful").string(), out, false); }).find("no such file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { export_state_dict((dir_ / "missing").string(), none, false); }).find("missing"),
            std::string::npos);
}

}  // namespace
