// Fuzz target of the ground-truth readers of the pairs_vts layout: `.vts` / `.sym.vts` files
// (one integer per line, eval/datasets/dataset_files.h ParseIntegerLines) turned into vertex
// ids of a mesh whose vertex count the first byte chooses (1 + 64 * byte; OneBasedIds).
#include <cstdlib>

#include "core/errors.h"
#include "eval/datasets/dataset_files.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int num_vertices = 1 + 64 * data[0];
  try {
    const std::vector<long long> values =
        symembed::ParseIntegerLines(symembed::fuzz::Text(data + 1, size - 1), "fuzz.vts");
    const std::vector<int> ids = symembed::OneBasedIds(values, "fuzz.vts", num_vertices, true);
    if (ids.size() != values.size()) std::abort();
    for (int id : ids) {
      if (id < -1 || id >= num_vertices) std::abort();
    }
  } catch (const symembed::Error&) {
  }
  return 0;
}
