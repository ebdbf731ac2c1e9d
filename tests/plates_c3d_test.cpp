// Force plates of C3D files: plates of types 1-4 written by the test's own
// writer (tests/support/c3d_writer) with a known ground reaction force,
// centre of pressure and free moment, stored as the action on the plate or
// the reaction on the subject, ORIGIN's z stored either sign, read back in
// the lab frame; the ZERO baseline, the CoP threshold, the marker-rate
// average, errors; the bench's trials CSV taking a C3D file's own plates.
// Then ../shared/c3d (skipped when absent): JA1Gait35's plates against
// their OpenSim export, Motion Analysis type-4 plates whose CoP lies on the
// plate, and physics-bench on JA1Gait35.c3d giving the figures of its
// .trc/.mot export.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

#include <Eigen/Dense>

#include "motion/c3d_internal.hpp"
#include "plates/plates_internal.hpp"
#include "ptnet/c3d.hpp"
#include "ptnet/error.hpp"
#include "ptnet/plates.hpp"
#include "support/c3d_writer.hpp"

namespace {

using V = Eigen::Vector3d;
using ptnet::C3dFormat;
using ptnet::PlateRate;
using ptnet::test::C3dPlateSpec;
using ptnet::test::C3dSpec;
namespace fs = std::filesystem;

const std::string kShared = std::string(PTNET_SOURCE_DIR) + "/../shared/c3d";

std::string write_temp(const std::string& name, const std::string& bytes) {
  const std::string p = (fs::temp_directory_path() / ("ptnet_plates_c3d_" + std::to_string(::getpid()) + "_" + name)).string();
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

// What a plate should read: the reaction on the subject in the lab (N), its
// CoP on the surface (m) and free moment about the vertical (N m).
struct Load {
  V force, cop;
  double free = 0;
};

// The stored channels (N, mm, N mm) of a plate of `spec` (corners in mm)
// carrying `load`: `action` stores the force on the plate (C3D's
// convention), else the reaction on the subject (Vicon's).
std::vector<double> channels_of(const C3dPlateSpec& spec, const Load& load, bool action) {
  const V c0 = spec.corners[0] / 1000, c1 = spec.corners[1] / 1000, c3 = spec.corners[3] / 1000;
  const V x = (c0 - c1).normalized(), z = x.cross(c0 - c3).normalized(), y = z.cross(x);
  Eigen::Matrix3d r;
  r << x, y, z;
  const V centre = (spec.corners[0] + spec.corners[1] + spec.corners[2] + spec.corners[3]) / 4000;
  const double s = action ? -1 : 1;
  const V f = s * r.transpose() * load.force;                      // plate frame
  const V cop = r.transpose() * (load.cop - centre);                // from the surface's centre
  const V free(0, 0, -s * load.free);                               // about plate z (into the floor)
  const V m_surface = V(cop.x(), cop.y(), 0).cross(f) + free;
  if (spec.type == 1) return {f.x(), f.y(), f.z(), cop.x() * 1000, cop.y() * 1000, free.z() * 1000};
  V o = spec.origin / 1000;
  if (o.z() > 0) o = -o;  // the surface above the origin, whichever sign was stored
  if (spec.type == 3) {
    const double a = spec.origin.x() / 1000, b = spec.origin.y() / 1000;
    const V m = m_surface - f.cross(V(0, 0, o.z()));  // about the sensors' plane
    Eigen::Matrix4d k;
    k << 1, 1, 1, 1, b, b, -b, -b, -a, a, a, -a, 1, -1, 1, -1;
    const Eigen::Vector4d fz = k.colPivHouseholderQr().solve(Eigen::Vector4d(f.z(), m.x(), m.y(), 0));
    const double dx = m.z() / b;  // fx34 - fx12 (fy14 = fy23)
    return {(f.x() - dx) / 2, (f.x() + dx) / 2, f.y() / 2, f.y() / 2, fz[0], fz[1], fz[2], fz[3]};
  }
  const V m = m_surface - f.cross(o);  // about the plate's origin
  Eigen::Matrix<double, 6, 1> c;
  c << f, m * 1000;
  if (spec.type == 4) c = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(spec.cal_matrix.data()).inverse() * c;
  return {c.begin(), c.end()};
}

// A file with one plate of `type` at a turned position (its x along the
// lab's -Y), every sample carrying `load` but the first frame's, empty.
C3dSpec plate_file(int type, const Load& load, bool action, double origin_z, C3dFormat format = C3dFormat::intel,
                   double moment_scale = 1) {
  C3dSpec s;
  s.format = format;
  s.rate_hz = 100;
  s.first_frame = 21;
  s.frames = 5;
  s.per_frame = 4;
  C3dPlateSpec p;
  p.type = type;
  p.corners = {V(1000, -2000, 0), V(1000, -1400, 0), V(1400, -1400, 0), V(1400, -2000, 0)};
  p.origin = type == 3 ? V(210, 260, origin_z) : V(2, -3, origin_z);
  if (type == 4)
    for (int k = 0; k < 36; ++k) p.cal_matrix.push_back(k % 7 == 0 ? 1.5 + 0.25 * (k / 7) : 0.01 * (k % 5) - 0.02);
  const int n = type == 3 ? 8 : 6;
  for (int k = 0; k < n; ++k) {
    p.channels.push_back(k + 1);
    s.analog_labels.push_back("C" + std::to_string(k + 1));
    s.analog_units.push_back(type == 1 ? (k < 3 ? "N" : k < 5 ? "mm" : "Nmm") : (k < 3 || type == 3 ? "N" : "Nmm"));
    s.analog_scale.push_back(k == 2 ? -2.0 : k >= 3 ? moment_scale : 1.0);  // a negative scale turns a channel over
    s.analog_offset.push_back(k == 1 ? 10 : 0);
  }
  s.plates = {p};
  const std::vector<double> loaded = channels_of(p, load, action);
  for (int sample = 0; sample < s.frames * s.per_frame; ++sample)
    for (int k = 0; k < n; ++k) {
      const double value = sample < s.per_frame ? 0.0 : loaded[std::size_t(k)];
      s.analog.push_back(value / s.analog_scale[std::size_t(k)] + s.analog_offset[std::size_t(k)]);
    }
  return s;
}

ptnet::ForcePlates plates_of(const C3dSpec& s, PlateRate rate, double cop_min_n = 20) {
  return ptnet::plates_from_c3d(ptnet::parse_c3d(ptnet::test::write_c3d(s).bytes, "p.c3d"), cop_min_n, rate);
}

}  // namespace

TEST(C3dPlates, EveryTypeAndConventionGivesTheReactionCopAndFreeMoment) {
  const Load load{V(35, -60, 720), V(1.31, -1.52, 0), 4.5};
  for (int type : {1, 2, 3, 4})
    for (bool action : {true, false})
      for (double origin_z : {-40.0, 40.0}) {
        SCOPED_TRACE("type " + std::to_string(type) + (action ? " action" : " reaction") + " origin z " +
                     std::to_string(origin_z));
        const ptnet::ForcePlates fp = plates_of(plate_file(type, load, action, origin_z), PlateRate::analog);
        ASSERT_EQ(fp.plates.size(), 1u);
        ASSERT_EQ(fp.time_s.size(), 20u);
        EXPECT_DOUBLE_EQ(fp.time_s[0], 0.2);  // frame 21 at 100 Hz
        EXPECT_NEAR(fp.time_s[1] - fp.time_s[0], 1 / 400.0, 1e-15);
        const auto& p = fp.plates[0];
        EXPECT_LT(p.force_n[0].norm(), 1e-9);
        EXPECT_TRUE(std::isnan(p.cop_m[0].x()));         // unloaded: no CoP
        EXPECT_TRUE(std::isnan(p.free_moment_nm[0].x()));
        for (int s = 4; s < 20; ++s) {
          EXPECT_LT((p.force_n[std::size_t(s)] - load.force).norm(), 1e-3);
          EXPECT_LT((p.cop_m[std::size_t(s)] - load.cop).norm(), 1e-6);
          EXPECT_LT((p.free_moment_nm[std::size_t(s)] - V(0, 0, load.free)).norm(), 1e-4);
        }
      }
}

TEST(C3dPlates, EveryNumberFormatAndIntegerStorageReadTheSamePlate) {
  const Load load{V(0, 0, 800), V(1.2, -1.7, 0), 0};
  for (C3dFormat format : {C3dFormat::intel, C3dFormat::dec, C3dFormat::mips})
    for (bool floats : {true, false}) {
      C3dSpec s = plate_file(2, load, true, -40, format, floats ? 1 : 10);  // integers: moments in 10 N mm counts
      s.floats = floats;
      const ptnet::ForcePlates fp = plates_of(s, PlateRate::analog);
      // Integer storage rounds each channel to a whole count.
      const double tol = floats ? 1e-6 : 0.005;
      EXPECT_LT((fp.plates[0].force_n[10] - load.force).norm(), floats ? 1e-3 : 2.0);
      EXPECT_LT((fp.plates[0].cop_m[10] - load.cop).norm(), tol) << ptnet::c3d_format_name(format);
    }
}

TEST(C3dPlates, MarkerRateAveragesEachFramesSamples) {
  const Load load{V(10, 20, 600), V(1.2, -1.6, 0), 2};
  const ptnet::ForcePlates fp = plates_of(plate_file(2, load, true, -40), PlateRate::markers);
  ASSERT_EQ(fp.time_s.size(), 5u);  // one per frame, on the frames' clock
  EXPECT_DOUBLE_EQ(fp.time_s[1], 0.21);
  const auto& p = fp.plates[0];
  // Frame 1's window holds two empty samples of frame 0 and two loaded.
  EXPECT_LT((p.force_n[1] - load.force / 2).norm(), 1e-3);
  EXPECT_LT((p.cop_m[1] - load.cop).norm(), 1e-6);  // the CoP of the mean wrench
  EXPECT_LT((p.force_n[2] - load.force).norm(), 1e-3);
  // Below the threshold, no CoP: frame 1 carries 300 N.
  const ptnet::ForcePlates high = plates_of(plate_file(2, load, true, -40), PlateRate::markers, 400);
  EXPECT_TRUE(std::isnan(high.plates[0].cop_m[1].x()));
  EXPECT_FALSE(std::isnan(high.plates[0].cop_m[2].x()));
}

TEST(C3dPlates, TheZeroFramesAreEachChannelsBaseline) {
  const Load load{V(0, 30, 700), V(1.25, -1.8, 0), 1};
  C3dSpec s = plate_file(2, load, false, -40);
  for (std::size_t k = 0; k < s.analog.size(); ++k) s.analog[k] += 3.0 + double(k % 6);  // a bias per channel
  s.zero = {1, 1};  // frame 1 is unloaded
  const ptnet::ForcePlates fp = plates_of(s, PlateRate::analog);
  EXPECT_LT((fp.plates[0].force_n[12] - load.force).norm(), 1e-3);
  EXPECT_LT((fp.plates[0].cop_m[12] - load.cop).norm(), 1e-6);
  s.zero = {0, 0};  // no baseline: the bias stays
  EXPECT_GT((plates_of(s, PlateRate::analog).plates[0].force_n[12] - load.force).norm(), 1.0);
}

TEST(C3dPlates, PlatesThatCannotBeReadAreOneLineErrors) {
  const Load load{V(0, 0, 700), V(1.2, -1.7, 0), 0};
  auto error = [](const C3dSpec& s) -> std::string {
    try {
      plates_of(s, PlateRate::analog);
    } catch (const ptnet::Error& e) {
      return e.what();
    }
    return "";
  };
  C3dSpec s = plate_file(2, load, true, -40);
  s.plates[0].type = 5;
  EXPECT_EQ(error(s), "p.c3d: force plate 1 is of type 5; ptnet reads force plates of types 1-4");
  s = plate_file(2, load, true, -40);
  s.plates[0].type = 4;  // and no CAL_MATRIX written
  EXPECT_EQ(error(s), "p.c3d: force plate 1 is of type 4 without its 6 x 6 FORCE_PLATFORM:CAL_MATRIX");
  s = plate_file(2, load, true, -40);
  s.plates[0].channels[4] = 9;  // of 6 channels
  EXPECT_EQ(error(s), "p.c3d: FORCE_PLATFORM:CHANNEL: plate 1 reads channel 9 of the 6 analog channels");
  s = plate_file(2, load, true, -40);
  s.plates[0].corners[1] = s.plates[0].corners[0];
  EXPECT_NE(error(s).find("force plate 1: expected CORNERS that span a plane"), std::string::npos) << error(s);
  s = plate_file(2, load, true, -40);
  s.analog[6 + 1] = NAN;  // sample 1, channel C2
  EXPECT_EQ(error(s), "p.c3d: force plate 1: expected numbers in channel 'C2', found nan at analog sample 1");
  s = plate_file(2, load, true, -40);
  s.plates.clear();
  EXPECT_EQ(error(s), "p.c3d: no force plates (FORCE_PLATFORM:USED is 0 or absent)");
}

TEST(C3dPlates, TheReaderIsChosenByExtensionAndTheBenchTakesAC3dFilesOwnPlates) {
  const Load load{V(0, 0, 700), V(1.2, -1.7, 0), 0};
  const std::string c3d = write_temp("trial.c3d", ptnet::test::write_c3d(plate_file(2, load, true, -40)).bytes);
  const ptnet::ForcePlates fp = ptnet::read_force_plates(c3d, 20);
  EXPECT_EQ(fp.time_s.size(), 5u);  // the marker rate
  EXPECT_LT((fp.plates[0].force_n[3] - load.force).norm(), 1e-3);
  const std::string mot = write_temp("grf.mot", "grf\nendheader\ntime\tground_force_vx\tground_force_vy\t"
                                                "ground_force_vz\tground_force_px\tground_force_py\tground_force_pz\n"
                                                "0\t1\t2\t3\t4\t5\t6\n");
  EXPECT_EQ(ptnet::read_force_plates(mot, 20).plates[0].force_n[0], V(1, 2, 3));
  // A trials CSV: plates may be empty when the markers are a .c3d file.
  const std::string dir = fs::path(c3d).parent_path().string();
  const std::string trc = write_temp("trial.trc", "x");
  const std::string csv = write_temp("trials.csv", "trial,markers,plates,sex,height_cm,weight_kg\nt1," +
                                                       fs::path(c3d).filename().string() + ",,male,180,75\n");
  const auto trials = ptnet::read_gait_trials(csv, dir);
  ASSERT_EQ(trials.size(), 1u);
  EXPECT_EQ(trials[0].plates, "");
  const std::string bad = write_temp("bad.csv", "trial,markers,plates,sex,height_cm,weight_kg\nt1," +
                                                    fs::path(trc).filename().string() + ",,male,180,75\n");
  try {
    ptnet::read_gait_trials(bad, dir);
    ADD_FAILURE() << "expected an error";
  } catch (const ptnet::Error& e) {
    EXPECT_EQ(std::string(e.what()), bad + ":2: expected a plates file (or markers in a .c3d file, which holds its "
                                           "plates), found an empty field");
  }
  for (const std::string& f : {c3d, mot, trc, csv, bad}) fs::remove(f);
}

// ------------------------------------------------------ ../shared/c3d

TEST(C3dPlatesShared, Ja1PlatesMeetTheirMotExport) {
  if (!fs::exists(kShared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  const ptnet::C3d c = ptnet::read_c3d(kShared + "/JA1Gait35.c3d");
  const ptnet::ForcePlates analog = ptnet::plates_from_c3d(c, 20, PlateRate::analog);
  const ptnet::ForcePlates frames = ptnet::plates_from_c3d(c, 20, PlateRate::markers);
  const ptnet::ForcePlates mot = ptnet::read_grf_mot(kShared + "/JA1Gait35_grf.mot");
  ASSERT_EQ(analog.plates.size(), mot.plates.size());
  // The export (nimblephysics' C3D loader) takes the first analog sample of
  // each frame from the third frame on (no average, no filter), its clock
  // starting there (3.336 s); axes (x, y, z)_mot = (y, z, x)_c3d.
  double peak = 0;
  for (const auto& p : mot.plates)
    for (const V& f : p.force_n) peak = std::max(peak, f.y());
  double f_first = 0, cop_first = 0, f_avg = 0, cop_avg = 0, f_avg_sq = 0, cop_avg_sq = 0;
  int loaded = 0, n = 0;
  for (std::size_t i = 0; i < mot.plates.size(); ++i)
    for (std::size_t t = 0; t < mot.time_s.size(); ++t) {
      const std::size_t frame = t + 2, sample = frame * std::size_t(c.analog.per_frame);
      ASSERT_NEAR(analog.time_s[sample] - 3.336, mot.time_s[t], 1e-9);
      const V& fm = mot.plates[i].force_n[t];
      const V& pm = mot.plates[i].cop_m[t];
      const V& fa = analog.plates[i].force_n[sample];
      const V& ff = frames.plates[i].force_n[frame];
      f_first = std::max(f_first, std::abs(fa.z() - fm.y()));
      f_avg = std::max(f_avg, std::abs(ff.z() - fm.y()));
      f_avg_sq += (ff.z() - fm.y()) * (ff.z() - fm.y()), ++n;
      if (!(fm.y() > 20 && ff.z() > 20)) continue;
      const V& pa = analog.plates[i].cop_m[sample];
      const V& pf = frames.plates[i].cop_m[frame];
      cop_first = std::max(cop_first, std::hypot(pa.y() - pm.x(), pa.x() - pm.z()));
      const double d = std::hypot(pf.y() - pm.x(), pf.x() - pm.z());
      cop_avg = std::max(cop_avg, d), cop_avg_sq += d * d, ++loaded;
    }
  std::cout << "JA1Gait35 plates against the .mot (peak " << peak << " N, " << loaded
            << " loaded plate-frames): at the export's samples, vertical force within " << f_first << " N, CoP within "
            << cop_first * 1000 << " mm; averaged over each frame, force within " << f_avg << " N (RMS "
            << std::sqrt(f_avg_sq / n) << "), CoP within " << cop_avg * 1000 << " mm (RMS "
            << std::sqrt(cop_avg_sq / loaded) * 1000 << ")\n";
  EXPECT_GT(loaded, 100);
  EXPECT_LT(f_first, 0.01 * peak);
  EXPECT_LT(cop_first, 0.005);
  EXPECT_LT(f_avg, 0.05 * peak);                  // the sprint's impacts change within a frame
  EXPECT_LT(std::sqrt(f_avg_sq / n), 0.005 * peak);
}

TEST(C3dPlatesShared, EveryFilesPlatesReadAndMotionAnalysisCopsLieOnTheirPlates) {
  if (!fs::exists(kShared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  for (const char* name : {"JA1Gait35.c3d", "S01DB201.c3d", "motion_analysis_trial1.c3d"}) {
    const ptnet::C3d c = ptnet::read_c3d(kShared + "/" + name);
    const ptnet::ForcePlates fp = ptnet::plates_from_c3d(c, 100, PlateRate::analog);
    ASSERT_EQ(fp.plates.size(), c.plates.size()) << name;
    int loaded = 0, inside = 0;
    for (std::size_t i = 0; i < fp.plates.size(); ++i) {
      V lo = V::Constant(1e9), hi = V::Constant(-1e9);
      for (const V& k : c.plates[i].corners) lo = lo.cwiseMin(k), hi = hi.cwiseMax(k);
      for (const V& p : fp.plates[i].cop_m) {
        if (std::isnan(p.x())) continue;
        ++loaded;
        inside += (p.head<2>().array() >= lo.head<2>().array() - 0.01).all() &&
                  (p.head<2>().array() <= hi.head<2>().array() + 0.01).all();
      }
    }
    std::cout << name << ": " << loaded << " samples above 100 N, " << inside << " with the CoP on the plate (+-1 cm)\n";
    if (loaded) EXPECT_GE(inside, 0.99 * loaded) << name;
  }
  EXPECT_THROW(ptnet::plates_from_c3d(ptnet::read_c3d(kShared + "/cmu_02_05.c3d"), 20, PlateRate::analog), ptnet::Error);
}

TEST(C3dPlatesShared, PhysicsBenchOnTheC3dGivesTheFiguresOfItsExport) {
  if (!fs::exists(kShared + "/JA1Gait35.c3d")) GTEST_SKIP() << "../shared/c3d not found";
  // The subject's mass and stature are not stated: 78 kg (the plates'
  // impulse per step over the step time) and 179 cm (the markers' stature
  // estimate), the same in both runs.
  ptnet::GaitTrial c3d;
  c3d.name = "ja1_c3d";
  c3d.markers = kShared + "/JA1Gait35.c3d";
  c3d.body.id = "ja1";
  c3d.body.sex = ptnet::Sex::male;
  c3d.body.height_cm = 179;
  c3d.body.weight_kg = 78;
  c3d.body.role = "original";
  ptnet::GaitTrial exported = c3d;
  exported.name = "ja1_export";
  exported.markers = kShared + "/JA1Gait35.trc";
  exported.plates = kShared + "/JA1Gait35_grf.mot";
  const ptnet::PhysicsBenchOptions o;
  const ptnet::GaitTrialResult a = ptnet::run_gait_trial(c3d, o), b = ptnet::run_gait_trial(exported, o);
  // The same frames on the two clocks: the export starts two frames later.
  ASSERT_EQ(a.time_s.size(), b.time_s.size() + 2);
  double plates_sq = 0, sim_sq = 0;
  for (std::size_t t = 0; t < b.time_s.size(); ++t) {
    EXPECT_NEAR(a.time_s[t + 2] - 3.336, b.time_s[t], 1e-6);
    plates_sq += std::pow(a.plates.total_bw[t + 2] - b.plates.total_bw[t], 2);
    sim_sq += std::pow(a.simulated.total_bw[t + 2] - b.simulated.total_bw[t], 2);
  }
  const double plates_rms = std::sqrt(plates_sq / b.time_s.size()), sim_rms = std::sqrt(sim_sq / b.time_s.size());
  std::cout << "JA1Gait35 physics-bench, .c3d against .trc + .mot: plates' total force " << plates_rms
            << " BW RMS apart, simulated " << sim_rms << " BW RMS apart\n";
  for (const ptnet::ForceSource* f : {&a.simulated, &b.simulated, &a.naive, &b.naive})
    std::cout << "  " << f->name << " rmse " << f->rmse_bw << " peak " << f->peak_error_pct << " stance "
              << f->stance_error_ms << " lrate " << f->loading_rate_error_pct << " impulse "
              << f->stride_impulse_error_pct << " flight " << f->flight_recall << " cop " << f->cop_rms << "\n";
  ASSERT_EQ(a.plates.contacts.size(), b.plates.contacts.size());
  for (std::size_t k = 0; k < a.plates.contacts.size(); ++k) {
    EXPECT_EQ(a.plates.contacts[k].foot, b.plates.contacts[k].foot);
    EXPECT_NEAR(a.plates.contacts[k].peak_n, b.plates.contacts[k].peak_n, 0.01 * b.plates.contacts[k].peak_n);
    EXPECT_NEAR(a.plates.contacts[k].end_s - a.plates.contacts[k].start_s,
                b.plates.contacts[k].end_s - b.plates.contacts[k].start_s, 0.004);
  }
  // Their inputs differ: the export took one analog sample a frame where the
  // C3D plates are averaged over it (the plates' loading rates differ most:
  // 7-10 points of the loading-rate error), smoothed and cleaned the
  // markers (2-4 ms of stance) and lacks the first two frames.
  EXPECT_LT(plates_rms, 0.03);
  for (const auto& [x, y] : {std::pair{&a.simulated, &b.simulated}, std::pair{&a.naive, &b.naive}}) {
    SCOPED_TRACE(x->name);
    EXPECT_NEAR(x->rmse_bw, y->rmse_bw, 0.03);
    EXPECT_NEAR(x->peak_error_pct, y->peak_error_pct, 2.0);
    EXPECT_NEAR(x->stance_error_ms, y->stance_error_ms, 6.0);
    EXPECT_NEAR(x->loading_rate_error_pct, y->loading_rate_error_pct, 12.0);
    EXPECT_NEAR(x->stride_impulse_error_pct, y->stride_impulse_error_pct, 1.0);
    EXPECT_NEAR(x->flight_recall, y->flight_recall, 0.01);
    EXPECT_NEAR(x->cop_rms, y->cop_rms, 0.01);
    EXPECT_EQ(x->matched, y->matched);
  }
  // A sprint on the forefoot, never flat: the floor follows its planted toes
  // (the runway falls 5 cm over the trial in the markers' frame). Before,
  // the floor was found from flat feet only, there were none, and the first
  // two steps never touched it: RMSE 1.02 BW, no better than the naive
  // reference (1.13). Measured 0.293 BW, peaks 11.5 %, flight 98 %; the
  // running bar's RMSE (0.15) is not met: the 4 Hz centre-of-mass filter
  // rounds ~0.1 s contacts.
  EXPECT_LE(a.simulated.rmse_bw, 0.35);
  EXPECT_LT(a.simulated.rmse_bw, a.naive.rmse_bw / 2);
  EXPECT_LE(a.simulated.peak_error_pct, 15);
  EXPECT_GE(a.simulated.flight_recall, 0.9);
}
