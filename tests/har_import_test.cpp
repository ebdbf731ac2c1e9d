// ptnet import: recordings listed in a manifest become a dataset.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "ptnet/har.hpp"
#include "ptnet/npy.hpp"

namespace fs = std::filesystem;
using namespace ptnet;

namespace {
struct Folder {
  fs::path dir;
  explicit Folder(const std::string& name) : dir(fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Folder() { fs::remove_all(dir); }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
  }
};
}  // namespace

TEST(HarImport, CsvAndNpyRecordingsBecomeSubjects) {
  Folder f("ptnet_har_import_ok");
  // 2 x 3 mat: s1 walks (2 CSV frames), s2 stands (a 3-frame .npy).
  f.write("walk.csv", "1,2,3,4,5,6\n0,0,0,0,0,7.5\n");
  PressureSequence stand(MatSpec{2, 3, 0.05}, 3, 50);
  stand.at(2, 1, 2) = 9;
  write_npy_sequence((f.dir / "stand.npy").string(), stand, true);
  f.write("m.csv",
          "subject,sex,height_cm,weight_kg,file,category\n"
          "s1,female,160,55,walk.csv,walking\n"
          "s2,m,182.5,90,stand.npy,rom\n");
  har::ImportOptions o;
  o.mat = MatSpec{2, 3, 0.05};
  o.fps = 50;
  const std::string out = (f.dir / "real.h5").string();
  har::import_recordings((f.dir / "m.csv").string(), out, o, false);
  const Dataset d = Dataset::open(out);
  ASSERT_EQ(d.bodies().size(), 2u);
  EXPECT_EQ(d.body("s2").sex, Sex::male);
  EXPECT_EQ(d.body("s2").height_cm, 182.5);
  EXPECT_EQ(d.body("s1").role, "original");
  EXPECT_EQ(d.info().fps, 50);
  const SequenceMeta& w = d.sequence("walk__s1");
  EXPECT_EQ(w.frames, 2);
  EXPECT_EQ(w.category, "walking");
  EXPECT_EQ(d.read("walk__s1").at(1, 1, 2), 7.5f);
  EXPECT_EQ(d.read("stand__s2").at(2, 1, 2), 9.0f);
  EXPECT_THROW(har::import_recordings((f.dir / "m.csv").string(), out, o, false), Error);  // exists
}

TEST(HarImport, BadManifestLinesNameFileAndLine) {
  Folder f("ptnet_har_import_bad");
  f.write("a.csv", "1,2,3,4,5,6\n");
  const std::string m = (f.dir / "m.csv").string(), out = (f.dir / "x.h5").string();
  har::ImportOptions o;
  o.mat = MatSpec{2, 3, 0.05};
  auto message = [&](const std::string& manifest) {
    f.write("m.csv", manifest);
    try {
      har::import_recordings(m, out, o, true);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("subject,sex,height_cm,weight_kg,file\ns1,x,160,55,a.csv\n"),
            m + ":2: expected sex female or male, found 'x'");
  EXPECT_EQ(message("subject,sex,height_cm,weight_kg,file\ns1,f,160,55\n"),
            m + ":2: expected 5 fields (as the header), found 4");
  EXPECT_EQ(message("subject,sex,height_cm,weight_kg,file\ns1,f,160,55,a.csv\ns1,f,170,55,a.csv\n"),
            m + ":3: expected the attributes given before for subject s1, found different ones");
  f.write("b.csv", "1,2,3\n");
  EXPECT_EQ(message("subject,sex,height_cm,weight_kg,file\ns1,f,160,55,b.csv\n"),
            (f.dir / "b.csv").string() + ":1: expected 6 values (2 x 3), found 3");
}

// The dataset's config names the manifest: valid JSON whatever the name
// holds (quotes, backslashes, a name that reads like more keys).
TEST(HarImport, ConfigIsJsonWhateverTheManifestName) {
  Folder f("ptnet_har_import_names");
  f.write("a.csv", "1,2,3,4,5,6\n");
  har::ImportOptions o;
  o.mat = MatSpec{2, 3, 0.05};
  int i = 0;
  for (const std::string name : {"m\"q\\.csv", "x\", \"shard\": \"0\", \"y\": \"z.csv"}) {
    f.write(name, "subject,sex,height_cm,weight_kg,file\ns1,f,160,55,a.csv\n");
    const std::string out = (f.dir / ("out" + std::to_string(i++) + ".h5")).string();
    har::import_recordings((f.dir / name).string(), out, o, false);
    nlohmann::json config;
    ASSERT_NO_THROW(config = nlohmann::json::parse(Dataset::open(out).info().config_json)) << name;
    EXPECT_EQ(config, (nlohmann::json{{"manifest", name}})) << config.dump();
  }
}
