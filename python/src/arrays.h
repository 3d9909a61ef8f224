// numpy arrays in and out of the library, each large array copied once.
//
// In: a mesh's V (#V x 3 positions, any real or integer dtype, any strides) and F (#F x 3
// 0-based vertex ids, any integer dtype) are read where numpy keeps them and copied once, into
// the Surface the pipeline owns (Eigen, column-major, double and int). No intermediate numpy
// array is made, whatever the dtype or the memory order.
// Out: a std::vector becomes a numpy array that owns it (no copy).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace symembed::python {

namespace py = pybind11;

// V: #V x 3, F: #F x 3; v_name, f_name: the arguments' names in messages ("VA", "FA"). Coordinates
// are copied as they are (NaN and Inf included: the pipeline's validation reports them). Throws
// py::type_error for a V dtype that is not real or integral or an F dtype that is not integral,
// InvalidInputError for another shape than (n, 3), no vertices or no faces, or a vertex id
// outside [0, #V).
Surface SurfaceFromArrays(const py::array& V, const py::array& F, const std::string& v_name,
                          const std::string& f_name);

// Bytes SurfaceFromArrays copied since the module was loaded (the tests check that each input
// array is copied exactly once).
int64_t InputBytesCopied();

// 0-based ids as a numpy int32 array owning `ids` (not copied).
py::array_t<int32_t> IdsToNumpy(std::vector<int> ids);

// A vector of doubles as a numpy float64 array owning it (not copied).
py::array_t<double> ToNumpy(std::vector<double> values);

// A copy of integer ids (any integer dtype, 1-D) as a vector; what: the argument's name.
// Throws py::type_error for another dtype, InvalidInputError for another shape or an id that is
// negative or above INT_MAX.
std::vector<int> IdsFromArray(const py::array& ids, const std::string& what);

}  // namespace symembed::python
