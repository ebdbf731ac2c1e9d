// C3D files in: every number format (Intel, DEC, MIPS) and both point
// storages written by the test's own writer (tests/support/c3d_writer) and
// read back field by field; the labels' rules; markers through load_motion
// as a .trc file gives them; malformed files, each one line; then the C3D
// files of ../shared/c3d (skipped when absent): every file loads, and
// JA1Gait35.c3d's markers meet their OpenSim export JA1Gait35.trc.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "motion/c3d_internal.hpp"
#include "ptnet/c3d.hpp"
#include "ptnet/error.hpp"
#include "ptnet/markers.hpp"
#include "support/c3d_writer.hpp"

namespace {

using V = Eigen::Vector3d;
using ptnet::C3dFormat;
using ptnet::test::C3dImage;
using ptnet::test::C3dPlateSpec;
using ptnet::test::C3dSpec;
namespace fs = std::filesystem;

const std::string kShared = std::string(PTNET_SOURCE_DIR) + "/../shared/c3d";

std::string temp_path(const std::string& name) {
  return (fs::temp_directory_path() / ("ptnet_c3d_" + std::to_string(::getpid()) + "_" + name)).string();
}
std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string p = temp_path(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// 3 markers over 4 frames from frame 11 at 200 Hz, one invalid sample; 2
// analog channels, 2 samples a frame; a type-2 and a type-4 plate. Values
// are whole counts of 1/8 mm: exact in 16-bit integers x 0.125 and in every
// float format.
C3dSpec small_spec(C3dFormat format, bool floats) {
  C3dSpec s;
  s.format = format;
  s.floats = floats;
  s.scale = 0.125;
  s.rate_hz = 200;
  s.first_frame = 11;
  s.frames = 4;
  s.labels = {"RASI", "LASI", "SACR"};
  for (int f = 0; f < s.frames; ++f)
    for (int m = 0; m < 3; ++m) s.xyz.push_back(V(100.5 * m + f, -250.25 + 8 * f, 900 + 0.125 * m * f));
  s.xyz[1 * 3 + 2] = V::Constant(NAN);  // SACR invalid in the second frame
  s.per_frame = 2;
  s.analog_labels = {"Fz1", "EMG"};
  s.analog_units = {"N", "V"};
  s.analog_scale = {2.0, -0.25};
  s.analog_offset = {4, -2};
  s.gen_scale = 0.5;
  for (int k = 0; k < s.frames * s.per_frame; ++k) s.analog.insert(s.analog.end(), {double(100 + 3 * k), double(-7 * k)});
  C3dPlateSpec a;
  a.type = 2;
  a.corners = {V(600, 900, 0), V(0, 900, 0), V(0, 0, 0), V(600, 0, 0)};
  a.origin = V(1, -2, -40);
  a.channels = {1, 2, 1, 2, 1, 2};
  C3dPlateSpec b = a;
  b.type = 4;
  b.corners = {V(1200, 900, 0), V(600, 900, 0), V(600, 0, 0), V(1200, 0, 0)};
  for (int k = 0; k < 36; ++k) b.cal_matrix.push_back(k % 7 == 0 ? 2.5 : 0.125 * k);
  s.plates = {a, b};
  s.zero = {1, 2};
  s.company = "Test Lab";
  s.software = "c3d_writer";
  return s;
}

void expect_reads_back(const C3dSpec& s, const ptnet::C3d& c) {
  EXPECT_EQ(c.format, s.format);
  EXPECT_EQ(c.float_storage, s.floats);
  EXPECT_EQ(c.point_scale, s.floats ? -s.scale : s.scale);
  EXPECT_EQ(c.first_frame, s.first_frame);
  EXPECT_EQ(c.units, "mm");
  EXPECT_EQ(c.manufacturer, "Test Lab, c3d_writer");
  const ptnet::Trc& t = c.points;
  EXPECT_EQ(t.markers, s.labels);
  EXPECT_EQ(t.rate_hz, s.rate_hz);
  EXPECT_EQ(t.metres_per_unit, 0.001);
  ASSERT_EQ(t.frames(), s.frames);
  for (int f = 0; f < s.frames; ++f) {
    EXPECT_EQ(t.time_s[std::size_t(f)], (s.first_frame - 1 + f) / s.rate_hz);
    for (int m = 0; m < 3; ++m) {
      const V& want = s.xyz[std::size_t(f * 3 + m)];
      if (want.allFinite())
        EXPECT_EQ(t.at(f, m), want) << "frame " << f << " marker " << m;
      else
        EXPECT_TRUE(std::isnan(t.at(f, m).x()));
    }
  }
  const ptnet::C3dAnalog& a = c.analog;
  EXPECT_EQ(a.labels, s.analog_labels);
  EXPECT_EQ(a.units, s.analog_units);
  EXPECT_EQ(a.rate_hz, 400);
  EXPECT_EQ(a.per_frame, 2);
  ASSERT_EQ(a.samples(), 8);
  for (int k = 0; k < 8; ++k)
    for (int ch = 0; ch < 2; ++ch)
      EXPECT_EQ(a.value(k, ch), (s.analog[std::size_t(k * 2 + ch)] - s.analog_offset[std::size_t(ch)]) * 0.5 *
                                    s.analog_scale[std::size_t(ch)]);
  ASSERT_EQ(c.plates.size(), 2u) << c.plates_problem;
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(c.plates[i].type, s.plates[i].type);
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(c.plates[i].corners[std::size_t(k)].isApprox(s.plates[i].corners[std::size_t(k)] * 0.001, 1e-15));
    EXPECT_TRUE(c.plates[i].origin.isApprox(s.plates[i].origin * 0.001, 1e-15));
    EXPECT_EQ(c.plates[i].channels, (std::vector<int>{0, 1, 0, 1, 0, 1}));
  }
  EXPECT_TRUE(c.plates[0].cal_matrix.empty() || c.plates[0].cal_matrix[0] == 1);
  EXPECT_EQ(c.plates[1].cal_matrix, s.plates[1].cal_matrix);
  EXPECT_EQ(c.plates_zero, (std::array<int, 2>{1, 2}));
}

}  // namespace

