// What the physics bench reads and what its figures rest on, in a bare
// clone (no ../shared): the trials CSV (trial names that are file names and
// one per trial, files resolved and checked as the filesystem and InputFile
// have them, marker maps beside the CSV), its one column list (the help and
// docs/physics.md), plates from storage and CSV files and from ptnet's own
// force files, and the checks of a result (plates on another clock, a
// negated vertical force, a partial overlap).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "data_test_util.hpp"
#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/plates.hpp"
#include "ptnet/sim.hpp"
#include "ptnet/strings.hpp"

using namespace ptnet;
using ptnet::testing_util::TempDir;
using ptnet::testing_util::error_of;
namespace fs = std::filesystem;

namespace {

const char* kHeader = "trial,markers,static,plates,sex,height_cm,weight_kg";

// A folder with a trials CSV of `rows` and the (empty) files they name.
struct Trials {
  TempDir dir{"trials"};
  std::string csv;
  explicit Trials(const std::string& rows, const std::string& header = kHeader) {
    for (const char* f : {"w.trc", "w_static.trc", "w.mot", "lab.map"}) std::ofstream(dir.file(f)) << "x\n";
    csv = dir.file("trials.csv");
    std::ofstream(csv) << header << "\n" << rows;
  }
};

}  // namespace

// Before: the trial name became file names unchecked: "../escaped" wrote
// four files into the parent of --out (with --force it replaced them), and
// two trials of one name wrote half the output before an error.
TEST(GaitTrials, ATrialNameIsAFileNameOfItsOwn) {
  Trials escape("../escaped,w.trc,w_static.trc,w.mot,male,180,72\n");
  EXPECT_EQ(error_of([&] { read_gait_trials(escape.csv, ""); }),
            escape.csv + ":2: expected a trial name that is a file name (it names the trial's outputs), found "
                         "'../escaped', which holds '/'");
  Trials twice("w,w.trc,w_static.trc,w.mot,male,180,72\nw,w.trc,,w.mot,female,165,60\n");
  EXPECT_EQ(error_of([&] { read_gait_trials(twice.csv, ""); }),
            twice.csv + ":3: expected a trial name of its own, found 'w', the name of line 2's trial too");
  // The report refuses them too (a library caller's own GaitTrial).
  GaitTrial t;
  t.name = "../x";
  EXPECT_NE(error_of([&] { check_physics_report({t}, escape.dir.file("out"), false); }).find("holds '/'"),
            std::string::npos);
  t.name = "w";
  EXPECT_NE(error_of([&] { check_physics_report({t, t}, escape.dir.file("out"), false); })
                .find("two trials would write 'w_sim.mot'"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(escape.dir.file("out")));
}

// Before: a FIFO was "file ... not found", and "link/../w.trc" through a
// linked folder too (the path normalised as text).
TEST(GaitTrials, FilesAreResolvedByTheFilesystemAndSaidAsWhatTheyAre) {
  Trials t("w,sub/link/../w.trc,,fifo.mot,male,180,72\n");
  fs::create_directories(t.dir.path / "sub");
  fs::create_directories(t.dir.path / "other" / "deep");
  fs::create_symlink(t.dir.path / "other" / "deep", t.dir.path / "sub" / "link");
  fs::rename(t.dir.file("w.trc"), t.dir.file("other/w.trc"));
  ASSERT_EQ(::mkfifo(t.dir.file("fifo.mot").c_str(), 0600), 0);
  // sub/link/.. is other/deep/.. = other, where w.trc is (as text: sub/w.trc).
  EXPECT_EQ(error_of([&] { read_gait_trials(t.csv, ""); }),
            t.csv + ":2: plates 'fifo.mot': is a FIFO, expected a regular file");
  fs::remove(t.dir.file("fifo.mot"));
  std::ofstream(t.dir.file("fifo.mot")) << "x\n";
  const auto trials = read_gait_trials(t.csv, "");
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_TRUE(fs::is_regular_file(trials[0].markers)) << trials[0].markers;
  Trials empty("w,,,w.mot,male,180,72\n");
  EXPECT_EQ(error_of([&] { read_gait_trials(empty.csv, ""); }),
            empty.csv + ":2: expected a file in column markers, found an empty field");
}

// Before: marker_map was used as given, against the current folder, while
// the trial's other files were resolved against the CSV's folder.
TEST(GaitTrials, AMarkerMapFileIsBesideTheCsvAShippedMapStaysAName) {
  Trials t("a,w.trc,,w.mot,male,180,72,lab.map\nb,w.trc,,w.mot,male,180,72,delaware\n",
           std::string(kHeader) + ",marker_map");
  const auto trials = read_gait_trials(t.csv, "");
  EXPECT_EQ(trials[0].marker_map, t.dir.file("lab.map"));
  EXPECT_EQ(trials[1].marker_map, "delaware");
}

// Before: a trials CSV's marker_map was only resolved, and read when its
// trial ran: "nosuch.map" (or a folder, a FIFO) on row 3 failed after row
// 2's trial was simulated, without the CSV's line. It is now checked at its
// line with the trial's other files, before any trial runs.
TEST(GaitTrials, AMarkerMapFileIsCheckedAtItsLineBeforeAnyTrial) {
  Trials t("a,w.trc,,w.mot,male,180,72,lab.map\nb,w.trc,,w.mot,male,180,72,nosuch.map\n",
           std::string(kHeader) + ",marker_map");
  EXPECT_EQ(error_of([&] { read_gait_trials(t.csv, ""); }),
            t.csv + ":3: marker_map 'nosuch.map': no such file (shipped maps: common, delaware, plugin-gait)");
  fs::create_directories(t.dir.file("maps"));
  ASSERT_EQ(::mkfifo(t.dir.file("fifo.map").c_str(), 0600), 0);
  for (const char* name : {"maps", "fifo.map"}) {
    std::ofstream(t.csv) << kHeader << ",marker_map\na,w.trc,,w.mot,male,180,72," << name << "\n";
    const std::string e = error_of([&] { read_gait_trials(t.csv, ""); });
    EXPECT_EQ(e.rfind(t.csv + ":2: marker_map '" + name + "': is a ", 0), 0u) << e;
  }
}

// Before: a column the bench does not know (a misspelt "unit", "bogus")
// was ignored in silence; the markers' unit had no column, so the units
// error's "pass --units" named an option physics-bench does not have.
TEST(GaitTrials, AnUnknownColumnIsRefusedAndUnitsIsOne) {
  Trials bogus("a,w.trc,,w.mot,male,180,72,1\n", std::string(kHeader) + ",bogus");
  EXPECT_EQ(error_of([&] { read_gait_trials(bogus.csv, ""); }),
            bogus.csv + ":1: expected only the columns " + gait_trial_columns_text() + ", found column 'bogus'");
  Trials units("a,w.trc,,w.mot,male,180,72,m\nb,w.trc,,w.mot,male,180,72,\n", std::string(kHeader) + ",units");
  const auto trials = read_gait_trials(units.csv, "");
  EXPECT_EQ(trials[0].units, Units::m);
  EXPECT_EQ(trials[1].units, Units::automatic);
  Trials furlongs("a,w.trc,,w.mot,male,180,72,furlongs\n", std::string(kHeader) + ",units");
  EXPECT_EQ(error_of([&] { read_gait_trials(furlongs.csv, ""); }),
            furlongs.csv + ":2: expected units auto, m, cm, mm, in or cmu, found 'furlongs'");
}

// One list of the trials CSV's columns: the parser reads it, the help is
// built from it, docs/physics.md documents each (before: the help omitted
// coverage).
TEST(GaitTrials, TheColumnsAreOneListThatTheDocsFollow) {
  EXPECT_EQ(gait_trial_columns_text(), "trial,markers,plates,sex,height_cm,weight_kg[,static,marker_map,coverage,units]");
  std::ifstream in(std::string(PTNET_SOURCE_DIR) + "/docs/physics.md");
  const std::string page((std::istreambuf_iterator<char>(in)), {});
  const std::size_t at = page.find("## Trials of one's own");
  ASSERT_NE(at, std::string::npos);
  const std::string section = page.substr(at);
  EXPECT_NE(section.find("columns: `" + gait_trial_columns_text() + "`"), std::string::npos)
      << "docs/physics.md, Trials of one's own: list the columns as gait_trial_columns_text()";
  for (const GaitTrialColumn& c : kGaitTrialColumns)
    EXPECT_NE(section.find(std::string("`") + c.name + "`"), std::string::npos) << c.name << " is not documented";
  Trials missing("w,w.trc,,w.mot,male,180\n", "trial,markers,static,plates,sex,height_cm");
  EXPECT_EQ(error_of([&] { read_gait_trials(missing.csv, ""); }).find(missing.csv + ":1: expected a header with column weight_kg"),
            0u);
}

// ptnet's force files read back as force plates: one plate per foot, the
// vertical force on OpenSim's y, the centre of pressure where the foot's
// heel-toe line puts it (before: only *_vy columns, no plate group).
TEST(ForcePlates, PtnetsOwnForceFilesAreTwoPlates) {
  TempDir d("own_forces");
  ForceTable f;
  f.mass_kg = 70;
  f.time_s = {0, 0.01, 0.02};
  f.total_n = {700, 650, 0};
  f.foot_n = {{700, 0}, {400, 250}, {0, 0}};
  f.cop_u = {{0.2, NAN}, {0.7, 0.1}, {NAN, NAN}};
  f.carried_n = {0, 0, 0};
  f.cop_m = {{Eigen::Vector2d(1.0, 0.2), Eigen::Vector2d(0, 0)},
             {Eigen::Vector2d(1.1, 0.2), Eigen::Vector2d(0.5, -0.1)},
             {Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0)}};
  for (const char* name : {"a.mot", "a.csv"}) {
    SCOPED_TRACE(name);
    write_force_table(f, d.file(name), false);
    const ForcePlates p = read_grf_mot(d.file(name));
    ASSERT_EQ(p.plates.size(), 2u);
    EXPECT_EQ(p.plates[0].prefix, "l_ground_force_");
    EXPECT_EQ(p.plates[1].prefix, "r_ground_force_");
    EXPECT_EQ(p.time_s, f.time_s);
    for (std::size_t t = 0; t < 3; ++t)
      for (std::size_t s = 0; s < 2; ++s) {
        EXPECT_EQ(p.plates[s].force_n[t], Eigen::Vector3d(0, f.foot_n[t][s], 0));
        // OpenSim's axes: (world y, 0, world x).
        const Eigen::Vector3d at(f.cop_m[t][s].y(), 0, f.cop_m[t][s].x());
        EXPECT_EQ(p.plates[s].cop_m[t], at) << t << " " << s;
      }
  }
}

