// The simulator against force plates: OpenSim storage files read and
// written, contacts found where the force crosses its threshold, and the
// physics bench on the real gait-lab trials of ../shared/real-gait (skipped
// when absent), which must meet the figures of docs/physics.md: the
// simulated vertical force within 0.10 BW of the plates in walking, per
// contact peaks within 10 % (walking) and 15 % (running), stance within 40
// and 30 ms, flight found in running, the centre of pressure along the foot
// within 0.15 foot lengths, and every figure better than the naive
// reference's.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/plates.hpp"

namespace fs = std::filesystem;

TEST(ForcePlates, PlatesAreColumnGroupsReadByName) {
  const std::string text =
      "trial_grf.mot\nversion=1\nnRows=2\nnColumns=14\nendheader\n"
      "time\tknee_angle\tground_force_vx\tground_force_vy\tground_force_vz\tground_force_px\tground_force_py\t"
      "ground_force_pz\t1_ground_force_vx\t1_ground_force_vy\t1_ground_force_vz\t1_ground_force_px\t"
      "1_ground_force_py\t1_ground_force_pz\n"
      "0\t5\t1\t700\t3\t0.1\t0\t0.2\t0\t0\t0\t0\t0\t0\n"
      "0.01\t5\t2\t710\t4\t0.11\t0\t0.21\t0\t20\t0\t0.5\t0\t0.1\n";
  const ptnet::ForcePlates p = ptnet::parse_grf_mot(text, "t.mot");
  ASSERT_EQ(p.plates.size(), 2u);
  EXPECT_EQ(p.plates[0].prefix, "ground_force_");
  EXPECT_EQ(p.plates[1].prefix, "1_ground_force_");
  EXPECT_EQ(p.time_s, (std::vector<double>{0, 0.01}));
  EXPECT_EQ(p.plates[0].force_n[1], Eigen::Vector3d(2, 710, 4));
  EXPECT_EQ(p.plates[1].cop_m[1], Eigen::Vector3d(0.5, 0, 0.1));
  const std::string plate = "endheader\ntime\tforce_vx\tforce_vy\tforce_vz\tforce_px\tforce_py\tforce_pz\n";
  for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
           {"time\tx\n0\t1\n", "t.mot: expected an OpenSim storage header ending in 'endheader', found none"},
           {"endheader\ntime\tx\n0\t1\n", "t.mot: no force plate columns (expected PREFIX vx vy vz px py pz, e.g. "
                                          "ground_force_vx); found time x"},
           {"endheader\nx\tforce_vx\n0\t1\n", "t.mot: no 'time' column"},
           {plate, "t.mot: no rows after the column names"},
           {plate + "0\t1\n", "t.mot:3: expected 7 values (one per column), found 2"},
           {plate + "0\t1\t2\tabc\t4\t5\t6\n", "t.mot:3: expected a number in column force_vz, found 'abc'"},
           {plate + "0\t1\t2\tnan\t4\t5\t6\n", "t.mot:3: expected a number in column force_vz, found 'nan'"},
           {plate + "1\t0\t0\t0\t0\t0\t0\n0\t0\t0\t0\t0\t0\t0\n",
            "t.mot: expected increasing times, found 0 after 1"},
           // Before: a second plate of the same column names was not read.
           {"endheader\ntime\tforce_vx\tforce_vy\tforce_vz\tforce_px\tforce_py\tforce_pz\tforce_vx\tforce_vy\t"
            "force_vz\tforce_px\tforce_py\tforce_pz\n0\t1\t2\t3\t4\t5\t6\t7\t8\t9\t10\t11\t12\n",
            "t.mot: column 'force_vx' twice (columns 2 and 8): which one is meant?"}}) {
    try {
      ptnet::parse_grf_mot(bad, "t.mot");
      ADD_FAILURE() << bad;
    } catch (const ptnet::Error& e) {
      EXPECT_EQ(e.what(), message);
    }
  }
}

