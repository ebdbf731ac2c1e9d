// Weights as a PyTorch state dict (ptnet/state_dict.hpp) without Python:
// export then import gives a model folder that transfers exactly as the
// original; bad files and folders are one-line errors. (The PyTorch side:
// python/tests/test_torch.py, test_roundtrip.py.)
#include <gtest/gtest.h>
#include <torch/csrc/jit/serialization/pickle.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "ptnet/error.hpp"
#include "ptnet/model_config.hpp"
#include "ptnet/state_dict.hpp"
#include "ptnet/transfer.hpp"
#include "data_test_util.hpp"
#include "support/memory_source.hpp"
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
    EXPECT_NE(error_of([&] {
                import_state_dict(pt, (dir_ / model).string(), back, false);
              }).find(": exists; pass force to overwrite"),
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

TEST_F(StateDictTest, ExportHoldsNoGlobalTheWeightsOnlyUnpicklerRefuses) {
  // PyTorch's torch.load(weights_only=True) builds only tensors, storages,
  // dicts and numbers; torch::pickle_save's torch.jit._pickle.restore_type_tag
  // made it refuse ptnet's own export (python/tests/test_torch_load.py loads it).
  for (const char* model : {"faithful", "frame"}) {
    SCOPED_TRACE(model);
    const std::string pt = (dir_ / (std::string(model) + "_plain.pt")).string();
    export_state_dict((dir_ / model).string(), pt, /*force=*/true);
    std::ifstream in(pt, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(bytes.find("_rebuild_tensor_v2"), std::string::npos);  // data.pkl is stored, not deflated
    EXPECT_EQ(bytes.find("torch.jit"), std::string::npos);
    EXPECT_EQ(bytes.find("restore_type_tag"), std::string::npos);
  }
}

TEST_F(StateDictTest, ImportRefusesValuesNoTrainingGives) {
  struct Case {
    const char* model;
    const char* tensor;
    double value;
    const char* says;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Case& c : {Case{"faithful", "bn2.running_mean", nan, "has non-finite values"},
                        Case{"faithful", "dbn3.running_var", -0.25, "has a negative BatchNorm variance"},
                        Case{"faithful", "bn1.num_batches_tracked", -1, "is negative"},
                        Case{"frame", "frame.norm0.running_var", -1, "has a negative BatchNorm variance"},
                        Case{"frame", "contact_floor", 1e30, "is 1e+30, expected a value in [0, 1]"},
                        Case{"frame", "contact_floor", -0.5, "expected a value in [0, 1]"}}) {
    SCOPED_TRACE(c.tensor);
    const std::string pt = (dir_ / (std::string(c.model) + "_values.pt")).string();
    export_state_dict((dir_ / c.model).string(), pt, /*force=*/true);
    std::ifstream in(pt, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto dict = torch::jit::pickle_load(bytes).toGenericDict();
    dict.at(c.tensor).toTensor().fill_(c.value);
    const std::vector<char> bad = torch::jit::pickle_save(dict);  // the tagged form: import reads it too
    const std::string bad_path = (dir_ / "bad_values.pt").string();
    std::ofstream(bad_path, std::ios::binary).write(bad.data(), std::streamsize(bad.size()));
    const std::string out = (dir_ / "bad_values").string();
    const std::string e = error_of([&] { import_state_dict(bad_path, (dir_ / c.model).string(), out, true); });
    EXPECT_EQ(e.rfind(bad_path + ": tensor \"" + c.tensor + "\" ", 0), 0u) << e;
    EXPECT_NE(e.find(c.says), std::string::npos) << e;
    EXPECT_FALSE(fs::exists(fs::path(out) / "model.pt"));
  }
}

}  // namespace
