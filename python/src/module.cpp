// The extension module symembed._core; python/symembed/__init__.py re-exports it.
//
// The library's exceptions become Python exceptions with the same message:
//   symembed.Error (RuntimeError)        any other symembed::Error
//   symembed.ConfigError (Error, ValueError)
//   symembed.InvalidInputError (Error, ValueError)
//   symembed.IoError (Error, OSError)
//   symembed.SolverError (Error)
//   symembed.InternalError (Error)       a violated invariant: a bug
//   symembed.UsageError (Error, ValueError)  arguments run() passes on that the binary refuses
#include <pybind11/pybind11.h>

#include "apps/args.h"
#include "core/errors.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"

namespace py = pybind11;

namespace {

// The exception types, owned by the module (which lives as long as the interpreter can raise
// them); a translator is a plain function, so it finds them here.
struct ExceptionTypes {
  PyObject* error = nullptr;
  PyObject* config = nullptr;
  PyObject* input = nullptr;
  PyObject* io = nullptr;
  PyObject* solver = nullptr;
  PyObject* internal = nullptr;
  PyObject* usage = nullptr;
};
ExceptionTypes types;

void Translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const symembed::UsageError& e) {
    PyErr_SetString(types.usage, e.message.c_str());
  } catch (const symembed::ConfigError& e) {
    PyErr_SetString(types.config, e.what());
  } catch (const symembed::InvalidInputError& e) {
    PyErr_SetString(types.input, e.what());
  } catch (const symembed::IoError& e) {
    PyErr_SetString(types.io, e.what());
  } catch (const symembed::SolverError& e) {
    PyErr_SetString(types.solver, e.what());
  } catch (const symembed::InternalError& e) {
    PyErr_SetString(types.internal, e.what());
  } catch (const symembed::Error& e) {
    PyErr_SetString(types.error, e.what());
  }
}

// A new exception class symembed.NAME with the given bases, added to the module. The module
// keeps it alive; the returned handle is borrowed from it.
PyObject* AddException(py::module_& m, const char* name, py::tuple bases) {
  const std::string qualified = std::string("symembed.") + name;
  PyObject* type = PyErr_NewException(qualified.c_str(), bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::reinterpret_steal<py::object>(type));
  return type;
}

}  // namespace

PYBIND11_MODULE(_core, m) {
  m.doc() = "symembed's C++ library (symembed._core); use it through the package `symembed`.";
  const py::handle runtime_error(PyExc_RuntimeError), value_error(PyExc_ValueError),
      os_error(PyExc_OSError);
  types.error = AddException(m, "Error", py::make_tuple(runtime_error));
  const py::handle base(types.error);
  types.config = AddException(m, "ConfigError", py::make_tuple(base, value_error));
  types.input = AddException(m, "InvalidInputError", py::make_tuple(base, value_error));
  types.io = AddException(m, "IoError", py::make_tuple(base, os_error));
  types.solver = AddException(m, "SolverError", py::make_tuple(base));
  types.internal = AddException(m, "InternalError", py::make_tuple(base));
  types.usage = AddException(m, "UsageError", py::make_tuple(base, value_error));
  py::register_exception_translator(&Translate);

  symembed::python::BindMatch(m);
  symembed::python::BindEvaluation(m);
  symembed::python::BindExperiments(m);
  m.def("_input_bytes_copied", &symembed::python::InputBytesCopied,
        "bytes copied from input arrays into meshes since the module was loaded (for tests)");
}
