// Training on the synthetic moving-blob data: the validation loss falls by
// at least half from the first epoch (the paper's network); the fast
// preset's per-frame network beats its aligned starting point (body scale) and copying, on the
// validation windows and on a held-out body; resume reaches the same weights as an
// uninterrupted run; a NaN loss stops with a clear error; the output folder
// is never clobbered without --force.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>

#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/model.hpp"
#include "ptnet/transfer.hpp"
#include "support/memory_source.hpp"
#include "train/source.hpp"
#include "train_synthetic.hpp"
#include "train/window_index.hpp"

using namespace ptnet;
using namespace ptnet::testing;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("ptnet_train_learn_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p;
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p);
  return {std::istreambuf_iterator<char>(f), {}};
}

}  // namespace

TEST(TrainLearn, FastPresetArchitectureBeatsBodyScaleOnAHeldOutBody) {
  // The fast preset's network (per-frame conditional U-Net on body-scale
  // aligned input) starts as the aligned source (zero-initialised correction).
  // Trained on the retargeted bodies, it must beat that starting point (the
  // body-scale baseline) and copying by a margin on the validation windows,
  // and on a body it never saw: every retargeted body -> the original body,
  // on the seen motions and on the unseen (take-2) motion, in RMSE and, with
  // its contact head, in binary R^2.
  const TrainOptions fast = TrainOptions::from_preset("fast");
  ASSERT_EQ(fast.model.arch, Arch::frame);
  ASSERT_EQ(fast.model.align, Align::zoom);
  MemorySource src = synth_source(6, 3, 120);
  fs::path dir = temp_dir("frame");
  TrainOptions o = synth_options(8, Arch::frame, Align::zoom);
  o.model.window = fast.model.window;
  ASSERT_TRUE(fast.model.contact);
  o.model.contact = fast.model.contact;
  o.contact_weight = fast.contact_weight;
  o.samples_per_epoch = 1024;
  o.val_samples = 512;
  TrainResult r = train(src, dir.string(), o);
  const ModelDir md = read_model_dir(dir.string());
  const double model = md.metrics["val_rmse_kpa"].get<double>();
  EXPECT_LT(model, 0.7 * md.metrics["val_rmse_zoom_kpa"].get<double>());
  EXPECT_LT(model, 0.7 * md.metrics["val_rmse_copy_kpa"].get<double>());
  EXPECT_EQ(r.warning, "") << "a model that learned is no better than a baseline?";
  EXPECT_GE(r.epochs_run, 8);

  Transfer transfer(dir.string());
  const BodySpec& held_out = src.body("orig");
  for (int take : {1, 2}) {
    double err_model = 0, err_scale = 0, r2_model = 0, r2_scale = 0;
    int n = 0;
    for (const auto& meta : src.sequences()) {
      if (meta.body_id == "orig" || meta.take != take) continue;
      const BodySpec& from = src.body(meta.body_id);
      const PressureSequence in = src.read_all(meta.name);
      const PressureSequence truth = src.read_all(meta.motion_id + "__orig");
      const PressureSequence out = transfer.run(in, from, held_out);
      const PressureSequence scaled = body_scale_baseline(in, from, held_out);
      err_model += rmse(out.kpa.data(), truth.kpa.data(), truth.kpa.size());
      err_scale += rmse(scaled.kpa.data(), truth.kpa.data(), truth.kpa.size());
      r2_model += binary_r2(out.kpa.data(), truth.kpa.data(), truth.kpa.size(), kContactKpa);
      r2_scale += binary_r2(scaled.kpa.data(), truth.kpa.data(), truth.kpa.size(), kContactKpa);
      ++n;
    }
    ASSERT_GT(n, 0);
    EXPECT_LT(err_model, 0.75 * err_scale) << "take " << take;
    // Mean binary R^2 (measured: 0.98 / 0.96 against body scale's 0.48).
    EXPECT_GT(r2_model / n, r2_scale / n + 0.25) << "take " << take;
  }
  fs::remove_all(dir);
}

TEST(TrainLearn, MirrorAveragingIsKeptOnlyWhereValidationSaysSo) {
  // TrainOptions::mirror trains on mirrored windows too, then measures the
  // validation RMSE with and without mirror averaging and records the choice
  // in config.json (architecture.mirror) and the options.
  MemorySource src = synth_source(4, 2, 90);
  fs::path dir = temp_dir("mirror");
  TrainOptions o = synth_options(2, Arch::frame, Align::zoom);
  o.model.window = 1;
  o.mirror = true;
  std::vector<std::string> lines;
  o.progress = [&](const Progress& p) {
    if (!p.line.empty()) lines.push_back(p.line);
  };
  train(src, dir.string(), o);
  double plain = 0, averaged = 0;
  std::string verdict;
  for (const auto& l : lines) {
    char word[16] = {};
    if (std::sscanf(l.c_str(), "train: mirror averaging: val RMSE %lf -> %lf kPa, %15s", &plain, &averaged, word) == 3)
      verdict = word;
  }
  ASSERT_FALSE(verdict.empty()) << "no mirror line in the log";
  ASSERT_GT(plain, 0);
  const ModelDir md = read_model_dir(dir.string());
  EXPECT_EQ(md.model.mirror, averaged < plain);
  EXPECT_EQ(verdict, averaged < plain ? "kept" : "not");
  EXPECT_TRUE(md.options["mirror"].get<bool>());
  // The recorded validation RMSE is the one of the chosen inference.
  EXPECT_NEAR(md.metrics["val_rmse_kpa"].get<double>(), std::min(plain, averaged), 1e-3);
  fs::remove_all(dir);
}

