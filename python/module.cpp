// The Python module `ptnet`: the library from Python (README, "Use from
// Python"; docs/python.md).
//
//   import ptnet
//   m = ptnet.read_bvh("walk.bvh")                       # m.positions [T, 19, 3] m
//   p = ptnet.simulate(m, ptnet.Body("female", 165, 60), seed=1)   # float32 [T, 80, 28] kPa
//   q = ptnet.Transfer("model/").run(p, source=("female", 165, 60), target=("male", 185, 95))
//   print(ptnet.rmse(q, p), ptnet.binary_r2(q, p))
//
// Errors: a ptnet::Error becomes the exception its kind names
// (FileNotFoundError, FileExistsError, OSError for other file failures,
// ValueError for bad input); the message is the library's one line, which is
// the CLI's without its "ptnet: error: " prefix except that it names option
// fields as the library does ("force", not "--force"). Long calls (read_bvh,
// generate_motion, simulate, Transfer, run, export) release the GIL.
#include <c10/util/Exception.h>

#include "module.hpp"
#include "ptnet/error.hpp"
#include "ptnet/strings.hpp"

namespace ptnet::python {
namespace {

PyObject* exception_of(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::not_found:
      return PyExc_FileNotFoundError;
    case ErrorKind::exists:
      return PyExc_FileExistsError;
    case ErrorKind::io:
      return PyExc_OSError;
    case ErrorKind::invalid:
    case ErrorKind::format:
      break;
  }
  return PyExc_ValueError;
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const Error& e) {
    PyErr_SetString(exception_of(e.kind()), one_line(e.what()).c_str());
  } catch (const c10::Error& e) {
    PyErr_SetString(PyExc_RuntimeError, one_line(e.what_without_backtrace()).c_str());
  }
}

}  // namespace

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

py::array_t<float> pressure_array(PressureSequence&& seq) {
  const py::ssize_t t = seq.frames(), h = seq.mat.rows, w = seq.mat.cols;
  return owned_array(std::move(seq.kpa), {t, h, w});
}

PressureSequence pressure_sequence(const FloatArray& kpa, const MatSpec& mat, double fps, const std::string& what) {
  if (kpa.ndim() != 3)
    throw Error(what + ": expected a float32 array [T, rows, cols] (kPa), found shape " + shape_text(kpa));
  MatSpec m = mat;
  m.rows = int(kpa.shape(1));
  m.cols = int(kpa.shape(2));
  PressureSequence seq;
  seq.mat = m;
  seq.fps = fps;
  seq.kpa.assign(kpa.data(), kpa.data() + kpa.size());
  check_finite(seq.kpa.data(), seq.kpa.size(), m.cells(), what, "");
  return seq;
}

BodySpec body_argument(const py::handle& value, const std::string& what) {
  if (py::isinstance<py::tuple>(value) || py::isinstance<py::list>(value)) {
    auto items = py::reinterpret_borrow<py::sequence>(value);
    if (items.size() != 3)
      throw Error(what + ": expected (sex, height_cm, weight_kg) like (\"female\", 165, 60), found " +
                  std::to_string(items.size()) + " values");
    // A number (int, float, numpy scalar); a string ("165") is not one.
    const auto number = [&](const py::handle& item, const char* field) {
      try {
        return item.cast<double>();
      } catch (const py::cast_error&) {
      }
      throw Error(what + ": " + field + ": expected a number, found " +
                  std::string(py::str(item.get_type().attr("__name__"))) + " " + std::string(py::repr(item)));
    };
    BodySpec b;
    b.id = what;
    b.sex = parse_sex(py::str(items[0]));
    b.height_cm = number(items[1], "height_cm");
    b.weight_kg = number(items[2], "weight_kg");
    return b;
  }
  try {
    return value.cast<BodySpec>();
  } catch (const py::cast_error&) {
    throw Error(what + ": expected a ptnet.Body or (sex, height_cm, weight_kg), found " +
                std::string(py::str(value.get_type().attr("__name__"))));
  }
}

}  // namespace ptnet::python

PYBIND11_MODULE(ptnet, m) {
  namespace pp = ptnet::python;
  m.doc() = "ptnet: simulated pressure-mat recordings from motion capture, and PressureTransferNet "
            "(transfer a pressure sequence between bodies). Arrays: pressure float32 [T, rows, cols] kPa.";
  m.attr("__version__") = PTNET_VERSION;
  pybind11::register_exception_translator(pp::translate);
  pp::bind_motion(m);
  pp::bind_model(m);
  pp::bind_train(m);
}
