#include "python/src/arrays.h"

#include <atomic>
#include <cstring>
#include <limits>
#include <type_traits>

#include "core/errors.h"

namespace symembed::python {
namespace {

std::atomic<int64_t> input_bytes_copied{0};

std::string ShapeText(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) {
    text += (d ? ", " : "") + std::to_string(a.shape(d));
  }
  return text + (a.ndim() == 1 ? ",)" : ")");
}

void RequireRowsOf3(const py::array& a, const std::string& name) {
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw InvalidInputError(name + ": expected an array of shape (n, 3), got shape " +
                            ShapeText(a));
  }
  if (a.shape(0) == 0) throw InvalidInputError(name + ": no rows");
  if (a.shape(0) > std::numeric_limits<int>::max()) {
    throw InvalidInputError(name + ": more than 2^31 - 1 rows");
  }
}

// Calls f(T{}) with the C++ type of a's elements; false when the dtype is none of them.
template <typename F>
bool WithElementType(const py::array& a, bool integers_only, F&& f) {
  const char kind = a.dtype().kind();
  const py::ssize_t size = a.itemsize();
  if (kind == 'f' && !integers_only) {
    if (size == 8) return f(double{}), true;
    if (size == 4) return f(float{}), true;
  } else if (kind == 'i') {
    if (size == 8) return f(int64_t{}), true;
    if (size == 4) return f(int32_t{}), true;
    if (size == 2) return f(int16_t{}), true;
    if (size == 1) return f(int8_t{}), true;
  } else if (kind == 'u') {
    if (size == 8) return f(uint64_t{}), true;
    if (size == 4) return f(uint32_t{}), true;
    if (size == 2) return f(uint16_t{}), true;
    if (size == 1) return f(uint8_t{}), true;
  }
  return false;
}

// Element (i, j) of a 2-D array of T, through its strides.
template <typename T>
T At(const py::array& a, py::ssize_t i, py::ssize_t j) {
  const char* base = static_cast<const char*>(a.data());
  T value;
  std::memcpy(&value, base + i * a.strides(0) + j * a.strides(1), sizeof(T));
  return value;
}

// Whether id is negative (false for unsigned T, without comparing it with 0).
template <typename T>
bool Negative(T id) {
  if constexpr (std::is_signed_v<T>) {
    return id < 0;
  } else {
    return false;
  }
}

}  // namespace

Surface SurfaceFromArrays(const py::array& V, const py::array& F, const std::string& v_name,
                          const std::string& f_name) {
  RequireRowsOf3(V, v_name);
  RequireRowsOf3(F, f_name);
  Surface surface;
  const py::ssize_t n = V.shape(0), m = F.shape(0);
  surface.V.resize(n, 3);
  const bool real = WithElementType(V, false, [&](auto zero) {
    using T = decltype(zero);
    for (py::ssize_t i = 0; i < n; ++i) {
      for (int j = 0; j < 3; ++j) surface.V(i, j) = static_cast<double>(At<T>(V, i, j));
    }
  });
  if (!real) {
    throw py::type_error(v_name + ": expected real or integer coordinates, got dtype " +
                         py::str(V.dtype()).cast<std::string>());
  }
  surface.F.resize(m, 3);
  const bool integral = WithElementType(F, true, [&](auto zero) {
    using T = decltype(zero);
    for (py::ssize_t i = 0; i < m; ++i) {
      for (int j = 0; j < 3; ++j) {
        const T id = At<T>(F, i, j);
        // Compared as T, so that no id is narrowed before it is checked.
        if (Negative(id) || static_cast<uint64_t>(id) >= static_cast<uint64_t>(n)) {
          throw InvalidInputError(f_name + ": face " + std::to_string(i) + " has vertex id " +
                                  std::to_string(id) + ", outside [0, " + std::to_string(n) + ")");
        }
        surface.F(i, j) = static_cast<int>(id);
      }
    }
  });
  if (!integral) {
    throw py::type_error(f_name + ": expected integer vertex ids, got dtype " +
                         py::str(F.dtype()).cast<std::string>());
  }
  input_bytes_copied +=
      static_cast<int64_t>(surface.V.size() * sizeof(double) + surface.F.size() * sizeof(int));
  return surface;
}

int64_t InputBytesCopied() { return input_bytes_copied.load(); }

py::array_t<int32_t> IdsToNumpy(std::vector<int> ids) {
  static_assert(sizeof(int) == sizeof(int32_t), "int is 32 bits");
  auto* owned = new std::vector<int>(std::move(ids));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<int>*>(p); });
  return py::array_t<int32_t>({static_cast<py::ssize_t>(owned->size())},
                              {static_cast<py::ssize_t>(sizeof(int32_t))}, owned->data(), owner);
}

py::array_t<double> ToNumpy(std::vector<double> values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size())},
                             {static_cast<py::ssize_t>(sizeof(double))}, owned->data(), owner);
}

std::vector<int> IdsFromArray(const py::array& ids, const std::string& what) {
  if (ids.ndim() != 1) {
    throw InvalidInputError(what + ": expected a 1-D array of vertex ids, got shape " +
                            ShapeText(ids));
  }
  std::vector<int> out(ids.shape(0));
  const bool integral = WithElementType(ids, true, [&](auto zero) {
    using T = decltype(zero);
    const char* base = static_cast<const char*>(ids.data());
    for (py::ssize_t i = 0; i < ids.shape(0); ++i) {
      T id;
      std::memcpy(&id, base + i * ids.strides(0), sizeof(T));
      if (Negative(id) ||
          static_cast<uint64_t>(id) > static_cast<uint64_t>(std::numeric_limits<int>::max())) {
        throw InvalidInputError(what + ": entry " + std::to_string(i) + " is " +
                                std::to_string(id) + ", not a vertex id");
      }
      out[i] = static_cast<int>(id);
    }
  });
  if (!integral) {
    throw py::type_error(what + ": expected integer vertex ids, got dtype " +
                         py::str(ids.dtype()).cast<std::string>());
  }
  return out;
}

}  // namespace symembed::python