TEST(TrainLearn, ValidationLossHalvesFromTheFirstEpoch) {
  MemorySource src = synth_source(6, 3, 120);
  fs::path dir = temp_dir("learn");
  TrainOptions o = synth_options(8);
  TrainResult r = train(src, dir.string(), o);
  EXPECT_EQ(r.epochs_run, 8);
  EXPECT_LE(r.best_val_loss, 0.5 * r.first_val_loss)
      << "first " << r.first_val_loss << " best " << r.best_val_loss;
  // The model folder: config.json, model.pt, checkpoint.pt, history.csv (header + 8 rows).
  for (const char* f : {"config.json", "model.pt", "checkpoint.pt", "history.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string history = read_file(dir / "history.csv");
  EXPECT_EQ(std::count(history.begin(), history.end(), '\n'), 9);
  EXPECT_EQ(history.rfind("epoch,train_loss,val_loss,lr,seconds\n", 0), 0u);
  ModelDir md = read_model_dir(dir.string());
  EXPECT_EQ(md.model.rows, kSynthRows);
  EXPECT_EQ(md.data["digest"], source_digest(src));
  EXPECT_EQ(md.metrics["best_epoch"], r.best_epoch);
  // Final metrics: the model and both naive baselines on the validation windows (kPa).
  EXPECT_GT(md.metrics["val_rmse_kpa"].get<double>(), 0);
  EXPECT_LT(md.metrics["val_rmse_kpa"].get<double>(), md.metrics["val_rmse_copy_kpa"].get<double>());
  EXPECT_GT(md.metrics["val_rmse_weight_scale_kpa"].get<double>(), 0);
  // No clobbering without force.
  try {
    train(src, dir.string(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              dir.string() + ": exists; pass force to overwrite or resume to continue");
    EXPECT_EQ(e.kind(), ErrorKind::exists);
  }
  fs::remove_all(dir);
}

TEST(TrainLearn, ResumeEqualsUninterrupted) {
  MemorySource src = synth_source(4, 2, 100);
  fs::path a = temp_dir("full"), b = temp_dir("resumed");
  TrainOptions o = synth_options(4);
  o.samples_per_epoch = 96;
  train(src, a.string(), o);
  TrainOptions first = o;
  first.epochs = 2;
  train(src, b.string(), first);
  TrainOptions rest = o;
  rest.resume = true;
  TrainResult r = train(src, b.string(), rest);
  EXPECT_EQ(r.epochs_run, 4);
  EXPECT_EQ(read_file(a / "history.csv").substr(0, 60), read_file(b / "history.csv").substr(0, 60));
  ModelConfig c = read_model_dir(a.string()).model;
  PressureTransferNet na(c), nb(c);
  load_weights(na, (a / "model.pt").string());
  load_weights(nb, (b / "model.pt").string());
  for (const auto& p : na->named_parameters())
    EXPECT_TRUE(torch::equal(p.value(), nb->named_parameters()[p.key()])) << p.key();
  for (const auto& p : na->named_buffers())
    EXPECT_TRUE(torch::equal(p.value(), nb->named_buffers()[p.key()])) << p.key();
  // Resuming on other data is refused.
  MemorySource other = synth_source(4, 2, 101);
  try {
    train(other, b.string(), rest);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("was trained on other data"), std::string::npos) << e.what();
  }
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(TrainLearn, NanLossStopsWithAClearErrorAndKeepsTheCheckpoint) {
  MemorySource clean = synth_source(3, 2, 90);
  MemorySource src(clean.mat(), 30, "nan-data");
  for (const auto& b : clean.bodies()) src.add_body(b);
  for (const auto& m : clean.sequences()) {
    PressureSequence s = clean.read_all(m.name);
    for (int t = 0; t < s.frames(); ++t) s.at(t, 3, 3) = std::numeric_limits<float>::quiet_NaN();
    src.add_sequence(m, s);
  }
  fs::path dir = temp_dir("nan");
  try {
    train(src, dir.string(), synth_options(2));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("training diverged: loss is NaN at epoch 1, batch 1", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("checkpoint.pt"), std::string::npos);
  }
  EXPECT_TRUE(fs::exists(dir / "checkpoint.pt"));
  fs::remove_all(dir);
}

TEST(TrainLearn, InitFromAModelForAnotherMatIsAClearError) {
  fs::path base = temp_dir("init_base"), tuned = temp_dir("init_tuned");
  MemorySource src = synth_source(3, 2, 90);
  train(src, base.string(), synth_options(1));
  // Fine-tuning on the same mat works and keeps the normalisation.
  TrainOptions o = synth_options(1);
  o.init = base.string();
  train(src, tuned.string(), o);
  EXPECT_EQ(read_model_dir(tuned.string()).norm.pressure_scale_kpa,
            read_model_dir(base.string()).norm.pressure_scale_kpa);
  // Another mat size is refused.
  MemorySource wide = synth_source(3, 2, 90, MatSpec{16, 10, 0.02});
  o.force = true;
  try {
    train(wide, tuned.string(), o);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "synthetic: mat is 16 x 10, the model was built for 16 x 8");
  }
  fs::remove_all(base);
  fs::remove_all(tuned);
}
