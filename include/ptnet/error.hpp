// ptnet/error.hpp: the project's one error type.
//
//   throw ptnet::Error::at("walk.bvh", 42, "CHANNELS", "OFFSET");
//   // what(): "walk.bvh:42: expected CHANNELS, found OFFSET"
//
// Every failure a user can cause (bad file, bad argument, impossible
// attribute) is a ptnet::Error whose what() is one line naming the file and
// the problem. main() prints it on stderr and exits with status 1.
#pragma once

#include <stdexcept>
#include <string>

namespace ptnet {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}

  // "FILE:LINE: expected X, found Y" (the parser style).
  static Error at(const std::string& file, long line, const std::string& expected,
                  const std::string& found) {
    return Error(file + ":" + std::to_string(line) + ": expected " + expected + ", found " +
                 found);
  }
  // "FILE: PROBLEM" (whole-file problems: missing, unreadable, wrong format).
  static Error in(const std::string& file, const std::string& problem) {
    return Error(file + ": " + problem);
  }
};

}  // namespace ptnet
