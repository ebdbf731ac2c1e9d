// app/command.hpp: how a subcommand joins the ptnet tool.
//
// Each app/cmd_<name>.cpp defines, in namespace ptnet::cli::cmd_<name> (the
// unity build compiles the commands together), `void setup(CLI::App& app)`
// that adds its subcommand (options bound to an options struct, a callback
// that runs it) and registers it with PTNET_COMMAND(order, setup). main()
// adds them in order.
// Naming: the struct holding a command's option values is `<Command>Cli`
// (TrainCli, ValidateHarCli); `*Options` names the library's option structs.
#pragma once

#include <CLI/CLI.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/progress.hpp"

namespace ptnet::cli {

using Setup = void (*)(CLI::App& app);

inline std::vector<std::pair<int, Setup>>& registry() {
  static std::vector<std::pair<int, Setup>> commands;
  return commands;
}

struct Registrar {
  Registrar(int order, Setup setup) { registry().emplace_back(order, setup); }
};

// ---- Option checks. Every numeric option has one: a range that NaN and Inf
// fall outside of, and messages with short numbers ("--lr: 0 is not in
// (0, 10]").

// A finite number in the library's `range` (ptnet::Range, error.hpp).
inline CLI::Validator in_range(const Range& range) {
  return CLI::Validator(
      [=](std::string& input) -> std::string {
        double v = 0;
        std::size_t used = 0;
        try {
          v = std::stod(input, &used);
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != input.size()) return escaped(input, 30) + " is not a number";
        if (!range.contains(v)) return escaped(input, 30) + " is not in " + range.text();
        return std::string();
      },
      "in " + range.text());
}
// An integer in the library's `range` (its bounds are integers).
inline CLI::Range int_range(const Range& range) {
  return CLI::Range(static_cast<long long>(range.lo), static_cast<long long>(range.hi));
}
// A finite number in [lo, hi] (lo_open: (lo, hi]).
inline CLI::Validator in_range(double lo, double hi, bool lo_open = false) { return in_range(Range{lo, hi, lo_open}); }
// A number > 0 (and <= hi).
inline CLI::Validator positive(double hi = 1e9) { return in_range(0, hi, /*lo_open=*/true); }
// Threads: 1 .. max_threads() (0 too when it means "the default").
inline CLI::Validator thread_count(bool zero_means_default) {
  return in_range(zero_means_default ? 0 : 1, max_threads());
}

// A TableFormat option ("mot" or "csv": parse_table_format, a usage error
// otherwise) that sets `format`.
inline CLI::Option* add_table_format(CLI::App* cmd, const std::string& flag, TableFormat& format,
                                     const std::string& help) {
  const auto problem = [](std::string& text) -> std::string {
    try {
      parse_table_format(text);
      return "";
    } catch (const Error& e) {
      return e.what();
    }
  };
  return cmd
      ->add_option_function<std::string>(flag, [&format](const std::string& text) { format = parse_table_format(text); },
                                         help)
      ->check(CLI::Validator(problem, "mot|csv"))
      ->default_str(table_format_name(format));
}

// A warning of the library's about a result (TrainResult::warning,
// EvaluationResult::warning) on stderr, "train: warning: model/: ...", with
// or without --quiet; nothing when `warning` is empty.
inline void print_warning(const std::string& command, const std::string& where, const std::string& warning) {
  if (!warning.empty()) std::cerr << command << ": warning: " << where << ": " << warning << "\n";
}

// Global flags every command may read (set by main before callbacks run).
struct Globals {
  bool quiet = false;  // no progress on stderr
};
Globals& globals();

// "3 min 05 s", "1 h 02 min", "12 s": a duration for progress lines.
inline std::string format_duration(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[48];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ld h %02ld min", s / 3600, s / 60 % 60);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%ld s", s);
  return buf;
}