TEST(Contacts, AHalfSineIsFoundWithItsCrossingsPeakImpulseAndRate) {
  // 600 N half sines of 0.25 s every 0.4 s, sampled at 60 Hz.
  std::vector<double> t, f;
  for (int k = 0; k < 120; ++k) {
    t.push_back(k / 60.0);
    const double phase = std::fmod(t.back(), 0.4);
    f.push_back(phase < 0.25 ? 600 * std::sin(M_PI * phase / 0.25) : 0.0);
  }
  const auto c = ptnet::find_contacts(t, f, 20, 1);
  ASSERT_EQ(c.size(), 5u);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double t0 = 0.4 * double(i), t20 = std::asin(20.0 / 600) / M_PI * 0.25;  // where 600 sin crosses 20 N
    EXPECT_EQ(c[i].foot, 1);
    EXPECT_TRUE(c[i].whole);
    EXPECT_NEAR(c[i].start_s, t0 + t20, 0.002);  // linear between samples 17 ms apart
    EXPECT_NEAR(c[i].end_s - c[i].start_s, 0.25 - 2 * t20, 0.004);
    EXPECT_NEAR(c[i].peak_n, 600, 600 * 0.02);
    EXPECT_NEAR(c[i].impulse_ns, 600 * 0.25 * 2 / M_PI, 600 * 0.25 * 2 / M_PI * 0.02);
    // 20 % -> 80 % of the peak: 0.6 peak over (asin 0.8 - asin 0.2) / pi x 0.25 s.
    const double rate = 0.6 * 600 / ((std::asin(0.8) - std::asin(0.2)) / M_PI * 0.25);
    EXPECT_NEAR(c[i].loading_rate_n_s, rate, rate * 0.1);
  }
}

