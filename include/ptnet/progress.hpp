// ptnet/progress.hpp: the one shape in which long library jobs report what
// they do. The library never prints; the caller (the CLI) decides what to
// show: a counter line, a log line, or nothing.
//
//   options.progress = [](const ptnet::Progress& p) {
//     if (!p.line.empty()) std::cerr << p.line << "\n";                  // a finished step
//     else std::cerr << p.what << ": " << p.done << "/" << p.total << "\n"; // a count
//   };
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace ptnet {

struct Progress {
  std::string what;         // the job or its phase: "simulate", "evaluate", "train", "har"
  std::int64_t done = 0;    // units done so far (a count; 0 with a line)
  std::int64_t total = 0;   // units in all
  std::string unit;         // what is counted: "sequences", "pairs", "windows"
  int step = 0, steps = 0;  // an outer count where there is one (epoch 3 of 15), else 0
  std::string line;         // a finished step's log line ("[epoch 3/15] train ..."), or ""
};

using ProgressFn = std::function<void(const Progress&)>;

// A count: {what, done, total, unit}.
inline Progress progress_count(std::string what, std::int64_t done, std::int64_t total, std::string unit) {
  Progress p;
  p.what = std::move(what);
  p.done = done;
  p.total = total;
  p.unit = std::move(unit);
  return p;
}
// A log line of `what`.
inline Progress progress_line(std::string what, std::string line) {
  Progress p;
  p.what = std::move(what);
  p.line = std::move(line);
  return p;
}

}  // namespace ptnet