TEST(C3d, EveryNumberFormatAndStorageReadsBackExactly) {
  for (C3dFormat format : {C3dFormat::intel, C3dFormat::dec, C3dFormat::mips})
    for (bool floats : {true, false}) {
      SCOPED_TRACE(std::string(ptnet::c3d_format_name(format)) + (floats ? " float" : " integer"));
      const C3dSpec s = small_spec(format, floats);
      const C3dImage img = ptnet::test::write_c3d(s);
      expect_reads_back(s, ptnet::parse_c3d(img.bytes, "t.c3d"));
      // And from a file, by read_c3d and read_markers.
      const std::string path = write_temp("t.c3d", img.bytes);
      expect_reads_back(s, ptnet::read_c3d(path));
      EXPECT_EQ(ptnet::read_markers(path).markers, s.labels);
      fs::remove(path);
    }
}

TEST(C3d, DecFloatsDecodeAsVaxFFloating) {
  // 1.0 is 0x4080 0x0000 in VAX F_floating (exponent 129, fraction 0).
  const unsigned char one[4] = {0x80, 0x40, 0x00, 0x00};
  EXPECT_EQ(ptnet::detail::c3d_float(one, C3dFormat::dec), 1.0);
  const unsigned char minus_half[4] = {0x00, 0xC0, 0x00, 0x00};
  EXPECT_EQ(ptnet::detail::c3d_float(minus_half, C3dFormat::dec), -0.5);
  const unsigned char reserved[4] = {0x00, 0x80, 0x00, 0x00};  // sign set, exponent 0
  EXPECT_TRUE(std::isnan(ptnet::detail::c3d_float(reserved, C3dFormat::dec)));
  for (float v : {1.0f, -3.25f, 1e-20f, 6.5e30f, 0.1f}) {
    const std::string b = ptnet::test::c3d_float_bytes(v, C3dFormat::dec);
    EXPECT_EQ(ptnet::detail::c3d_float(reinterpret_cast<const unsigned char*>(b.data()), C3dFormat::dec), double(v));
  }
}

