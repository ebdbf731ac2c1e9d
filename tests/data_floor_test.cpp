// /floor/<name> in the dataset file: a sequence's second-seed copy (the
// noise floor), written by DatasetWriter::add_floor, read by read_floor.
#include <gtest/gtest.h>

#include "data_test_util.hpp"
#include "ptnet/data.hpp"
#include "support/synthetic_walk.hpp"

namespace ptnet {
namespace {

using testing_util::error_of;
using testing_util::TempDir;

TEST(DatasetFloor, RoundTripAndOnlyForTheSequencesThatHaveOne) {
  TempDir dir("ds_floor");
  const std::string path = dir.file("d.h5");
  const DatasetInfo info;
  const PressureSequence a = synthetic_walk(info.mat, 20, 30, 186, 94, 1);
  const PressureSequence b = synthetic_walk(info.mat, 20, 30, 186, 94, 2);  // other noise
  {
    DatasetWriter w(path, info, testing_util::two_bodies(), false);
    w.add(testing_util::meta_for("walk", "b2"), a);
    w.add(testing_util::meta_for("walk", "b1"), synthetic_walk(info.mat, 20, 30, 158, 52, 1));
    w.add_floor("walk__b2", b);
    w.commit();
  }
  const Dataset d = Dataset::open(path);
  EXPECT_TRUE(d.sequence("walk__b2").floor);
  EXPECT_FALSE(d.sequence("walk__b1").floor);
  EXPECT_EQ(d.read_floor("walk__b2").kpa, b.kpa);
  EXPECT_EQ(d.read("walk__b2").kpa, a.kpa);  // the sequence itself is untouched
  EXPECT_EQ(d.sequences().size(), 2u);       // a floor copy is not a sequence
  EXPECT_NE(error_of([&] { d.read_floor("walk__b1"); }).find("no noise-floor copy"), std::string::npos);
}

TEST(DatasetFloor, WriterRefusesFloorsItCannotPair) {
  TempDir dir("ds_floor_bad");
  const DatasetInfo info;
  DatasetWriter w(dir.file("d.h5"), info, testing_util::two_bodies(), false);
  const PressureSequence s = synthetic_walk(info.mat, 20, 30, 186, 94, 1);
  EXPECT_NE(error_of([&] { w.add_floor("walk__b2", s); }).find("no such sequence"), std::string::npos);
  w.add(testing_util::meta_for("walk", "b2"), s);
  EXPECT_NE(error_of([&] { w.add_floor("walk__b2", synthetic_walk(info.mat, 19, 30, 186, 94, 1)); })
                .find("19 frames, the sequence has 20"),
            std::string::npos);
  w.add_floor("walk__b2", s);
  EXPECT_NE(error_of([&] { w.add_floor("walk__b2", s); }).find("added twice"), std::string::npos);
}

}  // namespace
}  // namespace ptnet
