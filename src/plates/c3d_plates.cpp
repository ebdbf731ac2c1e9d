// Force plates of a C3D file (c3d.org, "The C3D File Format User Guide",
// FORCE_PLATFORM group): each plate's analog channels, less their ZERO
// baseline, become the force and moments in the plate's frame (type 1:
// force, CoP and free moment stored; 2: force and moments; 3: eight
// sensor forces; 4: as 2 after the calibration matrix), then the centre of
// pressure on the plate's surface and the free moment, then the lab frame
// through the plate's corners. The plate's z axis points into the floor
// (corner order +x+y, -x+y, -x-y, +x-y). At the marker rate, each frame's
// wrench is the mean of its samples' (the CoP that of the mean wrench).
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <Eigen/Dense>

#include "plates/plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace {

using V = Eigen::Vector3d;

// A plate's axes in the lab (columns x, y, z) and the centre of its surface.
struct PlateAxes {
  Eigen::Matrix3d r;
  V centre;
};

PlateAxes plate_axes(const C3dPlate& p, const std::string& plate, const std::string& source) {
  V x = p.corners[0] - p.corners[1], y = p.corners[0] - p.corners[3];
  V z = x.cross(y);
  if (!(z.norm() > 1e-9))
    throw Error::in(source, plate + ": expected CORNERS that span a plane, found " + number_text(x.norm()) + " m by " +
                                number_text(y.norm()) + " m");
  x.normalize();
  z.normalize();
  y = z.cross(x);
  PlateAxes a;
  a.r << x, y, z;
  a.centre = (p.corners[0] + p.corners[1] + p.corners[2] + p.corners[3]) / 4;
  return a;
}

// Metres of a length unit, N m of a moment unit (ANALOG:UNITS); a unit
// not named is the file's: POINT:UNITS, N x POINT:UNITS.
double length_scale(const std::string& units, double metres) {
  const std::string u = lower(units);
  return u == "m" ? 1.0 : u == "cm" ? 0.01 : u == "mm" ? 0.001 : metres;
}
double moment_scale(const std::string& units, double metres) {
  const std::string u = lower(units);
  return u == "nm" || u == "n.m" ? 1.0 : u == "ncm" ? 0.01 : u == "nmm" || u == "n.mm" ? 0.001 : metres;
}

// One sample in the plate's frame: the stored force (N) and its moment
// about the centre of the plate's surface (N m).
struct Wrench {
  V force, moment;
};

// Forces and moments about the plate's origin O, ORIGIN the vector from O
// to the surface's centre S (its z negative: O below the surface; stored
// positive, as some writers do, it is negated whole, as Visual3D does).
Wrench about_surface(const V& f, const V& m_origin, V origin) {
  if (origin.z() > 0) origin = -origin;
  return {f, m_origin + f.cross(origin)};
}

// The plate's wrench from its channels `ch` (scaled analog values, less
// the baseline). `ms`: N m per moment unit, `ls`: m per CoP unit (type 1).
Wrench plate_wrench(const C3dPlate& p, const double* ch, double ms, double ls) {
  if (p.type == 1) {  // Fx Fy Fz, the CoP (x, y) from the surface's centre, the free moment
    const V f(ch[0], ch[1], ch[2]);
    const double x = ch[3] * ls, y = ch[4] * ls;
    return {f, V(y * f.z(), -x * f.z(), x * f.y() - y * f.x() + ch[5] * ms)};
  }
  if (p.type == 3) {  // Fx12 Fx34 Fy14 Fy23 Fz1..Fz4; ORIGIN: a, b (sensor offsets), surface z
    const double a = p.origin.x(), b = p.origin.y();
    const V f(ch[0] + ch[1], ch[2] + ch[3], ch[4] + ch[5] + ch[6] + ch[7]);
    const V m(b * (ch[4] + ch[5] - ch[6] - ch[7]), a * (-ch[4] + ch[5] + ch[6] - ch[7]),
              b * (-ch[0] + ch[1]) + a * (ch[2] - ch[3]));
    return about_surface(f, m, V(0, 0, p.origin.z()));
  }
  Eigen::Matrix<double, 6, 1> c;
  for (int k = 0; k < 6; ++k) c[k] = ch[k];
  if (p.type == 4) c = Eigen::Map<const Eigen::Matrix<double, 6, 6>>(p.cal_matrix.data()) * c;  // column order
  return about_surface(c.head<3>(), c.tail<3>() * ms, p.origin);
}

// The wrenches averaged over each marker frame: the samples within half a
// frame of the frame's time (a frame's first sample is at its time).
std::vector<Wrench> per_frame(const std::vector<Wrench>& w, int per) {
  const int lo = -per / 2, hi = (per + 1) / 2 - 1, S = int(w.size());
  std::vector<Wrench> out(w.size() / std::size_t(per));
  for (std::size_t f = 0; f < out.size(); ++f) {
    V force = V::Zero(), moment = V::Zero();
    int n = 0;
    for (int s = int(f) * per + lo; s <= int(f) * per + hi; ++s)
      if (s >= 0 && s < S) force += w[std::size_t(s)].force, moment += w[std::size_t(s)].moment, ++n;
    out[f] = {force / n, moment / n};
  }
  return out;
}

