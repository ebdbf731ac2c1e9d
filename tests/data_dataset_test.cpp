// Dataset file: round trip, partial reads, attributes, atomic writes, and the
// one-line error for every way a file can be wrong.
#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "ptnet/error.hpp"
#include "support/synthetic_walk.hpp"

namespace ptnet {
namespace {
using testing_util::TempDir;

using testing_util::error_of;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(Dataset, RoundTripIsBitExact) {
  TempDir dir("ds_roundtrip");
  const auto path = dir.file("data.h5");
  DatasetInfo info;
  info.fps = 30;
  info.generator = "ptnet test";
  info.config_json = R"({"seed": 7})";
  auto bodies = testing_util::two_bodies();
  std::vector<std::pair<SequenceMeta, PressureSequence>> written;
  {
    DatasetWriter w(path, info, bodies, false);
    int frames[] = {70, 5, 33};
    for (int i = 0; i < 3; ++i) {
      auto m = testing_util::meta_for("m" + std::to_string(i), bodies[i % 2].id, 1 + i % 2,
                                      i == 2 ? "rom" : "walking");
      auto s = synthetic_walk(info.mat, frames[i], info.fps, bodies[i % 2].height_cm,
                              bodies[i % 2].weight_kg, 100 + i);
      s.kpa[3] = 1.0e-7f;  // denormal-ish and exact values survive
      s.kpa[4] = 123456.75f;
      w.add(m, s);
      written.emplace_back(m, s);
    }
    w.commit();
  }
  Dataset d = Dataset::open(path);
  EXPECT_EQ(d.path(), path);
  EXPECT_EQ(d.info().mat, MatSpec{});
  EXPECT_EQ(d.info().fps, 30);
  EXPECT_EQ(d.info().generator, "ptnet test");
  EXPECT_EQ(d.info().config_json, R"({"seed": 7})");
  ASSERT_EQ(d.bodies().size(), 2u);
  EXPECT_EQ(d.body("b2").sex, Sex::male);
  EXPECT_EQ(d.body("b2").height_cm, 186);
  EXPECT_EQ(d.body("b2").weight_kg, 94);
  EXPECT_EQ(d.body("b2").role, "original");
  EXPECT_EQ(d.body("b1").sex, Sex::female);
  ASSERT_EQ(d.sequences().size(), 3u);
  for (const auto& [m, s] : written) {
    const SequenceMeta& r = d.sequence(m.name);
    EXPECT_EQ(r.body_id, m.body_id);
    EXPECT_EQ(r.motion_id, m.motion_id);
    EXPECT_EQ(r.performer, m.performer);
    EXPECT_EQ(r.category, m.category);
    EXPECT_EQ(r.take, m.take);
    EXPECT_EQ(r.source, m.source);
    EXPECT_EQ(r.frames, s.frames());
    PressureSequence back = d.read(m.name);
    ASSERT_EQ(back.kpa.size(), s.kpa.size());
    EXPECT_EQ(std::memcmp(back.kpa.data(), s.kpa.data(), s.kpa.size() * 4), 0) << m.name;
    EXPECT_EQ(back.fps, 30);
  }
  EXPECT_EQ(error_of([&] { d.body("nobody"); }), path + ": no body 'nobody'");
  EXPECT_EQ(error_of([&] { d.sequence("nope"); }),
            path + ": no sequence 'nope' (e.g. 'm0__b1'; `ptnet info` lists them)");
}

TEST(Dataset, PartialReadsMatchTheWholeSequence) {
  TempDir dir("ds_partial");
  const auto path = dir.file("data.h5");
  testing_util::write_small_dataset(path, 100, 5);
  Dataset d = Dataset::open(path);
  PressureSequence whole = d.read("walk_a__b1");
  const int cells = whole.mat.cells();
  std::vector<float> window(30 * cells);
  for (int start : {0, 17, 31, 32, 63, 70}) {
    d.read("walk_a__b1", start, 30, window.data());
    EXPECT_EQ(std::memcmp(window.data(), whole.frame(start), window.size() * 4), 0) << start;
  }
  // Interleaved sequences (handle cache) still give the right data.
  PressureSequence other = d.read("walk_a__b2");
  d.read("walk_a__b1", 5, 30, window.data());
  EXPECT_EQ(std::memcmp(window.data(), whole.frame(5), window.size() * 4), 0);
  d.read("walk_a__b2", 5, 30, window.data());
  EXPECT_EQ(std::memcmp(window.data(), other.frame(5), window.size() * 4), 0);
  EXPECT_EQ(error_of([&] { d.read("walk_a__b1", 80, 30, window.data()); }),
            path + ": sequence 'walk_a__b1': frames [80, 110) outside its 100 frames");
  EXPECT_EQ(error_of([&] { d.read("walk_a__b1", -1, 3, window.data()); }),
            path + ": sequence 'walk_a__b1': frames [-1, 2) outside its 100 frames");
  d.read("walk_a__b1", 100, 0, window.data());  // empty range at the end is fine
}

TEST(Dataset, FileLayoutAttributesAndCompression) {
  TempDir dir("ds_layout");
  const auto path = dir.file("data.h5");
  testing_util::write_small_dataset(path, 70, 5);
  H5::H5File f(path, H5F_ACC_RDONLY);
  H5::Group root = f.openGroup("/");
  auto str_attr = [](const H5::H5Object& o, const char* name) {
    H5::Attribute a = o.openAttribute(name);
    std::string s;
    a.read(a.getStrType(), s);
    return s;
  };
  auto int_attr = [](const H5::H5Object& o, const char* name) {
    int v = 0;
    o.openAttribute(name).read(H5::PredType::NATIVE_INT, &v);
    return v;
  };
  EXPECT_EQ(str_attr(root, "format"), "ptnet-dataset");
  EXPECT_EQ(int_attr(root, "version"), 1);
  EXPECT_EQ(int_attr(root, "rows"), 80);
  EXPECT_EQ(int_attr(root, "cols"), 28);
  EXPECT_EQ(str_attr(root, "units"), "kPa");
  EXPECT_EQ(str_attr(root, "config"), R"({"seed": 7})");
  H5::DataSet ds = f.openDataSet("sequences/walk_a__b2");
  EXPECT_EQ(str_attr(ds, "body_id"), "b2");
  EXPECT_EQ(str_attr(ds, "motion_id"), "walk_a");
  EXPECT_EQ(str_attr(ds, "category"), "walking");
  EXPECT_EQ(int_attr(ds, "take"), 1);
  EXPECT_TRUE(ds.openAttribute("body_id").getStrType().isVariableStr());
  EXPECT_EQ(ds.openAttribute("body_id").getStrType().getCset(), H5T_CSET_UTF8);
  H5::DSetCreatPropList plist = ds.getCreatePlist();
  ASSERT_EQ(plist.getLayout(), H5D_CHUNKED);
  hsize_t chunk[3];
  plist.getChunk(3, chunk);
  EXPECT_EQ(chunk[0], 32u);
  EXPECT_EQ(chunk[1], 80u);
  EXPECT_EQ(chunk[2], 28u);
  std::vector<H5Z_filter_t> filters;
  for (int i = 0; i < plist.getNfilters(); ++i) {
    unsigned flags;
    size_t n = 0;
    char name[32];
    unsigned config;
    filters.push_back(plist.getFilter(i, flags, n, nullptr, sizeof name, name, config));
  }
  EXPECT_EQ(filters, (std::vector<H5Z_filter_t>{H5Z_FILTER_DEFLATE}));  // any reader inflates it
  // Short sequences get a chunk as long as themselves.
  f.openDataSet("sequences/walk_b__b1").getCreatePlist().getChunk(3, chunk);
  EXPECT_EQ(chunk[0], 5u);
  // Sparse pressure compresses well.
  hsize_t stored = ds.getStorageSize();
  EXPECT_LT(stored * 4, 70u * 80 * 28 * 4);
  // The bodies table is a compound with the documented fields.
  H5::CompType bt = f.openDataSet("bodies").getCompType();
  ASSERT_EQ(bt.getNmembers(), 5);
  EXPECT_EQ(bt.getMemberName(0), "id");
  EXPECT_EQ(bt.getMemberName(1), "sex");
  EXPECT_EQ(bt.getMemberName(2), "height_cm");
  EXPECT_EQ(bt.getMemberName(3), "weight_kg");
  EXPECT_EQ(bt.getMemberName(4), "role");
}

// Each sequence's chunks are deflated by libdeflate and written with
// H5Dwrite_chunk: at every level, HDF5's own deflate filter (the one h5py and
// h5dump use) must give back the exact floats, the edge chunk included.
TEST(Dataset, EveryCompressionLevelReadsBackBitExactThroughHdf5sDeflate) {
  TempDir dir("ds_levels");
  auto bodies = testing_util::two_bodies();
  for (int level : {0, 1, 4, 6, 9}) {
    const auto path = dir.file("l" + std::to_string(level) + ".h5");
    DatasetInfo info;
    info.compression = level;
    std::vector<PressureSequence> written;
    const int frames[] = {70, 5, 32, 65};  // edge chunks of 6, 5 (whole), none, 1
    {
      DatasetWriter w(path, info, bodies, false);
      for (int i = 0; i < 4; ++i) {
        auto s = synthetic_walk(info.mat, frames[i], info.fps, 170, 70, 7 + i);
        s.kpa[5] = -0.0f;  // sign of zero, tiny and odd values survive
        s.kpa[6] = 1.0e-40f;
        s.kpa.back() = 3.25f;  // the last frame is not padding
        w.add(testing_util::meta_for("m" + std::to_string(i), "b1"), s);
        written.push_back(std::move(s));
      }
      w.commit();
    }
    Dataset d = Dataset::open(path);
    H5::H5File f(path, H5F_ACC_RDONLY);
    for (int i = 0; i < 4; ++i) {
      const std::string name = "m" + std::to_string(i) + "__b1";
      const PressureSequence& s = written[std::size_t(i)];
      PressureSequence back = d.read(name);
      ASSERT_EQ(back.kpa.size(), s.kpa.size());
      EXPECT_EQ(std::memcmp(back.kpa.data(), s.kpa.data(), s.kpa.size() * 4), 0) << level << " " << name;
      H5::DataSet ds = f.openDataSet("sequences/" + name);
      std::vector<float> raw(s.kpa.size());  // HDF5's plain read path
      ds.read(raw.data(), H5::PredType::NATIVE_FLOAT);
      EXPECT_EQ(std::memcmp(raw.data(), s.kpa.data(), s.kpa.size() * 4), 0) << level << " " << name;
      H5::DSetCreatPropList plist = ds.getCreatePlist();
      if (level == 0) {
        EXPECT_EQ(plist.getNfilters(), 0) << name;
        continue;
      }
      ASSERT_EQ(plist.getNfilters(), 1) << name;
      unsigned flags = 0, config = 0, cd[4] = {};
      size_t n = 4;
      char filter_name[32];
      EXPECT_EQ(plist.getFilter(0, flags, n, cd, sizeof filter_name, filter_name, config), H5Z_FILTER_DEFLATE);
      EXPECT_EQ(cd[0], unsigned(level)) << name;  // h5py's compression_opts
      const hsize_t last[3] = {hsize_t((frames[i] - 1) / 32 * 32), 0, 0};
      uint32_t mask = 99;
      hsize_t stored = 0;
      std::vector<unsigned char> chunk(32 * 80 * 28 * 4 + 1024);
      ASSERT_GE(H5Dget_chunk_storage_size(ds.getId(), last, &stored), 0);
      ASSERT_GE(H5Dread_chunk(ds.getId(), H5P_DEFAULT, last, &mask, chunk.data()), 0);
      EXPECT_EQ(mask, 0u) << name;  // the deflate filter applies to every chunk
      EXPECT_LT(stored, hsize_t(std::min(frames[i], 32)) * 80 * 28 * 4) << name;
    }
  }
}

TEST(Dataset, SameInputSameBytes) {
  TempDir dir("ds_bytes");
  testing_util::write_small_dataset(dir.file("a.h5"));
  testing_util::write_small_dataset(dir.file("b.h5"));
  std::string a = slurp(dir.file("a.h5")), b = slurp(dir.file("b.h5"));
  EXPECT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "two writes of the same data differ (timestamps in the file?)";
}

TEST(Dataset, RefusesToOverwriteWithoutForce) {
  TempDir dir("ds_force");
  const auto path = dir.file("data.h5");
  testing_util::write_small_dataset(path);
  auto before = slurp(path);
  EXPECT_EQ(error_of([&] { testing_util::write_small_dataset(path); }),
            path + ": exists; pass force to overwrite");
  EXPECT_EQ(slurp(path), before);
  testing_util::write_small_dataset(path, 40, 6, /*force=*/true);
  EXPECT_EQ(Dataset::open(path).sequence("walk_a__b1").frames, 40);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"data.h5"});
}