TEST(C3d, UnsignedIntegerAnalogAndItsOffsets) {
  C3dSpec s = small_spec(C3dFormat::mips, false);
  s.unsigned_analog = true;
  s.analog_offset = {-32768, 2};  // stored as 16 bits: 32768 unsigned
  for (std::size_t k = 0; k < s.analog.size(); ++k) s.analog[k] = 40000 + double(k);
  const ptnet::C3d c = ptnet::parse_c3d(ptnet::test::write_c3d(s).bytes, "u.c3d");
  EXPECT_EQ(c.analog.value(0, 0), (40000 - 32768) * 0.5 * 2.0);
  EXPECT_EQ(c.analog.value(0, 1), (40001 - 2) * 0.5 * -0.25);
}

TEST(C3d, LabelsDropComputedPointsAndTheSubjectPrefix) {
  C3dSpec s = small_spec(C3dFormat::intel, true);
  s.labels = {"Pat:RASI", "Pat:LKneeAngles", "", "Pat:RASI"};
  s.angles = {"Pat:LKneeAngles"};
  s.label_prefix = "Pat:";
  s.xyz.clear();
  for (int f = 0; f < s.frames; ++f)
    for (int m = 0; m < 4; ++m) s.xyz.push_back(V(m + 1, f + 1, 3));
  const ptnet::C3d c = ptnet::parse_c3d(ptnet::test::write_c3d(s).bytes, "l.c3d");
  EXPECT_EQ(c.points.markers, (std::vector<std::string>{"RASI", "*2", "RASI_2"}));
  EXPECT_EQ(c.points.at(2, 2), V(4, 3, 3));  // the fourth point
}

// C3D strings are ASCII; 8-bit ones are the writers' Latin-1 and read as
// such into UTF-8 (before: a Latin-1 label became a marker name as it was,
// and `ptnet info --json` ended in nlohmann's "[json.exception.type_error.316]
// invalid UTF-8 byte").
TEST(C3d, EightBitTextIsLatin1ReadAsUtf8) {
  C3dSpec s = small_spec(C3dFormat::intel, true);
  s.labels[0] = "Genou_\xe9";
  s.analog_units[0] = "mm/s\xb2";
  const ptnet::C3d c = ptnet::parse_c3d(ptnet::test::write_c3d(s).bytes, "l.c3d");
  EXPECT_EQ(c.points.markers[0], "Genou_\xc3\xa9");
  EXPECT_EQ(c.analog.units[0], "mm/s\xc2\xb2");
  s.labels[0] = "Genou_\xc3\xa9";  // UTF-8 stays as it is
  EXPECT_EQ(ptnet::parse_c3d(ptnet::test::write_c3d(s).bytes, "l.c3d").points.markers[0], "Genou_\xc3\xa9");
}