TEST(ForceTable, WrittenAsOpenSimStorageAndCsv) {
  ptnet::ForceTable f;
  f.mass_kg = 70;
  f.time_s = {0, 0.5};
  f.total_n = {686.7, 0};
  f.foot_n = {{686.7, 0}, {0, 0}};
  f.cop_u = {{0.5, NAN}, {NAN, NAN}};
  f.carried_n = {0, 0};
  const fs::path dir = fs::temp_directory_path() / ("ptnet_forces_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  ptnet::write_force_table(f, (dir / "a.mot").string(), false);
  ptnet::write_force_table(f, (dir / "a.csv").string(), false);
  EXPECT_THROW(ptnet::write_force_table(f, (dir / "a.csv").string(), false), ptnet::Error);  // no --force
  EXPECT_THROW(ptnet::write_force_table(f, (dir / "a.txt").string(), false), ptnet::Error);
  ptnet::ForceTable short_seat = f;
  short_seat.carried_n.pop_back();  // a column of another length: refused, nothing written
  EXPECT_THROW(ptnet::write_force_table(short_seat, (dir / "b.mot").string(), false), ptnet::Error);
  EXPECT_FALSE(fs::exists(dir / "b.mot"));
  const std::string mot = ptnet::read_text_file((dir / "a.mot").string());
  EXPECT_NE(mot.find("nRows=2\nnColumns=20\n"), std::string::npos);
  EXPECT_NE(mot.find("endheader\ntime\ttotal_force_vy\ttotal_force_bw\tl_ground_force_vy"), std::string::npos);
  // The columns of before, then each foot's plate group (no CoP known: 0).
  EXPECT_NE(mot.find("0\t686.7\t1\t686.7\t0\t1\t0\t0.5\tnan\t0\t0\t0\t0\t0\t0\t0\t0\t0\t0\t0\n"), std::string::npos)
      << mot;
  const std::string csv = ptnet::read_text_file((dir / "a.csv").string());
  EXPECT_EQ(csv.rfind("time,total_force_vy,total_force_bw,", 0), 0u);
  fs::remove_all(dir);
}
TEST(PhysicsBench, TheSimulatorMeetsThePlatesOfRealWalkingAndRunning) {
  const std::string dir = PTNET_SHARED_GAIT;
  if (!fs::exists(dir + "/walk_s01.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  const auto trials = ptnet::read_gait_trials(std::string(PTNET_SOURCE_DIR) + "/bench/real-gait.csv", dir);
  ASSERT_GE(trials.size(), 2u);
  for (const auto& trial : trials) {
    if (trial.name != "walk_s01" && trial.name != "run_s02") continue;  // the other labs: plates_activities_test
    SCOPED_TRACE(trial.name);
    const ptnet::GaitTrialResult r = ptnet::run_gait_trial(trial, {});
    const ptnet::ForceSource &s = r.simulated, &n = r.naive;
    const bool run = trial.name == "run_s02";
    EXPECT_EQ(r.fps, 60);
    int whole = 0;
    for (const auto& c : r.plates.contacts) whole += c.whole;
    EXPECT_EQ(s.matched, whole);
    EXPECT_LE(s.peak_error_pct, run ? 15 : 10);
    EXPECT_LE(s.stance_error_ms, run ? 30 : 40);
    EXPECT_LT(s.peak_error_pct, n.peak_error_pct);
    EXPECT_LT(s.rmse_bw, n.rmse_bw);
    EXPECT_LT(s.stride_impulse_error_pct, 5);
    if (run) {
      EXPECT_GT(r.flight_frames, 100);
      EXPECT_GE(s.flight_recall, 0.9);
      EXPECT_LE(s.rmse_bw, 0.2);
    } else {
      EXPECT_LE(s.rmse_bw, 0.10);
      EXPECT_LE(s.cop_rms, 0.15);
      EXPECT_LT(s.cop_rms, n.cop_rms);
    }
  }
}

TEST(PhysicsBench, OvergroundPlatesAreComparedOnlyWhereTheySeeEveryFoot) {
  const std::string dir = PTNET_SHARED_GAIT;
  if (!fs::exists(dir + "/walk_s01.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  // The walk as if its second plate ended at 1.2 s: the steps after it are
  // off the plates.
  std::istringstream in(ptnet::read_text_file(dir + "/walk_s01_grf.mot"));
  std::ostringstream out;
  bool data = false;
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) {
    if (!data || names.empty()) {
      out << line << "\n";
      if (line.rfind("endheader", 0) == 0) data = true;
      else if (data) {
        std::istringstream w(line);
        for (std::string n; w >> n;) names.push_back(n);
      }
      continue;
    }
    std::istringstream w(line);
    std::vector<std::string> v;
    for (std::string x; w >> x;) v.push_back(x);
    for (std::size_t c = 0; c < v.size(); ++c)
      if (std::stod(v[0]) > 1.2 && names[c].rfind("1_ground_force_v", 0) == 0) v[c] = "0";
    for (std::size_t c = 0; c < v.size(); ++c) out << (c ? "\t" : "") << v[c];
    out << "\n";
  }
  const fs::path tmp = fs::temp_directory_path() / ("ptnet_overground_" + std::to_string(::getpid()) + ".mot");
  std::ofstream(tmp) << out.str();
  ptnet::GaitTrial t = ptnet::read_gait_trials(std::string(PTNET_SOURCE_DIR) + "/bench/real-gait.csv", dir)[0];
  t.plates = tmp.string();
  const ptnet::GaitTrialResult all = ptnet::run_gait_trial(t, {});
  EXPECT_EQ(all.coverage, ptnet::PlateCoverage::some);  // auto: a foot on the floor that no plate sees
  int compared = 0;
  for (bool c : all.compared) compared += c;
  EXPECT_GT(compared, 40);
  EXPECT_LT(compared, int(all.time_s.size()) - 40);
  EXPECT_LE(all.simulated.rmse_bw, 0.10);  // over the frames the plates see whole
  t.coverage = ptnet::PlateCoverage::all;
  const ptnet::GaitTrialResult forced = ptnet::run_gait_trial(t, {});
  EXPECT_GT(forced.simulated.rmse_bw, 0.3);  // the unseen steps counted as the simulator's error
  fs::remove(tmp);
}

TEST(PhysicsBench, TheSameTrialsInTheCommonMarkerNamesGiveTheSameFigures) {
  const std::string dir = PTNET_SHARED_GAIT;
  if (!fs::exists(dir + "/run_s02.trc")) GTEST_SKIP() << "../shared/real-gait not found";
  // Delaware names -> the common names (RASI, RTH1, RKNE, RCAL, RMT1, ...):
  // the shipped "common" map is chosen and places the same landmarks.
  const std::vector<std::pair<std::string, std::string>> names = {
      {"ASIS", "ASI"}, {"Thigh.Upper", "TH1"}, {"Thigh.Front", "TH2"}, {"Thigh.Rear", "TH3"}, {"Shank.Upper", "SH1"},
      {"Shank.Front", "SH2"}, {"Shank.Rear", "SH3"}, {"Knee.Lat", "KNE"}, {"Knee.Med", "KNM"}, {"Ankle.Lat", "ANK"},
      {"Ankle.Med", "MMA"}, {"Heel", "CAL"}, {"Toe.Med", "MT1"}, {"Toe.Lat", "MT5"}, {"Toe.Tip", "HLX"},
      {"Acromium", "SHO"}, {"Elbow", "ELB"}, {"Wrist.Lat", "WRA"}, {"Wrist.Med", "WRB"}};
  auto rename = [&](const std::string& n) -> std::string {
    if (n == "V.Sacral") return "SACR";
    if (n == "Sternum") return "STRN";
    if (n == "Top.Head") return "HEAD";
    for (const auto& [from, to] : names)
      for (const char* side : {"R.", "L."})
        if (n == side + from) return std::string(1, side[0]) + to;
    return n;
  };
  const fs::path tmp = fs::temp_directory_path() / ("ptnet_common_" + std::to_string(::getpid()));
  fs::create_directories(tmp);
  for (const char* f : {"run_s02.trc", "run_s02_static.trc"}) {
    std::istringstream in(ptnet::read_text_file(dir + "/" + f));
    std::ofstream out(tmp / f);
    int n = 0;
    for (std::string line; std::getline(in, line);) {
      if (++n == 4) {  // the marker names
        std::string renamed, cell;
        std::istringstream cells(line);
        for (bool first = true; std::getline(cells, cell, '\t'); first = false)
          renamed += (first ? "" : "\t") + (cell.empty() ? cell : rename(cell));
        line = renamed;
      }
      out << line << "\n";
    }
  }
  ptnet::GaitTrial t = ptnet::read_gait_trials(std::string(PTNET_SOURCE_DIR) + "/bench/real-gait.csv", dir)[1];
  ASSERT_EQ(t.name, "run_s02");
  const ptnet::GaitTrialResult delaware = ptnet::run_gait_trial(t, {});
  t.markers = (tmp / "run_s02.trc").string();
  t.static_markers = (tmp / "run_s02_static.trc").string();
  ptnet::MarkerReport report;
  ptnet::MotionOptions mo;
  mo.static_markers = t.static_markers;
  ptnet::motion_from_trc(ptnet::read_trc(t.markers), mo, &report);
  EXPECT_EQ(report.map, "common");
  EXPECT_EQ(report.calibrated.size(), 8u);
  const ptnet::GaitTrialResult common = ptnet::run_gait_trial(t, {});
  EXPECT_NEAR(common.simulated.rmse_bw, delaware.simulated.rmse_bw, 0.01);
  EXPECT_NEAR(common.simulated.peak_error_pct, delaware.simulated.peak_error_pct, 1.0);
  fs::remove_all(tmp);
}