namespace {

// A result of T frames at 100 Hz whose plates read `plates_bw` (NaN: no
// sample) and whose every frame is compared; the left foot carries the
// load unless `under_feet` is false (no plate's CoP near a foot).
GaitTrialResult result_with_plates(const std::vector<double>& plates_bw, bool under_feet = true) {
  GaitTrialResult r;
  r.trial.name = "w";
  r.trial.plates = "w.mot";
  for (std::size_t t = 0; t < plates_bw.size(); ++t) {
    r.time_s.push_back(0.01 * double(t));
    r.plates.total_bw.push_back(plates_bw[t]);
    r.plates.foot_bw.push_back({under_feet ? plates_bw[t] : 0.0, 0.0});
    r.compared.push_back(true);
  }
  return r;
}

}  // namespace

// Before: plates on another clock or with the vertical force negated gave
// an empty table, "compared 0 of 151" and exit 0; a partial overlap gave
// figures without a word.
TEST(GaitResults, NothingComparedIsAnErrorAndAPartialOverlapAWarning) {
  const PhysicsBenchOptions o;
  EXPECT_TRUE(check_gait_result(result_with_plates(std::vector<double>(100, 1.0)), o).empty());
  EXPECT_EQ(error_of([&] { check_gait_result(result_with_plates(std::vector<double>(100, NAN)), o); }),
            "w.mot: trial 'w': no plate sample within the markers' 0.000-0.990 s: the plates on another clock? "
            "nothing to compare");
  std::vector<double> negated(100, -1.0);
  negated[0] = negated[1] = 0;
  EXPECT_EQ(error_of([&] { check_gait_result(result_with_plates(negated), o); }),
            "w.mot: trial 'w': the vertical force is below zero in 98 % of the frames (mean -0.98 BW): the force on "
            "the plates, not the ground reaction on the feet; negate the plates' force columns (vx, vy, vz) and run "
            "again");
  EXPECT_NE(error_of([&] { check_gait_result(result_with_plates(std::vector<double>(100, 0.0)), o); })
                .find("the plates carry no load"),
            std::string::npos);
  std::vector<double> late(100, NAN);
  for (std::size_t t = 40; t < 100; ++t) late[t] = 1.0;
  const auto warnings = check_gait_result(result_with_plates(late), o);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0], "trial 'w': the plates cover 60 % of the 100 frames (0.400-0.990 s of the markers' "
                         "0.000-0.990 s): the figures are over those; the plates on another clock?");
  GaitTrialResult none = result_with_plates(std::vector<double>(100, 1.0));
  none.compared.assign(100, false);
  EXPECT_NE(error_of([&] { check_gait_result(none, o); }).find("no frame compared"), std::string::npos);
  // Before: plates whose CoP is in mm (or another frame) gave no force to
  // any foot: every per-foot figure "-", exit 0.
  EXPECT_EQ(error_of([&] { check_gait_result(result_with_plates(std::vector<double>(100, 1.0), false), o); }),
            "w.mot: trial 'w': the plates' centres of pressure are within 0.15 m of a foot for 0 % of their load: "
            "the CoP in mm (OpenSim storage has metres), or in another lab frame than the markers'? nothing per "
            "foot to compare");
}

