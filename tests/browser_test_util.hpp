// browser_test_util.hpp: loading a report page in a real browser (Debian's
// chromium, headless, from file://) for the report tests. The pages carry an
// inline check script (viz.hpp html_page) that sets body[data-ok] once every
// image loaded and no error occurred; chromium's --dump-dom gives the DOM
// after the load event, and a second run saves a screenshot.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace ptnet::testing_browser {

namespace fs = std::filesystem;

// The chromium binary on PATH, or "" when it is not installed.
inline std::string find_chromium() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':'))
    for (const char* name : {"chromium", "chromium-browser"}) {
      const fs::path p = fs::path(dir) / name;
      if (::access(p.c_str(), X_OK) == 0) return p.string();
    }
  return "";
}

inline constexpr const char* kNoChromium =
    "chromium is not installed (scripts/install-deps.sh installs Debian's chromium): the report "
    "page was "
    "written but not loaded in a browser";

struct PageLoad {
  int status = -1;
  std::string dom;                   // the DOM after load (--dump-dom)
  std::string log;                   // chromium's stderr
  std::vector<std::string> console;  // console messages that are errors
  std::string ok, failures;          // body[data-ok], body[data-failures]
  int images = -1;                   // body[data-images]
};

// Runs chromium headless on `page` (a file) with a fresh profile in `scratch`;
// `extra` are more flags (--dump-dom, --screenshot=...).
inline ptnet::testing_cli::RunResult run_chromium(const std::string& chromium, const fs::path& page,
                                                  const fs::path& scratch,
                                                  const std::string& extra) {
  const fs::path profile = scratch.string() + ".profile";
  fs::remove_all(profile);
  fs::create_directories(profile);
  const fs::path out = scratch.string() + ".out", err = scratch.string() + ".err";
  const std::string cmd =
      "timeout 120 '" + chromium +
      "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
      " --disable-background-networking --disable-component-update --disable-sync"
      " --disable-dev-shm-usage --enable-logging=stderr --v=0 --user-data-dir='" +
      profile.string() + "' " + extra + " 'file://" + fs::absolute(page).string() + "' >'" +
      out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  ptnet::testing_cli::RunResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = ptnet::testing_cli::slurp(out);
  r.err = ptnet::testing_cli::slurp(err);
  fs::remove(out);
  fs::remove(err);
  fs::remove_all(profile);
  return r;
}

inline std::string body_attribute(const std::string& dom, const std::string& name) {
  std::smatch m;
  const std::regex body("<body[^>]*\\b" + name + "=\"([^\"]*)\"");
  return std::regex_search(dom, m, body) ? m[1].str() : "(absent)";
}

// Loads the page (DOM and console) and saves a 1280 x 2000 screenshot.
inline PageLoad load_page(const std::string& chromium, const fs::path& page,
                          const fs::path& screenshot) {
  const fs::path scratch =
      fs::temp_directory_path() / ("ptnet_browser_" + std::to_string(::getpid()));
  const auto dump = run_chromium(chromium, page, scratch, "--dump-dom --virtual-time-budget=10000");
  PageLoad p;
  p.status = dump.status;
  p.dom = dump.out;
  p.log = dump.err;
  std::istringstream lines(dump.err);
  std::string line;
  while (std::getline(lines, line))
    if (line.find(":CONSOLE") != std::string::npos || line.find("Uncaught") != std::string::npos)
      p.console.push_back(line);
  p.ok = body_attribute(p.dom, "data-ok");
  p.failures = body_attribute(p.dom, "data-failures");
  const std::string images = body_attribute(p.dom, "data-images");
  p.images = images == "(absent)" ? -1 : std::stoi(images);
  fs::remove(screenshot);
  run_chromium(
      chromium, page, scratch,
      "--screenshot='" + screenshot.string() + "' --window-size=1280,2000 --hide-scrollbars");
  return p;
}

// The text of every <td> with data-* attributes, keyed by "attr=value|attr=value|...".
inline std::map<std::string, std::string> data_cells(const std::string& dom,
                                                     const std::vector<std::string>& attrs) {
  std::string pattern = "<td[^>]*?";
  for (const auto& a : attrs) pattern += "\\s" + a + "=\"([^\"]*)\"";
  pattern += "[^>]*>([^<]*)</td>";
  const std::regex cell(pattern);
  std::map<std::string, std::string> out;
  for (auto it = std::sregex_iterator(dom.begin(), dom.end(), cell); it != std::sregex_iterator();
       ++it) {
    std::string key;
    for (std::size_t i = 0; i < attrs.size(); ++i) key += (i ? "|" : "") + (*it)[i + 1].str();
    out[key] = (*it)[attrs.size() + 1].str();
  }
  return out;
}

}  // namespace ptnet::testing_browser
