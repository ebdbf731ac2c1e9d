// The physics bench: a gait-lab trial simulated on a body of the subject's
// sex, stature and mass, its forces set beside the trial's force plates and
// beside the naive reference (body weight shared by the feet the simulator
// puts in contact), on the trial's clock.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "core/anthropometry.hpp"
#include "core/csv.hpp"
#include "plates_internal.hpp"
#include "ptnet/error.hpp"
#include "ptnet/io.hpp"
#include "ptnet/markers.hpp"
#include "ptnet/strings.hpp"

namespace ptnet {
namespace fs = std::filesystem;

PlateCoverage parse_plate_coverage(const std::string& text) {
  if (text == "auto") return PlateCoverage::automatic;
  if (text == "all") return PlateCoverage::all;
  if (text == "some") return PlateCoverage::some;
  throw Error("plate coverage '" + text + "' is not auto, all or some");
}

const char* plate_coverage_name(PlateCoverage coverage) {
  switch (coverage) {
    case PlateCoverage::automatic: return "auto";
    case PlateCoverage::all: return "all";
    case PlateCoverage::some: return "some";
  }
  return "auto";
}

PhysicsBenchOptions::PhysicsBenchOptions() {
  sim.placement = Placement::follow;
  sim.sensor = ideal_sensor();
}

std::string gait_trial_columns_text() {
  std::string required, optional;
  for (const GaitTrialColumn& c : kGaitTrialColumns) (c.required ? required : optional) += std::string(",") + c.name;
  return required.substr(1) + (optional.empty() ? "" : "[" + optional + "]");
}

namespace {

// A file named in a trials CSV's row: resolved against `base` and checked as
// InputFile will open it (absent, a folder, a FIFO: said at its row).
std::string trial_file(const std::string& csv, long line, const char* column, const std::string& base,
                       const std::string& name, bool required) {
  if (required && name.empty()) throw Error::at(csv, line, std::string("a file in column ") + column, "an empty field");
  return listed_input(csv, line, column, base, name);  // no output of the bench may replace it
}

// Each trial's name is a file name of the report (TRIAL_sim.mot, ...) and
// names one trial only: checked before any trial runs.
void check_trial_name(const std::string& csv, long line, const std::string& name,
                      std::map<std::string, long>& seen) {
  if (const std::string problem = name_problem(name); !problem.empty())
    throw Error::at(csv, line, "a trial name that is a file name (it names the trial's outputs)",
                    escaped(name) + ", which " + problem);
  const auto [it, fresh] = seen.emplace(name, line);
  if (!fresh)
    throw Error::at(csv, line, "a trial name of its own", escaped(name) + ", the name of line " +
                                                          std::to_string(it->second) + "'s trial too");
}

// The header names only columns of kGaitTrialColumns (a misspelt optional
// column would be ignored: "unit" for units).
void check_trial_columns(const CsvTable& t, const std::string& columns) {
  for (const std::string& name : t.header) {
    const bool known = std::any_of(std::begin(kGaitTrialColumns), std::end(kGaitTrialColumns),
                                   [&](const GaitTrialColumn& c) { return name == c.name; });
    if (!known) throw Error::at(t.source, t.header_line, "only the columns " + columns, "column " + escaped(name));
  }
}

// A row's optional fields: the coverage and the markers' units.
void read_trial_options(const std::string& csv, long line, const std::string& coverage, const std::string& units,
                        GaitTrial& g) {
  if (!coverage.empty()) try {
      g.coverage = parse_plate_coverage(coverage);
    } catch (const Error&) {
      throw Error::at(csv, line, "coverage auto, all or some", escaped(coverage));
    }
  if (!units.empty()) try {
      g.units = parse_units(units);
    } catch (const Error&) {
      throw Error::at(csv, line, "units auto, m, cm, mm, in or cmu", escaped(units));
    }
}

}  // namespace

std::vector<GaitTrial> read_gait_trials(const std::string& csv, const std::string& data_dir) {
  const CsvTable t = read_csv(csv);
  const std::string columns = gait_trial_columns_text();
  std::map<std::string, int> c;
  for (const GaitTrialColumn& col : kGaitTrialColumns)
    c[col.name] = col.required ? t.required(col.name, columns) : t.column(col.name);
  check_trial_columns(t, columns);
  const std::string base = data_dir.empty() ? fs::path(csv).parent_path().string() : data_dir;
  std::vector<GaitTrial> out;
  std::map<std::string, long> names;
  for (const CsvRow& row : t.rows) {
    auto get = [&](const char* column) -> const std::string& { return CsvTable::field(row, c.at(column)); };
    GaitTrial g;
    g.name = get("trial");
    check_trial_name(csv, row.line, g.name, names);
    g.markers = trial_file(csv, row.line, "markers", base, get("markers"), true);
    g.plates = trial_file(csv, row.line, "plates", base, get("plates"), false);  // "": the markers' own (a .c3d file's)
    if (g.plates.empty() && lower(fs::path(g.markers).extension().string()) != ".c3d")
      throw Error::at(csv, row.line, "a plates file (or markers in a .c3d file, which holds its plates)", "an empty field");
    g.static_markers = trial_file(csv, row.line, "static", base, get("static"), false);
    g.marker_map = marker_map_in(csv, row.line, base, get("marker_map"));
    read_trial_options(csv, row.line, get("coverage"), get("units"), g);
    g.body = parse_body_fields(csv, row.line, g.name, get("sex"), get("height_cm"), get("weight_kg"));
    g.body.role = "original";
    out.push_back(std::move(g));
  }
  if (out.empty()) throw Error::in(csv, "no trials listed after the header");
  return out;
}

namespace {

using V2 = Eigen::Vector2d;

// Distance from p to the segment a-b (horizontal).
double segment_distance(const V2& p, const V2& a, const V2& b) {
  const V2 d = b - a;
  const double s = d.squaredNorm() > 0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

// The plates per foot at their own rate: vertical force (N) and the force
// times the CoP along the foot (N), each plate's force given to the foot
// nearest its CoP, the foot's height above the floor counted as distance
// (none beyond assign_m).
struct PlateFeet {
  std::array<std::vector<double>, 2> force_n, force_u;
  std::vector<double> total_n;
};

PlateFeet plate_feet(const ForcePlates& fp, const Motion& lab, int up, const PhysicsBenchOptions& o) {
  const std::size_t N = fp.time_s.size();
  PlateFeet out;
  out.total_n.assign(N, 0.0);
  for (auto* v : {&out.force_n[0], &out.force_n[1], &out.force_u[0], &out.force_u[1]}) v->assign(N, 0.0);
  // Lab (Y up: x, y, z) -> world (z, x, y), as the marker file's motion.
  auto horizontal = [&](const Eigen::Vector3d& p) { return up == 1 ? V2(p.z(), p.x()) : V2(p.x(), p.y()); };
  for (std::size_t k = 0; k < N; ++k) {
    const int f = std::clamp(int(std::lround((fp.time_s[k] - lab.start_s) * lab.fps)), 0, lab.size() - 1);
    std::array<std::array<Eigen::Vector3d, 2>, 2> ends{foot_ends(lab.frames[std::size_t(f)], 0),
                                                       foot_ends(lab.frames[std::size_t(f)], 1)};
    for (const auto& plate : fp.plates) {
      const double fv = plate.force_n[k][up];
      out.total_n[k] += fv;
      if (!(fv > o.contact_n)) continue;
      const V2 cop = horizontal(plate.cop_m[k]);
      double best = o.assign_m;
      int foot = -1;
      // The nearest foot on the ground: a foot's height above the floor
      // counts as distance (a swing foot passing over the stance foot's CoP).
      for (int s = 0; s < 2; ++s) {
        const double height = std::max(0.0, std::min(ends[s][0].z(), ends[s][1].z()));
        const double d = segment_distance(cop, ends[s][0].head<2>(), ends[s][1].head<2>()) + height;
        if (d < best) best = d, foot = s;
      }
      if (foot < 0) continue;
      const V2 heel = ends[foot][0].head<2>(), axis = ends[foot][1].head<2>() - heel;
      const double u = axis.squaredNorm() > 0 ? (cop - heel).dot(axis) / axis.squaredNorm() : NAN;
      out.force_n[foot][k] += fv;
      out.force_u[foot][k] += fv * u;
    }
  }
  return out;
}

// The plates' samples within the markers' time span [t0, t1] (1 us either
// side: times written to 6 decimals): a contact that runs past either end
// of the markers is cut in the plates as in the simulation, so neither
// counts it whole, and no plate sample is given to a foot the markers no
// longer place.
ForcePlates within_span(ForcePlates fp, double t0, double t1) {
  constexpr double kSlackS = 1e-6;
  const std::vector<double>& t = fp.time_s;
  const auto a = std::lower_bound(t.begin(), t.end(), t0 - kSlackS) - t.begin();
  const auto b = std::max(a, std::upper_bound(t.begin(), t.end(), t1 + kSlackS) - t.begin());
  const std::size_t N = t.size();
  auto cut = [&](auto& v) {
    if (v.size() == N) v = std::decay_t<decltype(v)>(v.begin() + a, v.begin() + b);
  };
  for (ForcePlates::Plate& p : fp.plates) {
    cut(p.force_n);
    cut(p.cop_m);
    cut(p.free_moment_nm);
  }
  cut(fp.time_s);
  return fp;
}

// The contacts of each foot's force ([2][N], N) at times `time_s` ([N]),
// in the order they start.
std::vector<Contact> foot_contacts(const std::vector<double>& time_s, const std::array<std::vector<double>, 2>& feet_n,
                                   double contact_n) {
  std::vector<Contact> out;
  for (int k = 0; k < 2; ++k)
    for (const Contact& c : find_contacts(time_s, feet_n[std::size_t(k)], contact_n, k)) out.push_back(c);
  std::sort(out.begin(), out.end(), [](const Contact& a, const Contact& b) { return a.start_s < b.start_s; });
  return out;
}

ForceSource plates_source(const ForcePlates& fp, const PlateFeet& pf, const std::vector<double>& time_s, double dt,
                          double bw, const PhysicsBenchOptions& o) {
  ForceSource s;
  s.name = "plates";
  const std::vector<double> total = detail::resample_box(fp.time_s, pf.total_n, time_s, dt);
  std::array<std::vector<double>, 2> f, fu;
  for (int k = 0; k < 2; ++k) {
    f[k] = detail::resample_box(fp.time_s, pf.force_n[k], time_s, dt);
    fu[k] = detail::resample_box(fp.time_s, pf.force_u[k], time_s, dt);
  }
  for (std::size_t t = 0; t < time_s.size(); ++t) {
    s.total_bw.push_back(total[t] / bw);
    std::array<double, 2> fb{}, u{};
    for (int k = 0; k < 2; ++k) {
      fb[k] = f[k][t] / bw;
      u[k] = f[k][t] > o.contact_n ? fu[k][t] / f[k][t] : NAN;
    }
    s.foot_bw.push_back(fb);
    s.cop_u.push_back(u);
  }
  s.contacts = foot_contacts(fp.time_s, pf.force_n, o.contact_n);
  return s;
}

// A source named `name` over the frames of `table`: `frame(t, fb, u)` gives
// frame t's per-foot load (BW) and CoP along the foot and returns its total
// (BW); the contacts are the feet's loads above o.contact_n.
template <class Frame>
ForceSource source_over(const char* name, const ForceTable& table, double bw, const PhysicsBenchOptions& o,
                        Frame frame) {
  ForceSource s;
  s.name = name;
  std::array<std::vector<double>, 2> feet;
  for (std::size_t t = 0; t < table.time_s.size(); ++t) {
    std::array<double, 2> fb{}, u{};
    s.total_bw.push_back(frame(t, fb, u));
    for (std::size_t k = 0; k < 2; ++k) feet[k].push_back(fb[k] * bw);
    s.foot_bw.push_back(fb);
    s.cop_u.push_back(u);
  }
  s.contacts = foot_contacts(table.time_s, feet, o.contact_n);
  return s;
}

// The simulator's force (ForceTable) as a source.
ForceSource simulated_source(const ForceTable& table, double bw, const PhysicsBenchOptions& o) {
  return source_over("simulated", table, bw, o, [&](std::size_t t, std::array<double, 2>& fb, std::array<double, 2>& u) {
    for (std::size_t k = 0; k < 2; ++k) {
      fb[k] = table.foot_n[t][k] / bw;
      u[k] = table.cop_u[t][k];
    }
    return table.total_n[t] / bw;
  });
}

// The naive reference: one body weight shared by the feet the simulator
// puts in contact, each pressing at its middle.
ForceSource naive_source(const ForceTable& table, double bw, const PhysicsBenchOptions& o) {
  return source_over("naive", table, bw, o, [&](std::size_t t, std::array<double, 2>& fb, std::array<double, 2>& u) {
    const bool on[2] = {table.foot_n[t][0] > o.contact_n, table.foot_n[t][1] > o.contact_n};
    const int count = on[0] + on[1];
    for (std::size_t k = 0; k < 2; ++k) {
      fb[k] = on[k] ? 1.0 / count : 0.0;
      u[k] = on[k] ? 0.5 : NAN;
    }
    return count ? 1.0 : 0.0;
  });
}

// What a source's figures are compared by: the thresholds of `o` for a
// body of weight `bw` (N).
detail::CompareOptions compare_options(const PhysicsBenchOptions& o, double bw) {
  detail::CompareOptions co;
  co.flight_bw = o.flight_bw;
  co.contact_bw = o.contact_n / bw;
  co.weight_n = bw;
  return co;
}

// The frames the figures are over (GaitTrial::coverage): all of them when
// the plates see every step; else all but those of the simulator's stances
// that the plates do not see (their foot loaded on a plate in under half of
// the contact's frames: a foot beside the plates, on a box, ...), whole, so
// that no contact is cut where the two disagree on its ends. A stance
// carries CompareOptions::stance_bw at its peak; a lighter contact (a swing
// foot grazing the floor) is the simulator's to answer for, and stays compared.
void choose_compared_frames(GaitTrialResult& r, PlateCoverage coverage, const detail::CompareOptions& co) {
  const double contact_bw = co.contact_bw, bw = co.weight_n;
  constexpr double kCarriedBw = 0.02;
  const std::size_t T = r.time_s.size();
  std::vector<bool> seen(T, true);
  bool missed = false;
  for (const Contact& c : r.simulated.contacts) {
    std::vector<std::size_t> frames;
    int on_plate = 0;
    for (std::size_t t = 0; t < T; ++t)
      if (r.time_s[t] >= c.start_s && r.time_s[t] <= c.end_s) {
        frames.push_back(t);
        on_plate += r.plates.foot_bw[t][std::size_t(c.foot)] > contact_bw;
      }
    if (frames.empty() || 2 * on_plate >= int(frames.size()) || c.peak_n < co.stance_bw * bw) continue;
    missed = true;
    for (std::size_t t : frames) seen[t] = false;
  }
  const bool some = coverage == PlateCoverage::some || (coverage == PlateCoverage::automatic && missed);
  r.coverage = some ? PlateCoverage::some : PlateCoverage::all;
  r.compared = some ? seen : std::vector<bool>(T, true);
  // Frames a seat carries (MotionDynamics::carried): the plates under the
  // feet see what is left of the load, the simulator's seat share is a model.
  r.carried_frames = 0;
  for (std::size_t t = 0; t < T; ++t)
    if (r.table.carried_n[t] > kCarriedBw * bw) r.compared[t] = false, ++r.carried_frames;
}

}  // namespace

GaitTrialResult run_gait_trial(const GaitTrial& trial, const PhysicsBenchOptions& o) {
  const Trc trc = read_markers(trial.markers);
  MotionOptions mo;
  mo.fps = o.fps > 0 ? o.fps : trc.rate_hz;
  mo.static_markers = trial.static_markers;
  mo.marker_map = trial.marker_map;
  mo.units = trial.units;
  mo.remove_belt = false;  // the lab's positions, where the plates' CoP is
  MarkerReport report;
  const Motion lab = motion_from_trc(trc, mo, &report);  // once, the static trial with it
  const Motion source = without_belt(lab, report.belt_velocity_mps);  // the belt the pipeline found taken out
  const Body body(trial.body);
  const double h = trial.body.height_cm;
  std::vector<FrameTrace> trace;
  simulate(retarget(source, h), body, o.sim, place_copy(source, h, o.sim), &trace);

  GaitTrialResult r;
  r.trial = trial;
  r.fps = source.fps;
  r.belt_mps = report.belt_speed_mps;
  r.table = force_table(trace, lab, body);  // each foot's CoP in the lab, as the plates'
  r.time_s = r.table.time_s;
  const double bw = body.mass_kg() * anthropometry::kGravity;
  ForcePlates fp = read_force_plates(trial.plates.empty() ? trial.markers : trial.plates, o.contact_n);
  if (!r.time_s.empty()) fp = within_span(std::move(fp), r.time_s.front(), r.time_s.back());
  const int up = report.up_axis == UpAxis::y ? 1 : 2;
  r.plates = plates_source(fp, plate_feet(fp, lab, up, o), r.time_s, 1 / r.fps, bw, o);
  r.simulated = simulated_source(r.table, bw, o);
  r.naive = naive_source(r.table, bw, o);
  const detail::CompareOptions co = compare_options(o, bw);
  choose_compared_frames(r, trial.coverage, co);
  detail::compare_with_plates(r.simulated, r.plates, {r.time_s, r.compared}, co);
  detail::compare_with_plates(r.naive, r.plates, {r.time_s, r.compared}, co);
  for (std::size_t t = 0; t < r.time_s.size(); ++t) {
    if (!r.compared[t]) continue;
    r.flight_frames += r.plates.total_bw[t] < o.flight_bw;
    r.single_stance_frames += (r.plates.foot_bw[t][0] > co.contact_bw) != (r.plates.foot_bw[t][1] > co.contact_bw);
  }
  return r;
}

}  // namespace ptnet