// physics-bench converts a trial once: the lab's positions (where the
// plates' CoP is) read without removing the treadmill's belt, and the belt
// the marker pipeline reports taken out for the simulator, bit for bit the
// motion read with remove_belt (before: the pipeline reported no belt when
// it removed none, so the bench converted the trial, and read its static
// trial, twice).
TEST(GaitTrials, OneConversionGivesTheLabAndTheMotionWithoutTheBelt) {
  const std::string dir = std::string(PTNET_TEST_DATA) + "/gait";
  const Trc trc = read_trc(dir + "/walk.trc");
  MotionOptions o;
  o.fps = trc.rate_hz;
  o.static_markers = dir + "/walk_static.trc";
  MarkerReport removed, kept;
  const Motion source = motion_from_trc(trc, o, &removed);
  o.remove_belt = false;
  const Motion lab = motion_from_trc(trc, o, &kept);
  ASSERT_GT(removed.belt_speed_mps, 0.5);  // the committed trial is on a treadmill
  EXPECT_EQ(kept.belt_velocity_mps, removed.belt_velocity_mps);
  EXPECT_EQ(kept.belt_speed_mps, removed.belt_speed_mps);
  const Motion back = without_belt(lab, kept.belt_velocity_mps);
  ASSERT_EQ(back.size(), source.size());
  for (int t = 0; t < source.size(); ++t)
    for (std::size_t j = 0; j < source.frames[std::size_t(t)].size(); ++j)
      ASSERT_EQ(back.frames[std::size_t(t)][j], source.frames[std::size_t(t)][j]) << t << " " << j;
  EXPECT_NE(lab.frames.back()[0], source.frames.back()[0]);  // the lab moved with the belt
}

