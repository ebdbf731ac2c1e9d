// ptnet (Python): training, as `ptnet train` does it: a preset with
// overrides (TrainOverrides; None keeps the preset's value), checked by the
// library's check_options before the data is opened.
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "module.hpp"
#include "ptnet/train.hpp"

namespace ptnet::python {
namespace {

// Every TrainOverrides field by its name, the keyword Python passes it as
// (None keeps the preset's value).
template <class T>
void set(std::optional<T>& field, py::handle value) {
  field = value.cast<T>();
}

TrainOverrides overrides_from(const py::kwargs& kwargs) {
  using Setter = void (*)(TrainOverrides&, py::handle);
  static const std::vector<std::pair<const char*, Setter>> fields = {
      {"epochs", [](TrainOverrides& v, py::handle h) { set(v.epochs, h); }},
      {"batch", [](TrainOverrides& v, py::handle h) { set(v.batch, h); }},
      {"micro_batch", [](TrainOverrides& v, py::handle h) { set(v.micro_batch, h); }},
      {"lr", [](TrainOverrides& v, py::handle h) { set(v.lr, h); }},
      {"lr_halve_every", [](TrainOverrides& v, py::handle h) { set(v.lr_halve_every, h); }},
      {"patience", [](TrainOverrides& v, py::handle h) { set(v.patience, h); }},
      {"seed", [](TrainOverrides& v, py::handle h) { set(v.seed, h); }},
      {"threads", [](TrainOverrides& v, py::handle h) { set(v.threads, h); }},
      {"stride", [](TrainOverrides& v, py::handle h) { set(v.stride, h); }},
      {"crop_rows", [](TrainOverrides& v, py::handle h) { set(v.crop_rows, h); }},
      {"cache_mb", [](TrainOverrides& v, py::handle h) { set(v.cache_mb, h); }},
      {"contact_weight", [](TrainOverrides& v, py::handle h) { set(v.contact_weight, h); }},
      {"samples_per_epoch", [](TrainOverrides& v, py::handle h) { set(v.samples_per_epoch, h); }},
      {"val_samples", [](TrainOverrides& v, py::handle h) { set(v.val_samples, h); }},
      {"arch", [](TrainOverrides& v, py::handle h) { v.arch = parse_arch(h.cast<std::string>()); }},
      {"align", [](TrainOverrides& v, py::handle h) { v.align = parse_align(h.cast<std::string>()); }},
      {"loss", [](TrainOverrides& v, py::handle h) { v.loss = parse_loss(h.cast<std::string>()); }},
      {"channels", [](TrainOverrides& v, py::handle h) { set(v.channels, h); }},
      {"hidden", [](TrainOverrides& v, py::handle h) { set(v.hidden, h); }},
      {"latent", [](TrainOverrides& v, py::handle h) { set(v.latent, h); }},
      {"window", [](TrainOverrides& v, py::handle h) { set(v.window, h); }},
      {"context", [](TrainOverrides& v, py::handle h) { set(v.context, h); }},
      {"mirror", [](TrainOverrides& v, py::handle h) { set(v.mirror, h); }},
  };
  TrainOverrides v;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const auto it = std::find_if(fields.begin(), fields.end(), [&](const auto& f) { return name == f.first; });
    if (it == fields.end()) throw py::type_error("train() got an unexpected keyword argument '" + name + "'");
    if (!value.is_none()) it->second(v, value);
  }
  return v;
}

}  // namespace

void bind_train(py::module_& m) {
  m.def("train",
        [](const PathArg& data_path, const PathArg& out_path, const std::string& preset, bool resume,
           const PathArg& init, bool identity_pairs, bool force, bool strict, const py::kwargs& overrides) {
          TrainOptions o = TrainOptions::from_preset(preset, overrides_from(overrides));
          o.resume = resume;
          o.init = init.string();
          const std::string data = data_path.string(), out = out_path.string();
          o.identity_pairs = identity_pairs;
          o.force = force;
          o.strict = strict;
          check_options(o);
          TrainResult r;
          {
            py::gil_scoped_release release;
            const auto source = open_dataset_source(data);
            r = ptnet::train(*source, out, o);
          }
          py::dict d;
          d["epochs_run"] = r.epochs_run;
          d["best_epoch"] = r.best_epoch;
          d["best_val_loss"] = r.best_val_loss;
          d["val_rmse_kpa"] = r.val_rmse_kpa;
          d["stopped_early"] = r.stopped_early;
          d["seconds"] = r.seconds;
          d["warning"] = r.warning;
          if (!r.warning.empty() && PyErr_WarnEx(PyExc_UserWarning, (out + ": " + r.warning).c_str(), 1) < 0)
            throw py::error_already_set();  // warnings turned into errors
          return d;
        },
        py::arg("data"), py::arg("out"), py::kw_only(), py::arg("preset") = "paper", py::arg("resume") = false,
        py::arg("init") = "", py::arg("identity_pairs") = false, py::arg("force") = false, py::arg("strict") = false,
        "`ptnet train`: the preset (paper | fast | full) with any option of TrainOverrides as a keyword "
        "(epochs, batch, micro_batch, lr, lr_halve_every, patience, seed, threads, stride, crop_rows, "
        "cache_mb, contact_weight, samples_per_epoch, val_samples, arch, align, loss, channels, hidden, "
        "latent, window, context, mirror; None: the preset's) on the dataset file `data`, into the model "
        "folder `out`; returns the run's summary as a dict. The same checks as the CLI: resume and init "
        "exclude each other, a contact weight needs the frame network. A model no better than the all-zero "
        "or copy baseline on validation is a UserWarning (and the dict's \"warning\"), a ValueError with "
        "strict=True (the folder is kept).");
}

}  // namespace ptnet::python