TEST(C3d, MarkersLoadAsTheSameTrcFileGivesThem) {
  // A standing body (Delaware names, mm, Z up) carried along X: as a .trc
  // file and as a C3D file the canonical joints are the same.
  std::vector<std::string> names;
  std::vector<V> at;
  auto add = [&](const std::string& n, double x, double y, double z) { names.push_back(n), at.emplace_back(x, y, z); };
  for (int side = 0; side < 2; ++side) {
    const double k = side == 0 ? -1 : 1;  // right: -Y (Z up, facing +X)
    const std::string p = side == 0 ? "R." : "L.";
    add(p + "ASIS", 120, k * 120, 1000);
    add(p + "Knee.Lat", 40, k * 150, 520);
    add(p + "Knee.Med", 40, k * 50, 520);
    add(p + "Ankle.Lat", 0, k * 135, 80);
    add(p + "Ankle.Med", 0, k * 65, 85);
    add(p + "Heel", -60, k * 100, 40);
    add(p + "Toe.Lat", 160, k * 130, 25);
    add(p + "Toe.Med", 170, k * 70, 25);
    add(p + "Toe.Tip", 220, k * 90, 20);
    add(p + "Acromium", 0, k * 190, 1450);
  }
  add("V.Sacral", -100, 0, 1000);
  add("Sternum", 100, 0, 1350);
  add("Top.Head", 0, 0, 1750);
  C3dSpec s;
  s.labels = names;
  s.frames = 50;
  s.rate_hz = 100;
  std::ostringstream trc;
  trc << "PathFileType\t4\t(X/Y/Z)\tt.trc\nDataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\n100\t100\t50\t"
      << names.size() << "\tmm\nFrame#\tTime";
  for (const auto& n : names) trc << "\t" << n << "\t\t";
  trc << "\n\n";
  for (int f = 0; f < s.frames; ++f) {
    trc << f + 1 << "\t" << f / 100.0;
    for (const V& p : at) {
      s.xyz.push_back(p + V(4.0 * f, 0, 0));
      trc << "\t" << s.xyz.back().x() << "\t" << s.xyz.back().y() << "\t" << s.xyz.back().z();
    }
    trc << "\n";
  }
  const std::string c3d_path = write_temp("stand.C3D", ptnet::test::write_c3d(s).bytes);
  const std::string trc_path = write_temp("stand.trc", trc.str());
  ptnet::MotionOptions o;
  o.fps = 0;
  o.remove_belt = false;
  const ptnet::Motion a = ptnet::load_motion(c3d_path, o), b = ptnet::load_motion(trc_path, o);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.fps, 100);
  for (int f = 0; f < a.size(); ++f)
    for (int k = 0; k < ptnet::kJointCount; ++k)
      EXPECT_LT((a.frames[std::size_t(f)][std::size_t(k)] - b.frames[std::size_t(f)][std::size_t(k)]).norm(), 1e-9);
  fs::remove(c3d_path);
  fs::remove(trc_path);
}