namespace {

std::string slurp_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `text` with its rows after the first `header` lines kept while their
// time (tab-separated column `time_col`) is at most `t_max_s`; `kept`
// counts them.
std::string rows_until(const std::string& text, std::size_t header, std::size_t time_col, double t_max_s,
                       long* kept) {
  std::istringstream in(text);
  std::string out, line;
  *kept = 0;
  for (std::size_t n = 0; std::getline(in, line); ++n) {
    std::vector<std::string> f = split(line, '\t');
    const bool row = n >= header && f.size() > time_col && !trim(f[time_col]).empty();
    if (row && std::stod(f[time_col]) > t_max_s + 1e-9) continue;
    *kept += row;
    out += line + "\n";
  }
  return out;
}

}  // namespace

// Before: plates that ran on past the markers (markers 0-2.0 s, plates
// 0-2.5 s) counted a contact cut by the markers' end as whole: on the
// committed trial the stance error was 127 ms against 88 with the plates
// cut to 2.0 s (129 against 11 ms on ../shared's walk_s01). The plates are
// now cut to the markers' time span before their contacts are found.
TEST(GaitTrials, PlatesThatRunPastTheMarkersAreCutToTheirSpan) {
  const std::string gait = std::string(PTNET_TEST_DATA) + "/gait";
  TempDir dir("span");
  long frames = 0, samples = 0;
  std::string trc = rows_until(slurp_file(gait + "/walk.trc"), 5, 1, 2.0, &frames);
  const std::string counts = "\t151\t24\tmm\t60.00\t1\t151\n";  // NumFrames ... OrigNumFrames
  ASSERT_EQ(frames, 121);
  ASSERT_NE(trc.find(counts), std::string::npos);
  trc.replace(trc.find(counts), counts.size(), "\t121\t24\tmm\t60.00\t1\t121\n");
  std::ofstream(dir.file("walk.trc"), std::ios::binary) << trc;
  const std::string plates = slurp_file(gait + "/walk_grf.mot");
  std::ofstream(dir.file("cut.mot"), std::ios::binary) << rows_until(plates, 7, 0, 2.0, &samples);
  ASSERT_EQ(samples, 361);
  GaitTrial t = read_gait_trials(gait + "/trials.csv", "")[0];
  t.markers = dir.file("walk.trc");
  const GaitTrialResult longer = run_gait_trial(t, {});  // the plates to 2.5 s
  t.plates = dir.file("cut.mot");
  const GaitTrialResult cut = run_gait_trial(t, {});
  ASSERT_EQ(longer.plates.contacts.size(), cut.plates.contacts.size());
  bool cut_by_the_end = false;
  for (std::size_t k = 0; k < cut.plates.contacts.size(); ++k) {
    const Contact &a = longer.plates.contacts[k], &b = cut.plates.contacts[k];
    EXPECT_EQ(a.whole, b.whole) << k;
    EXPECT_NEAR(a.end_s, b.end_s, 1e-9) << k;
    EXPECT_LE(a.end_s, 2.0 + 1e-6) << k;
    cut_by_the_end = cut_by_the_end || (a.end_s > 2.0 - 1e-6 && !a.whole);
  }
  EXPECT_TRUE(cut_by_the_end);  // the trial's end falls in a stance
  for (const auto& [x, y] : {std::make_pair(&longer.simulated, &cut.simulated), std::make_pair(&longer.naive, &cut.naive)}) {
    EXPECT_EQ(x->matched, y->matched);
    EXPECT_NEAR(x->stance_error_ms, y->stance_error_ms, 1e-9);
    EXPECT_NEAR(x->peak_error_pct, y->peak_error_pct, 1e-9);
    EXPECT_NEAR(x->loading_rate_error_pct, y->loading_rate_error_pct, 1e-9);
    EXPECT_NEAR(x->rmse_bw, y->rmse_bw, 1e-9);
  }
}
