// Pressure sources, their digest, the training protocol filter.

#include "train/source.hpp"

#include "core/hash.hpp"
#include "ptnet/error.hpp"
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
