// support/memory_source.hpp (test support, not the library): a training
// source whose sequences are held in memory.
//
//   ptnet::MemorySource src(ptnet::MatSpec{16, 8, 0.02}, /*fps=*/30);
//   src.add_body({"b1", ptnet::Sex::female, 160, 55, "retargeted"});
//   src.add_sequence(meta, sequence);          // meta.frames set from the data
//   ptnet::train(src, "model/", options);
//
// Dimension legend: T frames, H x W mat cells; sequences are [T, H, W] kPa.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ptnet/train.hpp"

namespace ptnet {

class MemorySource : public PressureSource {
 public:
  explicit MemorySource(MatSpec mat = {}, double fps = 30, std::string name = "memory");
  void add_body(const BodySpec& body);
  void add_sequence(SequenceMeta meta, PressureSequence sequence);  // meta.frames set from data

  std::string path() const override { return name_; }
  MatSpec mat() const override { return mat_; }
  double fps() const override { return fps_; }
  const std::vector<BodySpec>& bodies() const override { return bodies_; }
  const std::vector<SequenceMeta>& sequences() const override { return metas_; }
  void read(const std::string& name, int start, int count, float* out) const override;

 private:
  MatSpec mat_;
  double fps_;
  std::string name_;
  std::vector<BodySpec> bodies_;
  std::vector<SequenceMeta> metas_;
  std::map<std::string, PressureSequence> data_;
};

}  // namespace ptnet
