// Fuzz target of the map file reader (core/map_io.h ParseMap) as `symembed eval` calls it on
// other methods' maps: the first byte chooses the base (bit 0) and the target's vertex count
// (1 + 128 * the other bits).
#include <cstdlib>

#include "core/errors.h"
#include "core/map_io.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const int base = data[0] & 1;
  const int num_target_vertices = 1 + 128 * (data[0] >> 1);
  try {
    const std::vector<int> map = symembed::ParseMap(symembed::fuzz::Text(data + 1, size - 1),
                                                    base, -1, num_target_vertices, "fuzz.map");
    for (int id : map) {
      if (id < 0 || id >= num_target_vertices) std::abort();
    }
  } catch (const symembed::Error&) {
  }
  return 0;
}
