// ptnet (Python): training, as `ptnet train` does it: a preset with
// overrides (TrainOverrides; None keeps the preset's value), checked by the
// library's check_options before the data is opened.
#include <pybind11/stl.h>

#include <optional>

#include "module.hpp"
#include "ptnet/train.hpp"

namespace ptnet::python {

void bind_train(py::module_& m) {
  m.def("train",
        [](const std::string& data, const std::string& out, const std::string& preset, std::optional<int> epochs,
           std::optional<int> batch, std::optional<double> lr, std::optional<std::uint64_t> seed,
           std::optional<int> threads, std::optional<std::string> arch, std::optional<int> window,
           std::optional<double> contact_weight, std::optional<std::int64_t> samples_per_epoch,
           std::optional<std::int64_t> val_samples, bool resume, const std::string& init, bool identity_pairs,
           bool force) {
          TrainOverrides v;
          v.epochs = epochs;
          v.batch = batch;
          v.lr = lr;
          v.seed = seed;
          v.threads = threads;
          if (arch) v.arch = parse_arch(*arch);
          v.window = window;
          v.contact_weight = contact_weight;
          v.samples_per_epoch = samples_per_epoch;
          v.val_samples = val_samples;
          TrainOptions o = TrainOptions::from_preset(preset, v);
          o.resume = resume;
          o.init = init;
          o.identity_pairs = identity_pairs;
          o.force = force;
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
          return d;
        },
        py::arg("data"), py::arg("out"), py::kw_only(), py::arg("preset") = "paper", py::arg("epochs") = py::none(),
        py::arg("batch") = py::none(), py::arg("lr") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = py::none(), py::arg("arch") = py::none(), py::arg("window") = py::none(),
        py::arg("contact_weight") = py::none(), py::arg("samples_per_epoch") = py::none(),
        py::arg("val_samples") = py::none(), py::arg("resume") = false, py::arg("init") = "",
        py::arg("identity_pairs") = false, py::arg("force") = false,
        "`ptnet train`: the preset (paper | fast | full) with the given options (None: the preset's) on the "
        "dataset file `data`, into the model folder `out`; returns the run's summary as a dict. The same "
        "checks as the CLI: resume and init exclude each other, a contact weight needs the frame network.");
}

}  // namespace ptnet::python
