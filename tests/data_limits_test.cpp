// Bounds on what readers accept: header-declared sizes are checked with
// overflow-safe arithmetic before anything is allocated, NaN is rejected by
// every input format alike, BVH parsing is linear in the joint count, and
// what an error echoes of a file is escaped and cut.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <H5Cpp.h>
#include "core/npy_internal.hpp"
#include "data_test_util.hpp"
#include "motion/motion_internal.hpp"
#include "ptnet/data.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/npy.hpp"

using namespace ptnet;
using ptnet::testing_util::error_of;
using ptnet::testing_util::TempDir;

namespace {

std::string npy_bytes(const std::string& shape, const std::string& data) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  header.append((64 - (10 + header.size() + 1) % 64) % 64, ' ');
  header += '\n';
  std::string b = "\x93NUMPY\x01";
  b += '\0';
  b += char(header.size() & 0xff);
  b += char(header.size() >> 8);
  return b + header + data;
}

void spit(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace

TEST(Limits, NpyShapesAreCheckedWithoutOverflow) {
  TempDir d("limits_npy");
  const std::string p = d.file("x.npy");
  spit(p, npy_bytes("(4294967296, 4294967296, 2)", ""));
  EXPECT_EQ(error_of([&] { read_npy(p); }), p + ": npy header: the shape's element count overflows 64 bits");
  spit(p, npy_bytes("(72057594037927936, 80, 28)", ""));  // 2^56 frames
  EXPECT_EQ(error_of([&] { read_npy(p); }), p + ": npy header: the shape's element count overflows 64 bits");
  spit(p, npy_bytes("(1099511627776, 80, 28)", std::string(16, '\0')));  // 2^40 frames, 16 bytes
  EXPECT_EQ(error_of([&] { read_npy(p); }),
            p + ": expected 9851624184872960 data bytes for shape [1099511627776, 80, 28], found 16");
}

// A shape holds whole decimal numbers only: "80.9" is not 80, "3L" (the
// Python 2 long suffix) not 3, "0x10" not 16; "(3,)" is a 1-tuple.
TEST(Limits, NpyShapesAreWholeNumbers) {
  for (const std::string shape : {"(2, 80.9, 28)", "(3L, 4, 4)", "(0x2, 4)", "(2, +4)", "(2, 4 4)", "(2,, 4)", "(,)"}) {
    EXPECT_EQ(error_of([&] { parse_npy_header(npy_bytes(shape, ""), "x.npy"); }),
              "x.npy: npy header: bad shape '" + shape + "'") << shape;
  }
  EXPECT_EQ(parse_npy_header(npy_bytes("(32,)", ""), "x.npy").shape, (std::vector<std::int64_t>{32}));
  EXPECT_EQ(parse_npy_header(npy_bytes("( 2 , 4,4 )", ""), "x.npy").shape, (std::vector<std::int64_t>{2, 4, 4}));
  EXPECT_EQ(parse_npy(npy_bytes("()", std::string(4, '\0')), "x.npy").data.size(), 1u);
}

TEST(Limits, NanIsRejectedInNpyAsInDatasets) {
  TempDir d("limits_nan");
  const MatSpec mat{2, 3, 0.02};
  PressureSequence s(mat, 3, 30);
  s.at(2, 1, 1) = std::nanf("");
  const std::string p = d.file("nan.npy");
  write_npy_sequence(p, s, false);
  EXPECT_EQ(error_of([&] { read_npy_sequence(p, mat, 30); }), p + ": non-finite value (NaN or Inf) in frame 2");
  s.at(2, 1, 1) = INFINITY;
  const std::string q = d.file("inf.npy");  // (nan.npy, an input now, may not be replaced)
  write_npy_sequence(q, s, false);
  EXPECT_EQ(error_of([&] { read_npy_sequence(q, mat, 30); }), q + ": non-finite value (NaN or Inf) in frame 2");
}

TEST(Limits, HugeDeclaredSequencesAreRefusedBeforeAllocating) {
  TempDir d("limits_h5");
  const std::string p = d.file("huge.h5");
  testing_util::write_small_dataset(p);
  {
    H5::H5File f(p, H5F_ACC_RDWR);
    hsize_t dims[3] = {(hsize_t(1) << 31) + 5, 80, 28}, chunk[3] = {32, 80, 28};
    H5::DSetCreatPropList plist;
    plist.setChunk(3, chunk);
    f.createDataSet("sequences/huge", H5::PredType::IEEE_F32LE, H5::DataSpace(3, dims), plist);
  }
  EXPECT_EQ(error_of([&] { Dataset::open(p); }),
            p + ": sequence 'huge' has 2147483653 frames, more than the 2147483647 a sequence may have");
}

TEST(Limits, BvhParsingIsLinearInTheJointCount) {
  // 100k sibling joints took 18 s when each name was looked up linearly.
  std::string text = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition "
                     "Zrotation Xrotation Yrotation\n";
  const int n = 100000;
  for (int i = 0; i < n; ++i)
    text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\n";
  text += "}\nMOTION\nFrames: 1\nFrame Time: 0.0333333\n0 0 0 0 0 0\n";
  const auto t0 = std::chrono::steady_clock::now();
  const Bvh bvh = parse_bvh(text, "wide.bvh");
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(bvh.joints.size(), std::size_t(n) + 1);
  EXPECT_LT(s, 3.0) << "parse took " << s << " s";
}

TEST(Limits, BvhErrorsEscapeAndDoNotEchoForeignFiles) {
  EXPECT_EQ(error_of([] { parse_bvh("root:x:0:0:root:/root:/bin/bash\n", "passwd"); }),
            "passwd:1: expected HIERARCHY, found other text (not a BVH file)");
  EXPECT_EQ(error_of([] {
              parse_bvh("HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation \x1b[2J\n", "esc.bvh");
            }),
            "esc.bvh:5: expected a channel name (X|Y|Z + position|rotation), found \\x1b[2J");
}