TEST(Dataset, FailureBeforeCommitLeavesNothing) {
  TempDir dir("ds_atomic");
  const auto path = dir.file("data.h5");
  try {
    DatasetInfo info;
    DatasetWriter w(path, info, testing_util::two_bodies(), false);
    w.add(testing_util::meta_for("walk", "b1"), synthetic_walk(info.mat, 40, 30, 158, 52, 1));
    EXPECT_EQ(dir.entries().size(), 1u);  // the temporary file, hidden
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(dir.entries().empty());
  // Without commit() nothing appears either.
  {
    DatasetInfo info;
    DatasetWriter w(path, info, testing_util::two_bodies(), false);
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(Dataset, WriterValidatesWhatItIsGiven) {
  TempDir dir("ds_writer_checks");
  const auto path = dir.file("data.h5");
  DatasetInfo info;
  DatasetWriter w(path, info, testing_util::two_bodies(), false);
  auto good = synthetic_walk(info.mat, 10, 30, 158, 52, 1);
  EXPECT_EQ(error_of([&] { w.add(testing_util::meta_for("walk", "b9"), good); }),
            path + ": sequence 'walk__b9': body_id 'b9' not in the bodies table");
  MatSpec small{40, 28, 0.02};
  EXPECT_EQ(error_of([&] { w.add(testing_util::meta_for("walk", "b1"), synthetic_walk(small, 10, 30, 158, 52, 1)); }),
            path + ": sequence 'walk__b1': mat 40 x 28 differs from the dataset's 80 x 28");
  auto bad = good;
  bad.at(3, 4, 5) = std::nanf("");
  EXPECT_EQ(error_of([&] { w.add(testing_util::meta_for("walk", "b1"), bad); }),
            path + ": sequence 'walk__b1': non-finite value at frame 3 row 4 col 5");
  auto m = testing_util::meta_for("walk", "b1");
  m.name = "a/b";
  EXPECT_EQ(error_of([&] { w.add(m, good); }), path + ": invalid sequence name 'a/b': it holds '/'");
  w.add(testing_util::meta_for("walk", "b1"), good);
  EXPECT_EQ(error_of([&] { w.add(testing_util::meta_for("walk", "b1"), good); }),
            path + ": sequence 'walk__b1' added twice");
  auto bodies = testing_util::two_bodies();
  bodies[1].id = "b1";
  EXPECT_EQ(error_of([&] { DatasetWriter(dir.file("x.h5"), info, bodies, false); }),
            dir.file("x.h5") + ": body id 'b1' appears twice");
  bodies[1] = BodySpec{"b3", Sex::male, 260, 80};
  EXPECT_EQ(error_of([&] { DatasetWriter(dir.file("x.h5"), info, bodies, false); }),
            dir.file("x.h5") + ": body 'b3': height_cm 260 outside 100-230");
}

// --- Files that are wrong in one way each ---------------------------------

class BadFiles : public ::testing::Test {
 protected:
  TempDir dir{"ds_bad"};
  std::string good = dir.file("good.h5");
  void SetUp() override { testing_util::write_small_dataset(good, 40, 5); }
  std::string copy_as(const std::string& name, size_t bytes = size_t(-1)) {
    std::string data = slurp(good);
    std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary).write(data.data(), std::min(bytes, data.size()));
    return path;
  }
  std::string open_error(const std::string& path) {
    return error_of([&] { Dataset::open(path); });
  }
};

TEST_F(BadFiles, MissingFile) {
  EXPECT_EQ(open_error(dir.file("absent.h5")), dir.file("absent.h5") + ": no such file");
}

TEST_F(BadFiles, NotAnHdf5File) {
  const auto path = dir.file("notes.h5");
  std::ofstream(path) << "id,sex,height_cm,weight_kg\nb1,female,160,60\n";
  EXPECT_EQ(open_error(path), path + ": not an HDF5 file (no HDF5 signature)");
}

TEST_F(BadFiles, TruncatedFile) {
  const size_t size = slurp(good).size();
  const auto path = copy_as("half.h5", size / 2);
  EXPECT_EQ(open_error(path), path + ": truncated HDF5 file (" + std::to_string(size / 2) +
                                  " bytes; the end of the file is missing)");
}

TEST_F(BadFiles, ForeignHdf5WithoutFormat) {
  const auto path = dir.file("foreign.h5");
  {
    H5::H5File f(path, H5F_ACC_TRUNC);
    hsize_t dims[2] = {4, 4};
    std::vector<float> zeros(16, 0.0f);
    f.createDataSet("images", H5::PredType::IEEE_F32LE, H5::DataSpace(2, dims))
        .write(zeros.data(), H5::PredType::NATIVE_FLOAT);
  }
  EXPECT_EQ(open_error(path), path + ": not a ptnet dataset (HDF5 file without a 'format' attribute)");
}

TEST_F(BadFiles, ForeignHdf5WithOtherFormat) {
  const auto path = copy_as("other.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    H5::Group root = f.openGroup("/");
    root.removeAttr("format");
    H5::StrType t(H5::PredType::C_S1, H5T_VARIABLE);
    root.createAttribute("format", t, H5::DataSpace(H5S_SCALAR)).write(t, std::string("keras"));
  }
  EXPECT_EQ(open_error(path), path + ": not a ptnet dataset (format 'keras', expected 'ptnet-dataset')");
}

TEST_F(BadFiles, WrongVersion) {
  const auto path = copy_as("v2.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    int two = 2;
    f.openGroup("/").openAttribute("version").write(H5::PredType::NATIVE_INT, &two);
  }
  EXPECT_EQ(open_error(path), path + ": unsupported dataset version 2 (this ptnet reads version 1)");
}

TEST_F(BadFiles, ShapeMismatch) {
  const auto path = copy_as("shape.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    int cols = 30;
    f.openGroup("/").openAttribute("cols").write(H5::PredType::NATIVE_INT, &cols);
  }
  EXPECT_EQ(open_error(path), path + ": sequence 'walk_a__b1' has shape [40, 80, 28], expected "
                                     "[T, 80, 30] (root attributes rows, cols)");
}

TEST_F(BadFiles, MissingAttribute) {
  const auto path = copy_as("noattr.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    f.openGroup("/").removeAttr("fps");
  }
  EXPECT_EQ(open_error(path), path + ": root group: missing attribute 'fps'");
}

TEST_F(BadFiles, UnknownBody) {
  const auto path = copy_as("nobody.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    H5::DataSet ds = f.openDataSet("sequences/walk_b__b2");
    ds.removeAttr("body_id");
    H5::StrType t(H5::PredType::C_S1, H5T_VARIABLE);
    ds.createAttribute("body_id", t, H5::DataSpace(H5S_SCALAR)).write(t, std::string("b7"));
  }
  EXPECT_EQ(open_error(path), path + ": sequence 'walk_b__b2': body_id 'b7' not in /bodies");
}

TEST_F(BadFiles, NanIsCaughtOnRead) {
  const auto path = copy_as("nan.h5");
  {
    H5::H5File f(path, H5F_ACC_RDWR);
    H5::DataSet ds = f.openDataSet("sequences/walk_a__b1");
    H5::DataSpace fs = ds.getSpace();
    hsize_t offset[3] = {12, 40, 10}, count[3] = {1, 1, 1};
    fs.selectHyperslab(H5S_SELECT_SET, count, offset);
    float nan = std::nanf("");
    ds.write(&nan, H5::PredType::NATIVE_FLOAT, H5::DataSpace(3, count), fs);
  }
  Dataset d = Dataset::open(path);  // opening does not read the frames
  std::vector<float> buf(30 * 80 * 28);
  d.read("walk_a__b1", 0, 10, buf.data());  // frames before the NaN are fine
  EXPECT_EQ(error_of([&] { d.read("walk_a__b1", 0, 30, buf.data()); }),
            path + ": sequence 'walk_a__b1': non-finite value (NaN or Inf) in frame 12");
}

// --- The standard tools read it -------------------------------------------

int run(const std::string& command, std::string* out) {
  FILE* p = popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out->append(buf, n);
  int status = pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(DatasetTools, H5lsAndH5dumpOpenIt) {
  std::string out;
  if (run("command -v h5dump && command -v h5ls", &out) != 0)
    GTEST_SKIP() << "h5dump/h5ls not installed (Debian package hdf5-tools)";
  TempDir dir("ds_h5dump");
  const auto path = dir.file("data.h5");
  testing_util::write_small_dataset(path, 40, 5);
  out.clear();
  ASSERT_EQ(run("h5ls -r '" + path + "'", &out), 0) << out;
  std::string squeezed;  // h5ls pads names with spaces
  for (char c : out)
    if (!(c == ' ' && !squeezed.empty() && squeezed.back() == ' ')) squeezed += c;
  EXPECT_NE(squeezed.find("/sequences/walk_a__b1 Dataset {40, 80, 28}"), std::string::npos) << out;
  EXPECT_NE(squeezed.find("/bodies Dataset {2}"), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(run("h5dump -a /format '" + path + "'", &out), 0) << out;
  EXPECT_NE(out.find("\"ptnet-dataset\""), std::string::npos) << out;
  out.clear();
  ASSERT_EQ(run("h5dump -d /bodies '" + path + "'", &out), 0) << out;
  EXPECT_NE(out.find("\"b2\""), std::string::npos) << out;
  EXPECT_NE(out.find("186"), std::string::npos) << out;
}

TEST(DatasetTools, H5pyReadsItAsDocumented) {
  std::string out;
  if (run("/usr/bin/python3 -c 'import h5py'", &out) != 0)
    GTEST_SKIP() << "/usr/bin/python3 with h5py not found (Debian package python3-h5py)";
  TempDir dir("ds_h5py");
  const auto path = dir.file("data.h5");
  testing_util::write_small_dataset(path, 40, 5);
  PressureSequence seq = Dataset::open(path).read("walk_a__b2");
  double sum = 0;
  for (float v : seq.kpa) sum += v;
  // The snippet of docs/formats.md, plus checks.
  const std::string script = dir.file("read.py");
  std::ofstream(script) << R"(import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
seq = f["sequences/walk_a__b2"]
kpa = seq[:]                                    # float32 [T, rows, cols], kPa
assert seq.compression == "gzip" and not seq.shuffle, (seq.compression, seq.shuffle)
open(sys.argv[2], "wb").write(kpa.tobytes())
bodies = f["bodies"][:]                         # numpy structured array
body = bodies[bodies["id"] == seq.attrs["body_id"].encode()][0]
assert f.attrs["format"] == "ptnet-dataset" and isinstance(seq.attrs["category"], str)
assert kpa.dtype == np.float32 and kpa.shape == (40, f.attrs["rows"], f.attrs["cols"])
print(body["id"].decode(), int(body["sex"]), float(body["height_cm"]), float(body["weight_kg"]),
      body["role"].decode(), "%.3f" % kpa.astype(np.float64).sum(), seq.attrs["take"])
)";
  out.clear();
  ASSERT_EQ(run("/usr/bin/python3 '" + script + "' '" + path + "' '" + dir.file("kpa.raw") + "'", &out), 0)
      << out;
  const std::string bytes = slurp(dir.file("kpa.raw"));  // h5py's floats, bit for bit
  ASSERT_EQ(bytes.size(), seq.kpa.size() * 4);
  EXPECT_EQ(std::memcmp(bytes.data(), seq.kpa.data(), bytes.size()), 0);
  char expected[128];
  std::snprintf(expected, sizeof expected, "b2 1 186.0 94.0 original %.3f 1\n", sum);
  EXPECT_EQ(out, expected);
}

}  // namespace
}  // namespace ptnet
