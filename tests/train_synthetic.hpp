// A small synthetic pressure dataset for model/train tests: each "motion" is
// a blob moving along the mat; its radius grows with the body's height, its
// peak pressure with weight / area, and male bodies get a second (lateral)
// blob. So a network must use the attributes to transfer between bodies.
#pragma once

#include <cmath>
#include <string>

#include "ptnet/data.hpp"
#include "ptnet/train.hpp"
#include "support/memory_source.hpp"

namespace ptnet::testing {

inline constexpr int kSynthRows = 16;  // small mat for fast tests
inline constexpr int kSynthCols = 8;

// One frame-sequence of motion `m` on `body`: [frames, 16, 8] kPa.
inline PressureSequence synth_sequence(int motion, const BodySpec& body, int frames, MatSpec mat) {
  PressureSequence s(mat, frames, 30);
  const double radius = 1.0 + 2.0 * (body.height_cm - 140) / 80;     // cells
  const double peak = body.weight_kg / (radius * radius) * 1.5;        // kPa
  const double speed = 0.05 + 0.02 * motion, phase = 0.9 * motion;
  for (int t = 0; t < frames; ++t) {
    const double rc = (mat.rows - 1) * (0.5 + 0.35 * std::sin(speed * t + phase));
    const double cc = (mat.cols - 1) * (0.5 + 0.2 * std::cos(0.7 * speed * t + phase));
    for (int r = 0; r < mat.rows; ++r)
      for (int c = 0; c < mat.cols; ++c) {
        double d2 = (r - rc) * (r - rc) + (c - cc) * (c - cc);
        double v = peak * std::exp(-d2 / (2 * radius * radius));
        if (body.sex == Sex::male) {
          double c2 = cc + 2.5 > mat.cols - 1 ? cc - 2.5 : cc + 2.5;
          double e2 = (r - rc) * (r - rc) + (c - c2) * (c - c2);
          v += 0.5 * peak * std::exp(-e2 / (2 * radius * radius));
        }
        s.at(t, r, c) = v > 0.5 ? float(v) : 0.0f;  // activation threshold
      }
  }
  return s;
}

// `retargeted` training bodies (alternating sex) + 1 original body;
// `motions` take-1 motions and one take-2 motion on every body.
inline MemorySource synth_source(int retargeted = 6, int motions = 3, int frames = 120,
                                 MatSpec mat = MatSpec{kSynthRows, kSynthCols, 0.02}) {
  MemorySource src(mat, 30, "synthetic");
  for (int b = 0; b <= retargeted; ++b) {
    BodySpec body;
    body.id = b < retargeted ? "r" + std::to_string(b) : "orig";
    body.sex = b % 2 ? Sex::male : Sex::female;
    body.height_cm = 150 + 37 * ((b * 7) % 6) / 5.0 + (b % 2) * 8;
    body.weight_kg = 50 + 40 * ((b * 5) % 6) / 5.0;
    body.role = b < retargeted ? "retargeted" : "original";
    src.add_body(body);
  }
  for (int m = 0; m <= motions; ++m)
    for (const auto& body : std::vector<BodySpec>(src.bodies())) {
      SequenceMeta meta;
      meta.motion_id = "m" + std::to_string(m);
      meta.take = m < motions ? 1 : 2;
      meta.body_id = body.id;
      meta.name = meta.motion_id + "__" + body.id;
      meta.category = "walking";
      meta.performer = "P1";
      src.add_sequence(meta, synth_sequence(m, body, frames, mat));
    }
  return src;
}

// `src` written as a dataset file (for the CLI tests).
inline void write_source(const MemorySource& src, const std::string& path) {
  DatasetInfo info;
  info.mat = src.mat();
  info.generator = "test";
  DatasetWriter w(path, info, src.bodies(), false);
  for (const auto& m : src.sequences()) w.add(m, src.read_all(m.name));
  w.commit();
}

// Options for a few-second training run on the synthetic data.
// The paper's network (faithful, no alignment) unless told otherwise.
inline TrainOptions synth_options(int epochs = 6, Arch arch = Arch::faithful, Align align = Align::none) {
  TrainOptions o = TrainOptions::from_preset("fast");
  o.set_arch(arch);  // a window network: 30 frames, no contact head
  o.model.align = align;
  o.model.channels = {4, 8, 8};
  o.model.hidden = 32;
  o.model.latent = 32;
  o.epochs = epochs;
  o.batch = 16;
  o.lr = 3e-3;
  o.lr_halve_every = 4;
  o.patience = 50;
  o.stride = 2;
  o.samples_per_epoch = 256;
  o.val_samples = 128;
  o.threads = 1;
  return o;
}

}  // namespace ptnet::testing
