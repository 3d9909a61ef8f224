// The parts of the extension module symembed._core, each registered by its own file.
#pragma once

#include <pybind11/pybind11.h>

namespace symembed::python {

namespace py = pybind11;

void BindMatch(py::module_& m);        // Shape, MatchResult, match (match.cpp)
void BindEvaluation(py::module_& m);   // geodesic_errors, error_curve (evaluation.cpp)
void BindExperiments(py::module_& m);  // run, stages (experiments.cpp)

}  // namespace symembed::python
