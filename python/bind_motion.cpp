// ptnet (Python): motions, bodies and the simulator.
//
// Dimension legend: T frames, K = 19 canonical joints, H x W mat cells.
#include <pybind11/stl.h>

#include <optional>

#include "module.hpp"
#include "ptnet/body.hpp"
#include "ptnet/error.hpp"
#include "ptnet/motion.hpp"
#include "ptnet/sim.hpp"

namespace ptnet::python {
namespace {

static_assert(sizeof(Pose) == sizeof(double) * 3 * kJointCount, "Pose must be K x 3 packed doubles");

// motion.frames as a read-only float64 view [T, K, 3] (m) that keeps `self` alive.
py::array_t<double> positions_view(py::object self) {
  const Motion& mo = self.cast<const Motion&>();
  const py::ssize_t t = mo.size();
  py::array_t<double> view({t, py::ssize_t(kJointCount), py::ssize_t(3)},
                           t ? mo.frames.front()[0].data() : nullptr, self);
  view.attr("setflags")(py::arg("write") = false);
  return view;
}

std::vector<std::string> joint_names() {
  std::vector<std::string> names;
  for (int j = 0; j < kJointCount; ++j) names.emplace_back(joint_name(j));
  return names;
}

// As `ptnet simulate` does each sequence: the source motion retargeted onto
// the body's height, placed as the source is placed, scaled (place_copy).
// The pressure, and with `forces` also the force table as a dict of numpy
// arrays (time_s, total_n, left_n, right_n, left_cop_u, right_cop_u).
py::object simulate_motion(const Motion& motion, const BodySpec& spec, const SimSettings& settings,
                           bool retarget_to_body, bool forces) {
  const SimOptions options = sim_options(settings);  // `ptnet simulate`'s mapping, defaults and ranges
  PressureSequence out;
  ForceTable table;
  {
    py::gil_scoped_release release;
    const Body body(spec);  // validates
    std::vector<FrameTrace> trace;
    const Motion copy = retarget_to_body ? retarget(motion, spec.height_cm) : motion;
    const MotionPlacement place =
        retarget_to_body ? place_copy(motion, spec.height_cm, options) : place_motion(motion, options);
    out = simulate(copy, body, options, place, forces ? &trace : nullptr);
    if (forces) table = force_table(trace, copy, body);
  }
  py::array_t<float> pressure = pressure_array(std::move(out));
  if (!forces) return std::move(pressure);
  auto column = [&](auto get) {
    py::array_t<double> a(py::ssize_t(table.time_s.size()));
    for (std::size_t t = 0; t < table.time_s.size(); ++t) a.mutable_at(py::ssize_t(t)) = get(t);
    return a;
  };
  py::dict f;
  f["time_s"] = column([&](std::size_t t) { return table.time_s[t]; });
  f["total_n"] = column([&](std::size_t t) { return table.total_n[t]; });
  f["left_n"] = column([&](std::size_t t) { return table.foot_n[t][0]; });
  f["right_n"] = column([&](std::size_t t) { return table.foot_n[t][1]; });
  f["left_cop_u"] = column([&](std::size_t t) { return table.cop_u[t][0]; });
  f["right_cop_u"] = column([&](std::size_t t) { return table.cop_u[t][1]; });
  return py::make_tuple(std::move(pressure), std::move(f));
}

// ptnet.Body and the body functions.
void bind_bodies(py::module_& m) {
  py::class_<BodySpec>(m, "Body", "A body: sex, height (cm), weight (kg); id and role as in a bodies CSV.")
      .def(py::init([](const py::object& sex, double height_cm, double weight_kg, const std::string& id,
                       const std::string& role) {
             BodySpec b;
             b.sex = parse_sex(py::str(sex));
             b.height_cm = height_cm;
             b.weight_kg = weight_kg;
             b.id = id;
             b.role = role;
             validate(b);
             return b;
           }),
           py::arg("sex"), py::arg("height_cm"), py::arg("weight_kg"), py::arg("id") = "body",
           py::arg("role") = "retargeted")
      .def_property_readonly("sex", [](const BodySpec& b) { return std::string(sex_name(b.sex)); })
      .def_readonly("height_cm", &BodySpec::height_cm)
      .def_readonly("weight_kg", &BodySpec::weight_kg)
      .def_readonly("id", &BodySpec::id)
      .def_readonly("role", &BodySpec::role)
      .def("__repr__", [](const BodySpec& b) {
        return "ptnet.Body('" + std::string(sex_name(b.sex)) + "', " + number_text(b.height_cm) + ", " +
               number_text(b.weight_kg) + ", id='" + b.id + "', role='" + b.role + "')";
      });

  m.def(
      "sample_bodies",
      [](int males, int females, int originals_f, int originals_m, std::uint64_t seed, const std::string& sampling) {
        return sample_bodies(males, females, originals_f, originals_m, seed, parse_body_sampling(sampling));
      },
      py::arg("males") = 8, py::arg("females") = 8, py::arg("originals_f") = 0, py::arg("originals_m") = 0,
      py::arg("seed") = 1, py::arg("sampling") = "paper",
      "Bodies drawn as in the paper (ptnet bodies): ids f01.., m01.. (retargeted), of01.., om01.. (original); "
      "sampling 'paper' (Gaussian draws) or 'cover' (a Latin hypercube over mean +- 2.5 sd).");
  m.def("read_bodies_csv", [](const PathArg& path) { return read_bodies_csv(path.string()); }, py::arg("path"),
        "A bodies CSV (id,sex,height_cm,weight_kg[,role]).");
  m.def("sequence_seed", &sequence_seed, py::arg("seed"), py::arg("name"),
        "The sensor seed `ptnet simulate --seed SEED` gives sequence NAME (<motion_id>__<body_id>).");
}

// ptnet.simulate.
void bind_simulate(py::module_& m) {
  m.def("simulate",
        [](const Motion& motion, const py::object& body, std::uint64_t seed, const std::string& placement,
           bool retarget, int rows, int cols, double pitch_m, double compliance_mm, int subsamples, bool ideal,
           std::optional<double> crosstalk, std::optional<double> saturation_kpa, std::optional<double> noise_kpa,
           std::optional<double> threshold_kpa, std::optional<double> quantum_kpa, bool forces) {
          const BodySpec spec = body_argument(body, "body");
          SimSettings a;
          a.seed = seed;
          a.placement = placement;
          a.rows = rows;
          a.cols = cols;
          a.pitch_m = pitch_m;
          a.compliance_mm = compliance_mm;
          a.subsamples = subsamples;
          a.ideal_sensor = ideal;
          a.crosstalk = crosstalk;
          a.saturation_kpa = saturation_kpa;
          a.noise_kpa = noise_kpa;
          a.threshold_kpa = threshold_kpa;
          a.quantum_kpa = quantum_kpa;
          return simulate_motion(motion, spec, a, retarget, forces);
        },
        py::arg("motion"), py::arg("body"), py::kw_only(), py::arg("seed") = SimSettings{}.seed,
        py::arg("placement") = SimSettings{}.placement, py::arg("retarget") = true, py::arg("rows") = SimSettings{}.rows,
        py::arg("cols") = SimSettings{}.cols, py::arg("pitch_m") = SimSettings{}.pitch_m,
        py::arg("compliance_mm") = SimSettings{}.compliance_mm, py::arg("subsamples") = SimSettings{}.subsamples,
        py::arg("ideal_sensor") = SimSettings{}.ideal_sensor, py::arg("crosstalk") = py::none(), py::arg("saturation_kpa") = py::none(),
        py::arg("noise_kpa") = py::none(), py::arg("threshold_kpa") = py::none(),
        py::arg("quantum_kpa") = py::none(), py::arg("forces") = false,
        "The motion on the body, pressed onto the mat: float32 [T, rows, cols] kPa; with forces=True, "
        "(pressure, forces) where forces is a dict of float64 [T] arrays: time_s, total_n, left_n, right_n, "
        "left_cop_u, right_cop_u (the simulated ground reaction, `ptnet simulate --forces`). With retarget (the default) "
        "the motion is the source clip, retargeted onto the body's height and placed as `ptnet simulate` places "
        "it, so simulate(m, body, seed=sequence_seed(S, name)) equals the CLI's sequence NAME with --seed S. "
        "Options and sensor defaults: docs/simulate.md.");
}

// ptnet.Motion: its frames as a numpy view, retarget, write_bvh.
void bind_motion_class(py::module_& m) {
  py::class_<Motion>(m, "Motion",
                     "A motion on the canonical skeleton: world joint positions (m, z up, ground z = 0) at fps.")
      .def_readonly("name", &Motion::name)
      .def_readonly("fps", &Motion::fps)
      .def_readonly("start_s", &Motion::start_s, "time of frame 0 on the recording's clock (s)")
      .def("__len__", &Motion::size)
      .def_property_readonly("frames", &Motion::size)
      .def_property_readonly("positions", &positions_view, "float64 [T, 19, 3] world joint positions (m), read-only view")
      .def_property_readonly_static("joint_names", [](py::object) { return joint_names(); },
                                    "the 19 canonical joint names, in the order of positions' axis 1")
      .def("retarget", [](const Motion& mo, double height_cm) {
            py::gil_scoped_release release;
            return retarget(mo, height_cm);
          }, py::arg("height_cm"), "The motion on a body of height_cm (bone lengths replaced, rotations kept).")
      .def("write_bvh", [](const Motion& mo, const PathArg& path, bool force) {
            write_bvh(motion_to_bvh(mo), path.string(), force);
          }, py::arg("path"), py::arg("force") = false, "Writes the motion as BVH (canonical skeleton, cm, y up).")
      .def("__repr__", [](const Motion& mo) {
        return "<ptnet.Motion '" + mo.name + "': " + std::to_string(mo.size()) + " frames at " +
               number_text(mo.fps) + " fps>";
      });
}

// read_bvh and read_motion (BVH or .trc markers).
void bind_motion_files(py::module_& m) {
  m.def("read_bvh",
        [](const PathArg& path, const std::string& units, const std::string& up, double fps,
           double metres_per_unit, bool keep_tpose) {
          MotionOptions o;
          o.units = parse_units(units);
          o.up = parse_up_axis(up);
          o.fps = fps;
          o.metres_per_unit = metres_per_unit;
          o.keep_tpose = keep_tpose;
          py::gil_scoped_release release;
          return load_motion(path.string(), o);
        },
        py::arg("path"), py::arg("units") = "auto", py::arg("up") = "y", py::arg("fps") = kFps,
        py::arg("metres_per_unit") = 0.0, py::arg("keep_tpose") = false,
        "Reads a BVH file onto the canonical joints, resampled to fps (<= 0 keeps the file's), grounded. "
        "units: auto|m|cm|mm|in|cmu; up: y|z.");

  m.def("read_motion",
        [](const PathArg& path, double fps, const PathArg& marker_map, const PathArg& static_markers,
           double max_gap_s, bool remove_belt, const std::string& units, const std::string& up) {
          MotionOptions o;
          o.fps = fps;
          o.marker_map = marker_map.string();
          o.static_markers = static_markers.string();
          o.max_gap_s = max_gap_s;
          o.remove_belt = remove_belt;
          o.units = parse_units(units);
          o.up = parse_up_axis(up);
          py::gil_scoped_release release;
          return load_motion(path.string(), o);
        },
        py::arg("path"), py::kw_only(), py::arg("fps") = kFps, py::arg("marker_map") = "",
        py::arg("static") = "", py::arg("max_gap_s") = MotionOptions{}.max_gap_s,
        py::arg("remove_belt") = MotionOptions{}.remove_belt, py::arg("units") = "auto", py::arg("up") = "y",
        "Reads a motion file onto the canonical joints: BVH (units, up as read_bvh) or markers (OpenSim .trc, C3D .c3d: "
        "marker_map a shipped map's name or a map file, '' chooses; static the standing trial that calibrates "
        "missing joint markers; gaps up to max_gap_s filled), resampled to fps (<= 0 keeps the file's), "
        "grounded, a treadmill belt removed (remove_belt).");
}

// generate_motion.
void bind_generate(py::module_& m) {
  m.def("generate_motion",
        [](const std::string& category, int performer, int take, double seconds, std::uint64_t seed, double fps,
           double height_cm) {
          GenerateOptions g;
          g.category = parse_category(category);
          g.performer = performer;
          g.take = take;
          g.seconds = seconds;
          g.seed = seed;
          g.fps = fps;
          g.height_cm = height_cm;
          py::gil_scoped_release release;
          Motion mo = generate_motion(g);
          mo.name = motion_id(performer, g.category, take);
          return mo;
        },
        py::arg("category") = "walking", py::arg("performer") = 1, py::arg("take") = 1, py::arg("seconds") = 10.0,
        py::arg("seed") = 0, py::arg("fps") = kFps, py::arg("height_cm") = 0.0,
        "A procedural clip (walking|rom|freestyle|acting), named p<P>_<category>_t<T> as in ptnet's datasets; "
        "height_cm 0: the performer's own.");
}

}  // namespace

void bind_motion(py::module_& m) {
  bind_motion_class(m);
  bind_motion_files(m);
  bind_generate(m);
  bind_bodies(m);
  bind_simulate(m);
}

}  // namespace ptnet::python