// Progress of long work on stderr, the one printer of every command:
//   evaluate: 40/480 pairs, 2.3 pairs/s, ETA 3 min 12 s
// On a terminal one line rewritten in place (at most 10 times a second); in a
// log a line per 10 %; nothing with --quiet. A new `what`, or a count going
// back, starts a new clock (rate and ETA are measured from the first call).
// `extra` is appended. A `transient` line (training inside an epoch) shows on
// a terminal only and is erased when done == total: the caller then logs its
// own line.
inline void print_progress(const std::string& what, long long done, long long total, const std::string& unit,
                           const std::string& extra = "", bool transient = false) {
  using Clock = std::chrono::steady_clock;
  struct State {
    std::string what;
    long long first = 0, last = -1;
    Clock::time_point start, printed;
  };
  static State st;
  if (globals().quiet) return;
  static const bool tty = ::isatty(2) != 0;
  if (transient && !tty) return;
  const auto now = Clock::now();
  if (what != st.what || done < st.last) st = State{what, done, -1, now, now - std::chrono::seconds(1)};
  const long long previous = st.last;
  st.last = done;
  const bool end = done >= total;
  const bool due = tty ? std::chrono::duration<double>(now - st.printed).count() >= 0.1
                       : total > 0 && done * 10 / total > std::max(0LL, previous) * 10 / total;
  if (!end && !due) return;
  st.printed = now;
  if (end && transient) {
    std::cerr << "\r\033[K" << std::flush;
    return;
  }
  std::string line = what + ": " + std::to_string(done) + "/" + std::to_string(total) + " " + unit;
  const double secs = std::chrono::duration<double>(now - st.start).count();
  if (done > st.first && secs > 0.2) {
    const double rate = double(done - st.first) / secs;
    char buf[64];
    std::snprintf(buf, sizeof buf, rate >= 100 ? "%.0f" : "%.1f", rate);
    line += std::string(", ") + buf + " " + unit + "/s";
    if (!end) line += ", ETA " + format_duration(double(total - done) / rate);
  }
  if (!extra.empty()) line += ", " + extra;
  std::cerr << (tty ? "\r\033[K" : "") << line << (end || !tty ? "\n" : "") << std::flush;
}

// The one printer of the library's Progress for every command: a line as it
// is, a count through print_progress. Nothing with --quiet.
inline void print(const Progress& p) {
  if (globals().quiet) return;
  if (!p.line.empty()) std::cerr << p.line << "\n";
  else print_progress(p.what, p.done, p.total, p.unit);
}

// TrainOptions::progress for `ptnet train` and `ptnet demo`: the library's
// lines (setup, one per epoch, final metrics) on stderr; inside each epoch
// "epoch 3/15: 1024/4096 windows, 512 windows/s, ETA 6 s, run ETA 1 min 40 s"
// on a terminal (transient; a log keeps the one line per epoch). The run's
// ETA counts the remaining epochs at the last whole epoch's wall time
// (validation included); early stopping may end the run sooner. Nothing with
// --quiet.
inline ProgressFn train_progress() {
  struct EpochClock {
    int epoch = 0;
    std::chrono::steady_clock::time_point start;
    double last_epoch_s = 0;  // wall time of the last whole epoch
  };
  auto clock = std::make_shared<EpochClock>();
  return [clock](const Progress& p) {
    if (globals().quiet) return;
    if (!p.line.empty()) {
      std::cerr << p.line << std::endl;
      return;
    }
    const int epoch = p.step, epochs = p.steps;
    const std::int64_t done = p.done, total = p.total;
    const auto now = std::chrono::steady_clock::now();
    if (epoch != clock->epoch) {
      if (clock->epoch > 0) clock->last_epoch_s = std::chrono::duration<double>(now - clock->start).count();
      clock->epoch = epoch;
      clock->start = now;
    }
    const double in_epoch = std::chrono::duration<double>(now - clock->start).count();
    const double epoch_s = clock->last_epoch_s > 0 ? clock->last_epoch_s
                           : done > 0            ? in_epoch * double(total) / double(done)
                                                 : 0;
    std::string extra;
    if (epoch_s > 0 && epoch < epochs) {
      const double this_epoch_left = std::max(0.0, epoch_s - in_epoch);
      extra = "run ETA " + format_duration(this_epoch_left + epoch_s * double(epochs - epoch));
    }
    print_progress("epoch " + std::to_string(epoch) + "/" + std::to_string(epochs), done, total, p.unit, extra,
                   /*transient=*/true);
  };
}

}  // namespace ptnet::cli

#define PTNET_CONCAT_(a, b) a##b
#define PTNET_CONCAT(a, b) PTNET_CONCAT_(a, b)
#define PTNET_COMMAND(order, setup) \
  static const ::ptnet::cli::Registrar PTNET_CONCAT(ptnet_command_, __LINE__)(order, setup)
