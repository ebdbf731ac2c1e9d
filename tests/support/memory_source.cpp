// MemorySource (support/memory_source.hpp).
#include "support/memory_source.hpp"

#include <cstring>

#include "ptnet/error.hpp"

namespace ptnet {

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

}  // namespace ptnet
