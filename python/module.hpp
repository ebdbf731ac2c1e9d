// The Python module `ptnet` (pybind11): what its binding files share.
//
// Dimension legend: T frames, H x W = mat rows x cols (80 x 28), K = 19
// canonical joints.
//
// Arrays: results are numpy arrays that own the library's buffer (moved into a
// capsule, no copy); a pressure argument is used as given when it is a
// C-contiguous float32 array (numpy converts anything else once) and copied
// once into the library's PressureSequence.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include <string>
#include <vector>

#include "ptnet/body_spec.hpp"
#include "ptnet/pressure.hpp"

namespace ptnet::python {
namespace py = pybind11;

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// Every path argument: a str or any os.PathLike (pathlib.Path), as Python's
// own open() takes; .string() for the library. "" stays "" (not given).
using PathArg = std::filesystem::path;

// A numpy array of `shape` owning `data` (moved, not copied).
template <typename T>
py::array_t<T> owned_array(std::vector<T>&& data, const std::vector<py::ssize_t>& shape) {
  auto* owner = new std::vector<T>(std::move(data));
  py::capsule free_it(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), free_it);
}

// "(30, 80, 28)": an array's shape for messages.
std::string shape_text(const py::array& a);
// seq.kpa as float32 [T, H, W] (moved out of seq).
py::array_t<float> pressure_array(PressureSequence&& seq);
// A float32 [T, H, W] kPa array as a sequence on `mat` (rows and cols from the
// array, pitch from `mat`) at `fps`; throws Error "WHAT: expected ..." for
// another shape and for NaN or Inf.
PressureSequence pressure_sequence(const FloatArray& kpa, const MatSpec& mat, double fps, const std::string& what);
// A body argument: a ptnet.Body, or a tuple (sex, height_cm, weight_kg) with
// sex "female"/"male" or 0/1; `what` names it in errors.
BodySpec body_argument(const py::handle& value, const std::string& what);

void bind_motion(py::module_& m);  // bind_motion.cpp: Motion, read_bvh, generate_motion, Body, simulate
void bind_model(py::module_& m);   // bind_model.cpp: Transfer, metrics, baselines, zoom, export
void bind_train(py::module_& m);   // bind_train.cpp: train

}  // namespace ptnet::python
