// ptnet (Python): transfer with a trained model, metrics, baselines, the
// body-scale zoom.
//
// Dimension legend: T frames, H x W mat cells.
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "module.hpp"
#include "ptnet/error.hpp"
#include "ptnet/eval.hpp"
#include "ptnet/state_dict.hpp"
#include "ptnet/transfer.hpp"

namespace ptnet::python {
namespace {

// Two arrays of one shape, for a metric named `what`.
void check_same_shape(const FloatArray& a, const FloatArray& b, const char* what) {
  bool same = a.ndim() == b.ndim();
  for (py::ssize_t i = 0; same && i < a.ndim(); ++i) same = a.shape(i) == b.shape(i);
  if (!same)
    throw Error(std::string(what) + ": predicted and truth differ in shape, " + shape_text(a) + " and " + shape_text(b));
}

py::object json_object(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// ptnet.Transfer: a trained model folder.
void bind_transfer(py::module_& m) {
  py::class_<Transfer>(m, "Transfer",
                       "A trained model folder (config.json + model.pt, validated): run() transfers a pressure "
                       "sequence from one body to another, as `ptnet transfer` does.")
      .def(py::init([](const PathArg& model_dir, int stride, int batch, int threads, const std::string& device,
                       bool raw) {
             TransferOptions o;
             o.stride = stride;
             o.batch = batch;
             o.threads = threads;
             o.device = device;
             o.raw = raw;
             py::gil_scoped_release release;
             return Transfer(model_dir.string(), o);
           }),
           py::arg("model_dir"), py::arg("stride") = TransferOptions{}.stride,
           py::arg("batch") = TransferOptions{}.batch, py::arg("threads") = TransferOptions{}.threads,
           py::arg("device") = TransferOptions{}.device, py::arg("raw") = TransferOptions{}.raw)
      .def("run",
           [](const Transfer& t, const FloatArray& pressure, const py::object& source, const py::object& target) {
             const BodySpec s = body_argument(source, "source body"), d = body_argument(target, "target body");
             PressureSequence in = pressure_sequence(pressure, t.model().mat, t.model().fps, "pressure");
             PressureSequence out;
             {
               py::gil_scoped_release release;
               out = t.run(in, s, d);
             }
             return pressure_array(std::move(out));
           },
           py::arg("pressure"), py::kw_only(), py::arg("source"), py::arg("target"),
           "pressure float32 [T >= window, rows, cols] kPa recorded on `source` -> the same for `target`. "
           "Bodies: ptnet.Body or (sex, height_cm, weight_kg).")
      .def_property_readonly("config", [](const Transfer& t) { return json_object(to_json(t.model())); },
                             "config.json as a dict (architecture, normalisation, ...)")
      .def_property_readonly("window", [](const Transfer& t) { return t.model().model.window; })
      .def_property_readonly("fps", [](const Transfer& t) { return t.model().fps; })
      .def_property_readonly("arch", [](const Transfer& t) { return std::string(arch_name(t.model().model.arch)); });
}

// The metrics of `ptnet evaluate`.
void bind_metrics(py::module_& m) {
  m.def("rmse",
        [](const FloatArray& predicted, const FloatArray& truth) {
          check_same_shape(predicted, truth, "rmse");
          return rmse(predicted.data(), truth.data(), std::size_t(predicted.size()));
        },
        py::arg("predicted"), py::arg("truth"), "Root mean squared error (kPa) over all cells and frames.");
  m.def("binary_r2",
        [](const FloatArray& predicted, const FloatArray& truth, double threshold_kpa) {
          check_same_shape(predicted, truth, "binary_r2");
          return binary_r2(predicted.data(), truth.data(), std::size_t(predicted.size()), threshold_kpa);
        },
        py::arg("predicted"), py::arg("truth"), py::arg("threshold_kpa") = kContactKpa,
        "Binary R^2: both maps binarised (> threshold_kpa), 1 - SS_res / SS_tot about the truth's mean.");
  m.def("contact_iou",
        [](const FloatArray& predicted, const FloatArray& truth, double threshold_kpa) {
          check_same_shape(predicted, truth, "contact_iou");
          return contact_iou(predicted.data(), truth.data(), std::size_t(predicted.size()), threshold_kpa);
        },
        py::arg("predicted"), py::arg("truth"), py::arg("threshold_kpa") = kContactKpa,
        "Intersection over union of the binarised maps.");
  m.def("compare",
        [](const FloatArray& predicted, const FloatArray& truth, double threshold_kpa, double pitch_m) {
          check_same_shape(predicted, truth, "compare");
          const MatSpec mat{kMatRows, kMatCols, pitch_m};
          const PressureSequence p = pressure_sequence(predicted, mat, kFps, "predicted");
          const PressureSequence t = pressure_sequence(truth, mat, kFps, "truth");
          const SequenceMetrics s = compare(p, t, MetricOptions{threshold_kpa});
          py::dict d;
          d["rmse_kpa"] = s.rmse_kpa;
          d["binary_r2"] = s.binary_r2;
          d["cop_error_cm"] = s.cop_error_cm;
          d["cop_frames"] = s.cop_frames;
          d["force_error_pct"] = s.force_error_pct;
          d["contact_iou"] = s.contact_iou;
          return d;
        },
        py::arg("predicted"), py::arg("truth"), py::arg("threshold_kpa") = kContactKpa, py::arg("pitch_m") = kMatPitchM,
        "Every metric of `ptnet evaluate` (docs/results.md) of two [T, rows, cols] sequences, as a dict.");
}

// The analytic baselines and the body-scale zoom.
void bind_baselines(py::module_& m) {
  m.def("weight_ratio_baseline",
        [](const FloatArray& pressure, double source_weight_kg, double target_weight_kg) {
          return pressure_array(weight_ratio_baseline(pressure_sequence(pressure, MatSpec{}, kFps, "pressure"),
                                                      source_weight_kg, target_weight_kg));
        },
        py::arg("pressure"), py::arg("source_weight_kg"), py::arg("target_weight_kg"),
        "The paper's baseline: the source scaled by the target / source weight ratio.");
  m.def("body_scale_baseline",
        [](const FloatArray& pressure, const py::object& source, const py::object& target) {
          return pressure_array(body_scale_baseline(pressure_sequence(pressure, MatSpec{}, kFps, "pressure"),
                                                    body_argument(source, "source body"),
                                                    body_argument(target, "target body")));
        },
        py::arg("pressure"), py::kw_only(), py::arg("source"), py::arg("target"),
        "The source zoomed by the height ratio about the mat centre, scaled by weight over area ratio.");
  m.def("zoom_about_centre",
        [](const FloatArray& pressure, double scale, double gain) {
          return pressure_array(zoom_about_centre(pressure_sequence(pressure, MatSpec{}, kFps, "pressure"), scale, gain));
        },
        py::arg("pressure"), py::arg("scale"), py::arg("gain") = 1.0,
        "Each frame zoomed by `scale` about the mat centre (bilinear, outside = 0), times `gain`: "
        "the input alignment of --align zoom models (scale = target / source height, gain = body_gain).");
  m.def("body_gain", &body_gain, py::arg("source_height"), py::arg("source_weight"), py::arg("target_height"),
        py::arg("target_weight"), "Weight ratio over area ratio: the gain of the body-scale alignment.");
}

}  // namespace

void bind_model(py::module_& m) {
  bind_transfer(m);
  bind_metrics(m);
  bind_baselines(m);
  m.def("export_weights",
        [](const PathArg& model_dir, const PathArg& out_path, bool force) {
          py::gil_scoped_release release;
          export_state_dict(model_dir.string(), out_path.string(), force);
        },
        py::arg("model_dir"), py::arg("out_path"), py::arg("force") = false,
        "`ptnet export`: the model folder's weights as a PyTorch state dict (torch.load; ptnet_torch).");
  m.def("import_weights",
        [](const PathArg& weights_path, const PathArg& config_dir, const PathArg& out_dir, bool force) {
          py::gil_scoped_release release;
          import_state_dict(weights_path.string(), config_dir.string(), out_dir.string(), force);
        },
        py::arg("weights_path"), py::arg("config_dir"), py::arg("out_dir"), py::arg("force") = false,
        "`ptnet import-weights`: a state dict saved in PyTorch + config_dir's config.json -> model folder out_dir.");
}

}  // namespace ptnet::python