// Each channel's baseline: its mean over the ZERO frames (none: 0).
std::vector<double> baselines(const C3d& c3d, const std::vector<int>& channels) {
  std::vector<double> out(channels.size(), 0.0);
  const auto [z0, z1] = c3d.plates_zero;
  if (z0 < 1) return out;
  const int per = c3d.analog.per_frame, s0 = (z0 - 1) * per, s1 = std::min(z1 * per, c3d.analog.samples());
  for (std::size_t k = 0; k < channels.size(); ++k) {
    double sum = 0;
    for (int s = s0; s < s1; ++s) sum += c3d.analog.value(s, channels[k]);
    out[k] = s1 > s0 ? sum / (s1 - s0) : 0.0;
  }
  return out;
}

void check_plate(const C3d& c3d, const C3dPlate& p, const std::string& plate) {
  if (p.type < 1 || p.type > 4)
    throw Error::in(c3d.source, plate + " is of type " + std::to_string(p.type) + "; ptnet reads force plates of types 1-4");
  if (p.type == 4 && p.cal_matrix.size() != 36)
    throw Error::in(c3d.source, plate + " is of type 4 without its 6 x 6 FORCE_PLATFORM:CAL_MATRIX");
}

// Plate `i` at every analog sample or marker frame. The stored force is
// the reaction on the subject or the action on the plate (writers differ):
// the sign is chosen so that the plate pushes the subject up (out of its
// surface) over the trial.
ForcePlates::Plate plate_forces(const C3d& c3d, int i, double cop_min_n, PlateRate rate) {
  const C3dPlate& p = c3d.plates[std::size_t(i)];
  const std::string name = "force plate " + std::to_string(i + 1);
  check_plate(c3d, p, name);
  const PlateAxes axes = plate_axes(p, name, c3d.source);
  const std::size_t n = p.channels.size(), moment = p.type == 1 ? 5 : 3;
  const double metres = c3d.points.metres_per_unit;
  const double ms = moment_scale(c3d.analog.units[std::size_t(p.channels[moment])], metres);
  const double ls = length_scale(c3d.analog.units[std::size_t(p.channels[3])], metres);
  const std::vector<double> base = baselines(c3d, p.channels);
  std::vector<Wrench> w(std::size_t(c3d.analog.samples()));
  double vertical_sum = 0;
  std::vector<double> ch(n);
  for (std::size_t s = 0; s < w.size(); ++s) {
    for (std::size_t k = 0; k < n; ++k) {
      ch[k] = c3d.analog.value(int(s), p.channels[k]) - base[k];
      if (!std::isfinite(ch[k]))
        throw Error::in(c3d.source, name + ": expected numbers in channel " +
                                        escaped(c3d.analog.labels[std::size_t(p.channels[k])]) + ", found " +
                                        number_text(ch[k]) + " at analog sample " + std::to_string(s));
    }
    w[s] = plate_wrench(p, ch.data(), ms, ls);
    vertical_sum += w[s].force.z();
  }
  if (rate == PlateRate::markers) w = per_frame(w, c3d.analog.per_frame);
  const double sign = vertical_sum > 0 ? -1.0 : 1.0;  // +z is into the floor
  ForcePlates::Plate out;
  out.prefix = "plate" + std::to_string(i + 1) + "_";
  const V nan = V::Constant(NAN);
  for (const Wrench& x : w) {
    const V& f = x.force;
    out.force_n.push_back(sign * axes.r * f);
    if (!(-sign * f.z() >= cop_min_n)) {  // CoP undefined: too little vertical force
      out.cop_m.push_back(nan), out.free_moment_nm.push_back(nan);
      continue;
    }
    const double cx = -x.moment.y() / f.z(), cy = x.moment.x() / f.z();
    out.cop_m.push_back(axes.centre + axes.r * V(cx, cy, 0));
    out.free_moment_nm.push_back(sign * (x.moment.z() - cx * f.y() + cy * f.x()) * axes.r.col(2));
  }
  return out;
}

}  // namespace

ForcePlates plates_from_c3d(const C3d& c3d, double cop_min_n, PlateRate rate) {
  if (!c3d.plates_problem.empty()) throw Error::in(c3d.source, c3d.plates_problem);
  if (c3d.plates.empty()) throw Error::in(c3d.source, "no force plates (FORCE_PLATFORM:USED is 0 or absent)");
  if (c3d.analog.samples() == 0) throw Error::in(c3d.source, "no analog samples for the force plates");
  ForcePlates fp;
  fp.source = c3d.source;
  const double t0 = (c3d.first_frame - 1) / c3d.points.rate_hz;
  if (rate == PlateRate::markers)
    fp.time_s = c3d.points.time_s;
  else
    for (int s = 0; s < c3d.analog.samples(); ++s) fp.time_s.push_back(t0 + s / c3d.analog.rate_hz);
  for (int i = 0; i < int(c3d.plates.size()); ++i) fp.plates.push_back(plate_forces(c3d, i, cop_min_n, rate));
  return fp;
}

ForcePlates read_force_plates(const std::string& path, double cop_min_n) {
  if (lower(std::filesystem::path(path).extension().string()) == ".c3d")
    return plates_from_c3d(read_c3d(path), cop_min_n, PlateRate::markers);
  return read_grf_mot(path);
}

}  // namespace ptnet