namespace {

// The message of the Error parse_c3d throws on `bytes` ("" when it reads).
std::string error_of(const std::string& bytes) {
  try {
    ptnet::parse_c3d(bytes, "bad.c3d");
  } catch (const ptnet::Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}

// The byte after parameter `name`'s name in the image (its link word).
std::size_t after_name(const C3dImage& img, const std::string& name) {
  const std::size_t at = img.bytes.find(name, img.param_start);
  EXPECT_NE(at, std::string::npos) << name;
  return at + name.size();
}

void put16(std::string& b, std::size_t at, int v) {
  b[at] = char(v & 0xff);
  b[at + 1] = char((v >> 8) & 0xff);
}

}  // namespace

TEST(C3d, MalformedFilesAreOneLineErrors) {
  const C3dImage img = ptnet::test::write_c3d(small_spec(C3dFormat::intel, false));
  ASSERT_EQ(error_of(img.bytes), "");
  EXPECT_EQ(error_of(img.bytes.substr(0, 100)), "bad.c3d: expected a C3D header of 512 bytes, found 100 bytes");
  std::string b = img.bytes;
  b[1] = 0x42;
  EXPECT_EQ(error_of(b), "bad.c3d: expected a C3D file (its second byte 0x50), found byte 66 (not a C3D file?)");
  b = img.bytes;
  b[0] = char(200);
  EXPECT_NE(error_of(b).find("expected the parameter section's block (header byte 1) inside the file"), std::string::npos);
  b = img.bytes;
  b[img.param_start + 3] = char(99);
  EXPECT_EQ(error_of(b), "bad.c3d: expected the processor type 84 (Intel), 85 (DEC) or 86 (MIPS) at byte 515, found 99");
  // Truncated: the data section cut short.
  const std::string cut = img.bytes.substr(0, img.data_start + img.frame_bytes * 2 + 3);
  EXPECT_EQ(error_of(cut), "bad.c3d: expected 4 frames of " + std::to_string(img.frame_bytes) + " bytes from byte " +
                               std::to_string(img.data_start) + ", found " + std::to_string(img.frame_bytes * 2 + 3) +
                               " bytes (a truncated file?)");
  // Counts beyond the file: POINT:FRAMES 30000, then 65535 with a LONG_FRAMES-less file.
  b = img.bytes;
  put16(b, after_name(img, "FRAMES") + 4, 30000);
  EXPECT_NE(error_of(b).find("expected 30000 frames of"), std::string::npos) << error_of(b);
  // POINT:USED against the header.
  b = img.bytes;
  put16(b, after_name(img, "USED") + 4, 300);
  EXPECT_EQ(error_of(b), "bad.c3d: expected POINT:USED equal to the header's word 2, found 300 against 3");
  // No points and no analog channels: frames of nothing, however many.
  C3dSpec empty;
  empty.frames = 3;
  EXPECT_EQ(error_of(ptnet::test::write_c3d(empty).bytes),
            "bad.c3d: expected points or analog channels, found neither (POINT:USED and the analog count 0)");
  // The header's analog count not a multiple of the channels.
  b = img.bytes;
  put16(b, 4, 5);
  EXPECT_NE(error_of(b).find("ANALOG:USED channels dividing the header's 5 analog values per frame"), std::string::npos);
}

TEST(C3d, BadParameterSectionsAreOneLineErrors) {
  const C3dImage img = ptnet::test::write_c3d(small_spec(C3dFormat::intel, true));
  // A record's link pointing past the section.
  std::string b = img.bytes;
  put16(b, after_name(img, "SCALE"), 30000);
  EXPECT_NE(error_of(b).find("expected the offset of the record after 'SCALE' inside the parameter section"),
            std::string::npos)
      << error_of(b);
  EXPECT_NE(error_of(b).find("(a bad parameter section)"), std::string::npos);
  // A type that is none of -1, 1, 2, 4.
  b = img.bytes;
  b[after_name(img, "RATE") + 2] = char(3);
  EXPECT_NE(error_of(b).find("expected the type of parameter POINT:RATE (-1, 1, 2 or 4), found 3"), std::string::npos) << error_of(b);
  // Dimensions whose values run past the next record.
  b = img.bytes;
  b[after_name(img, "LABELS") + 4] = char(255);  // the label length
  EXPECT_NE(error_of(b).find("bytes of parameter POINT:LABELS before the next record"), std::string::npos) << error_of(b);
  // A parameter of group 0.
  b = img.bytes;
  const std::size_t used = after_name(img, "USED") - 4 - 2;
  b[used + 1] = char(0);
  EXPECT_NE(error_of(b).find("expected a group id of 'USED', found 0"), std::string::npos) << error_of(b);
  // A section of 0 blocks.
  b = img.bytes;
  b[img.param_start + 2] = char(0);
  EXPECT_NE(error_of(b).find("expected the parameter section's block count, found 0"), std::string::npos);
}

TEST(C3d, RandomlyDamagedFilesReadOrFailInOneLine) {
  // Never a crash, a hang or a huge allocation: every damaged copy either
  // reads or throws ptnet::Error (the fuzzer, fuzz/fuzz_c3d.cpp, goes further).
  std::mt19937 rng(7);
  for (C3dFormat format : {C3dFormat::intel, C3dFormat::dec, C3dFormat::mips}) {
    const std::string good = ptnet::test::write_c3d(small_spec(format, format != C3dFormat::dec)).bytes;
    for (int round = 0; round < 3000; ++round) {
      std::string b = good;
      const int edits = 1 + int(rng() % 4);
      for (int e = 0; e < edits; ++e) b[rng() % b.size()] = char(rng());
      if (rng() % 4 == 0) b.resize(rng() % b.size());
      try {
        const ptnet::C3d c = ptnet::parse_c3d(b, "fuzz.c3d");
        EXPECT_LE(c.points.xyz.size() * sizeof(V), 64 * b.size() + 4096);
      } catch (const ptnet::Error&) {
      }
    }
  }
}

TEST(C3d, LoadMotionRefusesMarkersItCannotPlaceByName) {
  C3dSpec s = small_spec(C3dFormat::intel, true);
  const std::string path = write_temp("few.c3d", ptnet::test::write_c3d(s).bytes);
  try {
    ptnet::load_motion(path, {});
    ADD_FAILURE() << "expected an error";
  } catch (const ptnet::Error& e) {
    EXPECT_NE(std::string(e.what()).find("the file has RASI LASI SACR"), std::string::npos) << e.what();
  }
  fs::remove(path);
}

// ------------------------------------------------------ ../shared/c3d

TEST(C3dShared, EveryFileLoads) {
  if (!fs::exists(kShared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  int files = 0;
  for (const auto& e : fs::directory_iterator(kShared)) {
    if (e.path().extension() != ".c3d") continue;
    const ptnet::C3d c = ptnet::read_c3d(e.path().string());
    EXPECT_GT(c.points.frames(), 100) << e.path();
    EXPECT_GT(c.points.markers.size(), 3u) << e.path();
    EXPECT_TRUE(c.plates_problem.empty()) << e.path() << ": " << c.plates_problem;
    ++files;
  }
  EXPECT_EQ(files, 4);
}

TEST(C3dShared, Ja1MarkersMeetTheirTrcExport) {
  if (!fs::exists(kShared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  const ptnet::Trc c = ptnet::read_c3d(kShared + "/JA1Gait35.c3d").points;
  const ptnet::Trc t = ptnet::read_trc(kShared + "/JA1Gait35.trc");
  // The export (AddBiomechanics, by nimblephysics' C3D loader) drops the
  // first two frames and restarts the clock at 0; its axes are OpenSim's
  // (Y up): (x, y, z)_trc = (y, z, x)_c3d, metres. It also cleaned the
  // markers: it removed 263 samples the C3D file holds, moved 11 by more
  // than 20 mm (swaps and spikes of RTOE, RP5MT, LELB) and smoothed the rest
  // (no sample is within 1 micrometre; median 0.09 mm).
  const int skip = 2;
  ASSERT_EQ(c.frames(), t.frames() + skip);
  EXPECT_NEAR(c.time_s[skip] - t.time_s[0], 3.336, 1e-9);
  double sum = 0;
  int n = 0, both_missing = 0, removed = 0, compared_markers = 0;
  std::set<std::string> moved;
  int moved_samples = 0;
  for (std::size_t m = 0; m < c.markers.size(); ++m) {
    std::string name = c.markers[m];
    if (!name.empty() && name[0] == '*') name[0] = 'x';  // the export renames unlabelled '*52' 'x52'
    const int k = t.find(name);
    ASSERT_GE(k, 0) << name;
    ++compared_markers;
    for (int f = 0; f < t.frames(); ++f) {
      const V& p = c.at(f + skip, int(m));
      const V& q = t.at(f, k);
      if (std::isnan(p.x())) EXPECT_TRUE(std::isnan(q.x())) << name << " frame " << f;
      if (std::isnan(p.x()) || std::isnan(q.x())) {
        both_missing += std::isnan(p.x());
        removed += !std::isnan(p.x());
        continue;
      }
      const double d = (V(p.y(), p.z(), p.x()) * c.metres_per_unit - q * t.metres_per_unit).norm();
      if (d > 0.020) {
        moved.insert(name), ++moved_samples;
        continue;
      }
      sum += d * d, ++n;
    }
  }
  const double rms = std::sqrt(sum / n);
  std::cout << "JA1Gait35 markers against the .trc: " << compared_markers << " markers, " << n << " samples, RMS "
            << rms * 1000 << " mm; " << moved_samples << " samples moved > 20 mm, " << removed
            << " removed by the export, " << both_missing << " missing in both\n";
  EXPECT_EQ(compared_markers, 53);
  EXPECT_LT(rms, 0.001);
  EXPECT_EQ(both_missing, 1);
  EXPECT_EQ(removed, 263);
  EXPECT_LE(moved_samples, 11);
  EXPECT_EQ(moved, (std::set<std::string>{"LELB", "RP5MT", "RTOE"}));
}
