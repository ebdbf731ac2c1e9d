// Pressure sources (memory), digest, the training protocol filter.
#include <cstring>

#include "ptnet/error.hpp"
#include "ptnet/hash.hpp"
#include "ptnet/train.hpp"

namespace ptnet {

const BodySpec& PressureSource::body(const std::string& id) const {
  for (const auto& b : bodies())
    if (b.id == id) return b;
  throw Error::in(path(), "no body \"" + id + "\" in the bodies table");
}

const SequenceMeta& PressureSource::sequence(const std::string& name) const {
  for (const auto& s : sequences())
    if (s.name == name) return s;
  throw Error::in(path(), "no sequence \"" + name + "\"");
}

PressureSequence PressureSource::read_all(const std::string& name) const {
  const SequenceMeta& meta = sequence(name);
  PressureSequence seq(mat(), meta.frames, fps());
  if (meta.frames > 0) read(name, 0, meta.frames, seq.kpa.data());
  return seq;
}

MemorySource::MemorySource(MatSpec mat, double fps, std::string name)
    : mat_(mat), fps_(fps), name_(std::move(name)) {}

void MemorySource::add_body(const BodySpec& body) { bodies_.push_back(body); }

void MemorySource::add_sequence(SequenceMeta meta, PressureSequence sequence) {
  if (!(sequence.mat.rows == mat_.rows && sequence.mat.cols == mat_.cols))
    throw Error::in(name_, "sequence " + meta.name + " has another mat size");
  body(meta.body_id);  // must exist
  if (data_.count(meta.name)) throw Error::in(name_, "duplicate sequence " + meta.name);
  meta.frames = sequence.frames();
  data_[meta.name] = std::move(sequence);
  metas_.push_back(std::move(meta));
}

void MemorySource::read(const std::string& name, int start, int count, float* out) const {
  auto it = data_.find(name);
  if (it == data_.end()) throw Error::in(name_, "no sequence \"" + name + "\"");
  if (start < 0 || count < 0 || start + count > it->second.frames())
    throw Error::in(name_, name + ": frames " + std::to_string(start) + "+" + std::to_string(count) +
                               " outside 0-" + std::to_string(it->second.frames()));
  std::memcpy(out, it->second.frame(start), sizeof(float) * std::size_t(count) * mat_.cells());
}

std::string source_digest(const PressureSource& source) {
  Fnv1a h(Fnv1a::kTruncatedBasis);
  const auto mix = [&](const std::string& s) { h.add(s).add_byte(0xff); };  // 0xff ends each field
  const MatSpec m = source.mat();
  mix(std::to_string(m.rows) + "x" + std::to_string(m.cols) + "@" + std::to_string(m.pitch_m));
  for (const auto& b : source.bodies())
    mix(b.id + "," + std::string(b.sex == Sex::male ? "male" : "female") + "," + std::to_string(b.height_cm) + "," +
        std::to_string(b.weight_kg) + "," + b.role);
  for (const auto& s : source.sequences())
    mix(s.name + "," + s.body_id + "," + s.motion_id + "," + std::to_string(s.take) + "," +
        std::to_string(s.frames));
  return h.hex();
}

bool is_training_sequence(const BodySpec& body, const SequenceMeta& meta) {
  return body.role == "retargeted" && meta.take == 1;
}

}  // namespace ptnet
