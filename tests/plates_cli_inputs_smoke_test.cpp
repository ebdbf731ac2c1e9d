// The gait-lab commands as a hostile but realistic user drives them (issue
// 48): nothing written outside --out, nothing half written, every check
// before the work, every text input UTF-8 or one line, a command that
// compares nothing exits non-zero. The trial is the committed synthetic
// gait trial (tests/data/gait): every case runs in a bare clone.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace {

namespace fs = std::filesystem;
using ptnet::testing_cli::RunResult;
using ptnet::testing_cli::slurp;

struct Dir {
  fs::path path = fs::temp_directory_path() / ("ptnet_gait_inputs_" + std::to_string(::getpid()));
  Dir() {
    fs::remove_all(path);
    fs::create_directories(path / "work");
  }
  ~Dir() { fs::remove_all(path); }
  // ptnet ARGS in path/work.
  RunResult run(const std::string& args) const { return ptnet::testing_cli::run_ptnet(args, path / "run", path / "work"); }
  void write(const std::string& name, const std::string& text) const {
    fs::create_directories((path / "work" / name).parent_path());
    std::ofstream(path / "work" / name, std::ios::binary) << text;
  }
  bool exists(const std::string& name) const { return fs::exists(path / "work" / name); }
};

// One line "ptnet: error: ..." holding `what`, status `status`.
void expect_error(const RunResult& r, int status, const std::string& what) {
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_EQ(r.err.rfind("ptnet: error: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

const std::string kGait = std::string(PTNET_TEST_DATA) + "/gait";
const char* kHeader = "trial,markers,static,plates,sex,height_cm,weight_kg\n";

// The walk's plates, each row's time moved by `shift_s`, its force negated
// when `negate`, its CoP in mm when `mm`; `bom` puts a byte-order mark
// before "endheader" on the file's first line.
std::string walk_plates(double shift_s, bool negate, bool bom = false, bool mm = false) {
  std::istringstream in(slurp(kGait + "/walk_grf.mot"));
  std::string out = bom ? "\xef\xbb\xbf" : "", line;
  std::vector<std::string> names;
  bool data = false;
  while (std::getline(in, line)) {
    if (!data) {
      data = line.rfind("endheader", 0) == 0;
      if (!bom || data) out += line + "\n";
      continue;
    }
    std::istringstream w(line);
    std::vector<std::string> v;
    for (std::string x; w >> x;) v.push_back(x);
    if (names.empty()) {
      names = v;
    } else if (!v.empty()) {
      v[0] = std::to_string(std::stod(v[0]) + shift_s);
      for (std::size_t c = 0; c < v.size(); ++c)
        if (negate && names[c].find("force_v") != std::string::npos) v[c] = std::to_string(-std::stod(v[c]));
        else if (mm && names[c].find("force_p") != std::string::npos) v[c] = std::to_string(1000 * std::stod(v[c]));
    }
    for (std::size_t c = 0; c < v.size(); ++c) out += (c ? "\t" : "") + v[c];
    out += "\n";
  }
  return out;
}

// A trials CSV in work/ for the walk with plates `plates` (a name in work/).
void walk_csv(const Dir& d, const std::string& csv, const std::string& plates, const std::string& name = "w") {
  d.write(csv, std::string(kHeader) + name + "," + kGait + "/walk.trc," + kGait + "/walk_static.trc," + plates +
                   ",male,175.0,70.0\n");
}

}  // namespace

// Before: "../escaped" wrote four files beside --out; two trials of one
// name wrote half the output, then an error; a trial name with '/' left an
// empty output folder; a Windows-1252 trials CSV ended in nlohmann's
// internal exception after four per-trial files.
TEST(CliGaitInputs, TrialNamesAndTextAreCheckedBeforeAnyOutput) {
  Dir d;
  for (const char* f : {"w.trc", "w.mot"}) d.write(f, "x\n");
  const std::string row = ",w.trc,,w.mot,male,180,72\n";
  d.write("escape.csv", std::string(kHeader) + "../escaped" + row);
  expect_error(d.run("physics-bench --trials escape.csv --out out/b"), 1,
               "escape.csv:2: expected a trial name that is a file name");
  d.write("slash.csv", std::string(kHeader) + "x/y" + row);
  expect_error(d.run("physics-bench --trials slash.csv --out slash"), 1, "which holds '/'");
  d.write("twice.csv", std::string(kHeader) + "w" + row + "w" + row);
  expect_error(d.run("physics-bench --trials twice.csv --out twice"), 1, "twice.csv:3: expected a trial name of its own");
  d.write("latin1.csv", std::string(kHeader) + "caf\xe9" + row);
  expect_error(d.run("physics-bench --trials latin1.csv --out latin1"), 1,
               "latin1.csv:2: expected UTF-8 text, found byte 0xE9");
  for (const char* out : {"out", "escaped_sim.mot", "slash", "twice", "latin1"}) EXPECT_FALSE(d.exists(out)) << out;
  // Text inputs of the other commands: a marker file, a non-UTF-8 argument.
  d.write("latin1.trc", "PathFileType\t4\t(X/Y/Z)\tx.trc\nDataRate\nLatin\xe9\n");
  expect_error(d.run("info latin1.trc --json"), 1, "latin1.trc:3: expected UTF-8 text, found byte 0xE9");
  expect_error(d.run("info 'caf\xe9.bvh'"), 2, "is not UTF-8");
}

TEST(CliGaitInputs, SimulateChecksItsForceFilesBeforeTheWork) {
  Dir d;
  d.write("b.csv", "id,sex,height_cm,weight_kg\nb1,female,160,55\n");
  // Before: the dataset was simulated and written, then "cannot create folder".
  expect_error(d.run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies b.csv --out s.h5 --forces s.h5"),
               1, "--forces: s.h5 is the dataset's own path");
  EXPECT_FALSE(d.exists("s.h5"));
  // A force file that is an input (the bodies CSV, as NAME.csv) is never
  // replaced, even with --force; before, found once the dataset was written.
  d.write("p1_walking_t1__b1.csv", "id,sex,height_cm,weight_kg\nb1,female,160,55\n");
  expect_error(d.run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies p1_walking_t1__b1.csv "
                     "--out t.h5 --forces . --forces-format csv --force"),
               1, "is the same file as the input");
  EXPECT_FALSE(d.exists("t.h5"));
  // A clip whose name is no UTF-8 (its stem names sequences; HDF5 declares
  // the attributes UTF-8): refused before any work.
  ASSERT_EQ(d.run("-q motions --category walking --seconds 1 --out walk.bvh").status, 0);
  fs::create_directories(d.path / "work" / "clips");
  fs::copy_file(d.path / "work" / "walk.bvh", d.path / "work" / "clips" / "caf\xe9.bvh");
  expect_error(d.run("-q simulate --motions clips --bodies b.csv --out c.h5"), 1, "is not UTF-8");
  EXPECT_FALSE(d.exists("c.h5"));
}

TEST(CliGaitInputs, MotionsWritesWhatItsNameSaysAndRefusesWhatItWouldIgnore) {
  Dir d;
  // Before: BVH written into w.trc; --seconds with --from silently ignored.
  expect_error(d.run("motions --category walking --seconds 1 --out w.trc"), 1, "w.trc: expected a .bvh file name");
  EXPECT_FALSE(d.exists("w.trc"));
  ASSERT_EQ(d.run("-q motions --category walking --seconds 1 --out w.bvh").status, 0);
  for (const char* extra : {"--seconds 1", "--seed 3", "--height-cm 170", "--performer 2", "--take 2"})
    expect_error(d.run(std::string("motions --from w.bvh --out w2.bvh ") + extra), 2, "excludes");
  EXPECT_FALSE(d.exists("w2.bvh"));
  // Before: a name error left an empty output folder.
  expect_error(d.run("motions --performers 1 --categories walking,bogus --out-dir set"), 1, "bogus");
  EXPECT_FALSE(d.exists("set"));
}

// Before: simulate wrote HDF5 into w.trc or w.bvh, merge into m.trc and
// bodies CSV into b.trc (only motions checked its output's name). One
// check (check_output_name) for every command that writes a file of one
// format, before any work; nothing is written.
TEST(CliGaitInputs, EveryOutputFileIsNamedForItsFormat) {
  Dir d;
  expect_error(d.run("bodies --males 1 --females 0 --originals 0,0 --out b.trc"), 1,
               "b.trc: expected a .csv file name (CSV is written), found '.trc'");
  ASSERT_EQ(d.run("-q bodies --males 1 --females 0 --originals 0,0 --out b.csv").status, 0);
  const std::string simulate = "-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies b.csv --out ";
  for (const char* name : {"w.trc", "w.bvh", "w"})
    expect_error(d.run(simulate + name), 1,
                 std::string(name) + ": expected a .h5 or .hdf5 file name (an HDF5 dataset is written), found " +
                     (std::string(name) == "w" ? "no extension" : "'" + fs::path(name).extension().string() + "'"));
  ASSERT_EQ(d.run(simulate + "e.H5").status, 0);  // any case
  expect_error(d.run("merge e.H5 -o m.trc"), 1, "m.trc: expected a .h5 or .hdf5 file name");
  expect_error(d.run("render e.H5 -s p1_walking_t1__b1 -o f.svg"), 1,
               "f.svg: expected a .png or .gif file name (a PNG strip or a GIF animation is written), found '.svg'");
  for (const char* name : {"b.trc", "w.trc", "w.bvh", "w", "m.trc", "f.svg"}) EXPECT_FALSE(d.exists(name)) << name;
}

TEST(CliGaitInputs, OneRuleForTheContactThreshold) {
  Dir d;
  d.write("b.csv", "id,sex,height_cm,weight_kg\nb1,female,160,55\n");
  ASSERT_EQ(d.run("-q simulate --embedded --performers 1 --takes 1 --seconds 2 --bodies b.csv --out e.h5").status, 0);
  // Before: nan exited 1 (the library's check), inf 2 (CLI11's Range).
  for (const char* v : {"nan", "inf", "-1", "2e6"})
    expect_error(d.run(std::string("forces e.h5 --out f --contact ") + v), 2, "--contact");
  EXPECT_FALSE(d.exists("f"));
}

// Before: plates on another clock or negated exited 0 with an empty table;
// +1 s gave figures without a word; a BOM before endheader was refused; a
// FIFO was "not found"; marker_map was read from the current folder.
TEST(CliGaitInputs, PhysicsBenchComparesSomethingOrSaysWhyNot) {
  Dir d;
  d.write("late.mot", walk_plates(100, false));
  walk_csv(d, "late.csv", "late.mot");
  expect_error(d.run("-q physics-bench --trials late.csv --out late"), 1,
               "late.mot: trial 'w': no plate sample within the markers' ");
  d.write("neg.mot", walk_plates(0, true));
  walk_csv(d, "neg.csv", "neg.mot");
  expect_error(d.run("-q physics-bench --trials neg.csv --out neg"), 1,
               "neg.mot: trial 'w': the vertical force is below zero in");
  d.write("mm.mot", walk_plates(0, false, false, true));
  walk_csv(d, "mm.csv", "mm.mot");
  expect_error(d.run("-q physics-bench --trials mm.csv --out mm"), 1,
               "mm.mot: trial 'w': the plates' centres of pressure are within 0.15 m of a foot for 0 % of their load");
  EXPECT_FALSE(d.exists("late") || d.exists("neg") || d.exists("mm"));
  d.write("shift.mot", walk_plates(1, false));
  walk_csv(d, "shift.csv", "shift.mot");
  const RunResult shift = d.run("-q physics-bench --trials shift.csv --out shift");
  EXPECT_EQ(shift.status, 0) << shift.err;
  EXPECT_NE(shift.err.find("physics-bench: warning: shift.mot: trial 'w': the plates cover 60 % of the 151 frames"),
            std::string::npos)
      << shift.err;
  d.write("bom.mot", walk_plates(0, false, true));
  walk_csv(d, "bom.csv", "bom.mot");
  const RunResult bom = d.run("-q physics-bench --trials bom.csv --out bom");
  EXPECT_EQ(bom.status, 0) << bom.err;
  EXPECT_EQ(bom.err, "");
  ASSERT_EQ(::mkfifo((d.path / "work" / "fifo.mot").c_str(), 0600), 0);
  walk_csv(d, "fifo.csv", "fifo.mot");
  expect_error(d.run("-q physics-bench --trials fifo.csv --out fifo"), 1,
               "fifo.csv:2: plates 'fifo.mot': is a FIFO, expected a regular file");
  // A map file beside the trials CSV, the bench run from another folder.
  d.write("lab/trials.csv", std::string("trial,markers,static,plates,sex,height_cm,weight_kg,marker_map\nw,") + kGait +
                                "/walk.trc," + kGait + "/walk_static.trc," + kGait + "/walk_grf.mot,male,175.0,70.0,lab.map\n");
  d.write("lab/lab.map", slurp(std::string(PTNET_SOURCE_DIR) + "/src/motion/markers/delaware.map"));
  const RunResult map = d.run("-q physics-bench --trials lab/trials.csv --out map");
  EXPECT_EQ(map.status, 0) << map.err;
}

// Before: a marker_map that is no file on row 3 of a trials CSV failed only
// after row 2's trial was simulated, and its message lacked "t.csv:3"; a
// clips CSV's static or marker_map likewise failed when its clip was read.
// Now each is checked at its line before any work.
TEST(CliGaitInputs, MarkerMapsAndStaticTrialsAreCheckedAtTheirLine) {
  Dir d;
  d.write("t.csv", std::string("trial,markers,static,plates,sex,height_cm,weight_kg,marker_map\nw,") + kGait +
                       "/walk.trc," + kGait + "/walk_static.trc," + kGait + "/walk_grf.mot,male,175.0,70.0,delaware\n" +
                       "v," + kGait + "/walk.trc,," + kGait + "/walk_grf.mot,male,175.0,70.0,nosuch.map\n");
  expect_error(d.run("-q physics-bench --trials t.csv --out pb"), 1,
               "t.csv:3: marker_map 'nosuch.map': no such file (shipped maps: common, delaware, plugin-gait)");
  EXPECT_FALSE(d.exists("pb"));
  d.write("b.csv", "id,sex,height_cm,weight_kg\nb1,female,160,55\n");
  const std::string header = "file,subject,category,take,marker_map,static\n", clip = kGait + "/walk.trc,s1,walking,";
  d.write("c.csv", header + clip + "1,delaware," + kGait + "/walk_static.trc\n" + clip + "2,delaware,nosuch.trc\n");
  expect_error(d.run("-q simulate --clips c.csv --bodies b.csv --out c.h5"), 1, "c.csv:3: static 'nosuch.trc': no such file");
  d.write("m.csv", header + clip + "1,nosuch.map,\n");
  expect_error(d.run("-q simulate --clips m.csv --bodies b.csv --out m.h5"), 1, "m.csv:2: marker_map 'nosuch.map': no such file");
  EXPECT_FALSE(d.exists("c.h5") || d.exists("m.h5"));
}

// Before: the .trc units error said "pass --units" from physics-bench and
// `motions --from`, neither of which had such an option. physics-bench
// takes a units column (and says so), motions --from takes --units.
TEST(CliGaitInputs, TheMarkersUnitCanBeGivenWhereverTheErrorAsksForIt) {
  Dir d;
  const std::string row = std::string("w,") + kGait + "/walk.trc," + kGait + "/walk_static.trc," + kGait +
                          "/walk_grf.mot,male,175.0,70.0,";
  d.write("m.csv", std::string(kHeader).substr(0, std::string(kHeader).size() - 1) + ",units\n" + row + "m\n");
  expect_error(d.run("-q physics-bench --trials m.csv --out m"), 1, "apart in the unit given (the trials CSV's units column), expected a pelvis [0.15, 0.4] m wide; "
               "the values fit mm: pass the trials CSV's units column");
  EXPECT_FALSE(d.exists("m"));
  d.write("mm.csv", std::string(kHeader).substr(0, std::string(kHeader).size() - 1) + ",units\n" + row + "mm\n");
  const RunResult mm = d.run("-q physics-bench --trials mm.csv --out mm");
  EXPECT_EQ(mm.status, 0) << mm.err;
  const std::string from = "motions --from " + kGait + "/walk.trc --static " + kGait + "/walk_static.trc ";
  expect_error(d.run(from + "--units m --out m.bvh"), 1, "apart in the unit given (--units), expected a pelvis");
  EXPECT_EQ(d.run("-q " + from + "--units mm --out mm.bvh").status, 0);
  expect_error(d.run("motions --category walking --units m --out g.bvh"), 2, "--units");
  EXPECT_FALSE(d.exists("m.bvh") || d.exists("g.bvh"));
}
