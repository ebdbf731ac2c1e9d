// data_test_util.hpp: fixtures shared by the data / viz / render tests.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "support/synthetic_walk.hpp"

namespace ptnet::testing_util {

// A fresh empty folder under the system temp dir, removed on destruction.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag) {
    static int counter = 0;
    path = std::filesystem::temp_directory_path() /
           ("ptnet_" + tag + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path)) names.push_back(e.path().filename().string());
    return names;
  }
};

// The message of the ptnet::Error that f throws, or "(no error)".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

inline std::vector<BodySpec> two_bodies() {
  return {BodySpec{"b1", Sex::female, 158, 52, "retargeted"},
          BodySpec{"b2", Sex::male, 186, 94, "original"}};
}

inline SequenceMeta meta_for(const std::string& motion, const std::string& body, int take = 1,
                             const std::string& category = "walking") {
  SequenceMeta m;
  m.name = motion + "__" + body;
  m.body_id = body;
  m.motion_id = motion;
  m.performer = "P1";
  m.category = category;
  m.take = take;
  m.source = "procedural:" + motion;
  return m;
}

// Writes a small dataset: motions {walk_a (frames_a), walk_b (frames_b)} on bodies b1, b2.
inline void write_small_dataset(const std::string& path, int frames_a = 70, int frames_b = 5,
                                bool force = false) {
  DatasetInfo info;
  info.generator = "ptnet test";
  info.config_json = R"({"seed": 7})";
  auto bodies = two_bodies();
  DatasetWriter w(path, info, bodies, force);
  unsigned long long seed = 1;
  for (const auto& [motion, frames] : {std::pair<std::string, int>{"walk_a", frames_a}, {"walk_b", frames_b}}) {
    for (const auto& b : bodies) {
      auto seq = synthetic_walk(info.mat, frames, info.fps, b.height_cm, b.weight_kg, seed++);
      w.add(meta_for(motion, b.id, motion == "walk_a" ? 1 : 2), seq);
    }
  }
  w.commit();
}

}  // namespace ptnet::testing_util
