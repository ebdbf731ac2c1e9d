// The real tool on C3D files: `ptnet info` on a file written by the test
// (the number format, writer, markers, frames, analog channels, plates,
// JSON), one line and exit 1 on a damaged one; `ptnet physics-bench` on
// ../shared/c3d/JA1Gait35.c3d with its own plates (skipped when absent).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_test_util.hpp"
#include "support/c3d_writer.hpp"

namespace {

namespace fs = std::filesystem;
using ptnet::testing_cli::run_ptnet;
using V = Eigen::Vector3d;

fs::path scratch_dir() {
  const fs::path d = fs::temp_directory_path() / ("ptnet_cli_c3d_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

ptnet::test::C3dSpec spec() {
  ptnet::test::C3dSpec s;
  s.format = ptnet::C3dFormat::mips;
  s.floats = false;
  s.rate_hz = 120;
  s.first_frame = 5;
  s.frames = 3;
  s.labels = {"A", "B"};
  for (int k = 0; k < 6; ++k) s.xyz.push_back(V(10 * k, 20, 30));
  s.per_frame = 2;
  for (int k = 0; k < 6; ++k) {
    s.analog_labels.push_back("F" + std::to_string(k + 1));
    s.analog_units.push_back(k < 3 ? "N" : "Nmm");
    s.analog_scale.push_back(1);
    s.analog_offset.push_back(0);
  }
  s.analog.assign(3 * 2 * 6, 0.0);
  ptnet::test::C3dPlateSpec p;
  p.type = 2;
  p.corners = {V(600, 900, 0), V(0, 900, 0), V(0, 0, 0), V(600, 0, 0)};
  p.channels = {1, 2, 3, 4, 5, 6};
  s.plates = {p};
  s.company = "Lab";
  s.software = "Writer 1";
  return s;
}

}  // namespace

TEST(CliC3d, InfoDescribesTheFileAndRefusesADamagedOneInOneLine) {
  const fs::path dir = scratch_dir();
  const std::string bytes = ptnet::test::write_c3d(spec()).bytes;
  std::ofstream(dir / "t.c3d", std::ios::binary) << bytes;
  auto r = run_ptnet("info '" + (dir / "t.c3d").string() + "'", dir / "run");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find(": C3D (MIPS, integer storage)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("written by        Lab, Writer 1"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("frames            3 from frame 5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("analog            6 channels at 240.0 Hz"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("plate 1           type 2, corners (m) (0.600, 0.900, 0.000)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("joints            not placed: "), std::string::npos) << r.out;  // A and B place no map
  r = run_ptnet("info --json '" + (dir / "t.c3d").string() + "'", dir / "run");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "c3d");
  EXPECT_EQ(j["number_format"], "MIPS");
  EXPECT_EQ(j["markers"], 2);
  EXPECT_EQ(j["marker_names"], (std::vector<std::string>{"A", "B"}));
  EXPECT_EQ(j["plates"][0]["channels"], (std::vector<std::string>{"F1", "F2", "F3", "F4", "F5", "F6"}));
  std::ofstream(dir / "cut.c3d", std::ios::binary) << bytes.substr(0, bytes.size() - 10);
  r = run_ptnet("info '" + (dir / "cut.c3d").string() + "'", dir / "run");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("(a truncated file?)"), std::string::npos) << r.err;
  // Before: a Latin-1 label ended `info --json` in nlohmann's type_error 316.
  ptnet::test::C3dSpec latin1 = spec();
  latin1.labels[0] = "caf\xe9";
  std::ofstream(dir / "l.c3d", std::ios::binary) << ptnet::test::write_c3d(latin1).bytes;
  r = run_ptnet("info --json '" + (dir / "l.c3d").string() + "'", dir / "run");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["marker_names"], (std::vector<std::string>{"caf\xc3\xa9", "B"}));
  fs::remove_all(dir);
}

TEST(CliC3d, InfoPrintsEverySharedFileAsTextAndJson) {
  // The text view is printed from the JSON one: a field of another type in
  // one (the up axis once an enum's number) failed only the text view.
  const std::string shared = std::string(PTNET_SOURCE_DIR) + "/../shared/c3d";
  if (!fs::exists(shared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  const fs::path dir = scratch_dir();
  int files = 0;
  for (const auto& e : fs::directory_iterator(shared)) {
    if (e.path().extension() != ".c3d") continue;
    ++files;
    for (const char* flag : {"", "--json "}) {
      const auto r = run_ptnet(std::string("info ") + flag + "'" + e.path().string() + "'", dir / "run");
      EXPECT_EQ(r.status, 0) << e.path() << " " << flag << r.err;
      EXPECT_TRUE(r.err.empty()) << r.err;
    }
  }
  EXPECT_GE(files, 4);
  const auto r = run_ptnet("info '" + shared + "/JA1Gait35.c3d'", dir / "run");
  EXPECT_NE(r.out.find(" landmarks), up z, stature (est.) "), std::string::npos) << r.out;
  fs::remove_all(dir);
}

TEST(CliC3d, PhysicsBenchTakesAC3dTrialWithItsOwnPlates) {
  const std::string shared = std::string(PTNET_SOURCE_DIR) + "/../shared/c3d";
  if (!fs::exists(shared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  const fs::path dir = scratch_dir();
  std::ofstream(dir / "trials.csv") << "trial,markers,plates,sex,height_cm,weight_kg\nsprint,JA1Gait35.c3d,,male,179,78\n";
  const auto r = run_ptnet("physics-bench --trials '" + (dir / "trials.csv").string() + "' --data '" + shared +
                               "' --out '" + (dir / "out").string() + "'",
                           dir / "run");
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream in(dir / "out" / "results.json");
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j.size(), 1u);
  EXPECT_EQ(j[0]["trial"], "sprint");
  EXPECT_EQ(j[0]["frames"], 324);
  EXPECT_EQ(j[0]["plates"]["contacts"].size(), 4u);  // two steps of each foot on the plates
  fs::remove_all(dir);
}
