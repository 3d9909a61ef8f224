// Fuzz target of the mesh readers (core/mesh_io.h ParseMesh), one binary per format:
// SYMEMBED_FUZZ_FORMAT is "off", "obj", "ply" (ASCII and binary) or "stl" (ASCII and binary).
// A mesh that parses must be well formed: face ids in range, one colour row per vertex when
// colours are given (coordinates may be non-finite: ValidateMesh reports them).
#include <cstdlib>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    Eigen::MatrixX3d colors;
    const symembed::Surface s =
        symembed::ParseMesh(symembed::fuzz::Text(data, size), SYMEMBED_FUZZ_FORMAT, "fuzz",
                            &colors);
    for (int f = 0; f < s.NumFaces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        if (s.F(f, k) < 0 || s.F(f, k) >= s.NumVertices()) std::abort();
      }
    }
    if (colors.rows() != 0 && colors.rows() != s.NumVertices()) std::abort();
  } catch (const symembed::Error&) {
  }
  return 0;
}
