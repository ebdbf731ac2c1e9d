// core/hash.hpp: the one non-cryptographic hash of ptnet, FNV-1a 64, behind
// every digest and name-derived seed (the weights digest in config.json, the
// training source digest, per-sequence sensor seeds, per-motion validation
// splits). Changing it changes recorded digests and simulated datasets.
//
//   ptnet::fnv1a("walk_01__b3")                     // one string -> 64 bits
//   ptnet::Fnv1a h;                                 // or piece by piece:
//   h.add(name).add_byte(0).add(data, bytes);       // "name\0" then raw bytes
//   h.hex()                                         // 16 lower-case hex digits
//
// Bytes are hashed in the order added; add(text) hashes the text's bytes
// only (no terminator: a caller that needs one between fields adds it).
// Two offset bases are in use: the standard one, and its first 19 decimal
// digits (kTruncatedBasis), with which the training source digest and the
// per-motion validation split were first written; they keep it, since a
// new value would make recorded model folders refuse to resume and move
// windows between training and validation.
//
// Private to the library (not installed): the stages include it as
// "core/hash.hpp".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace ptnet {

class Fnv1a {
 public:
  static constexpr std::uint64_t kOffsetBasis = 0xcbf29ce484222325ull;
  static constexpr std::uint64_t kTruncatedBasis = 1469598103934665603ull;  // 0x14650fb0739d0383
  static constexpr std::uint64_t kPrime = 0x100000001b3ull;

  explicit Fnv1a(std::uint64_t basis = kOffsetBasis) : h_(basis) {}
  Fnv1a& add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h_ = (h_ ^ p[i]) * kPrime;
    return *this;
  }
  Fnv1a& add(std::string_view text) { return add(text.data(), text.size()); }
  Fnv1a& add_byte(unsigned char b) { return add(&b, 1); }
  std::uint64_t value() const { return h_; }
  // The value as 16 lower-case hex digits.
  std::string hex() const;

 private:
  std::uint64_t h_;
};

// FNV-1a 64 of a text's bytes.
inline std::uint64_t fnv1a(std::string_view text, std::uint64_t basis = Fnv1a::kOffsetBasis) {
  return Fnv1a(basis).add(text).value();
}

}  // namespace ptnet
