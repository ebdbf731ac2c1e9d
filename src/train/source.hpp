// train/source.hpp (private to the train stage; tests include it as
// "train/source.hpp"): what train() asks of a PressureSource beside
// ptnet/train.hpp: its digest (recorded in config.json, checked on resume)
// and the training protocol's filter.
#pragma once

#include <string>

#include "ptnet/train.hpp"

namespace ptnet {

// FNV-1a 64 digest (16 hex digits) of the source's metadata: mat, bodies and
// each sequence's name, body, motion, take and frame count.
std::string source_digest(const PressureSource& source);

// True for what the paper trains on: role "retargeted" and take 1.
bool is_training_sequence(const BodySpec& body, const SequenceMeta& meta);

}  // namespace ptnet
