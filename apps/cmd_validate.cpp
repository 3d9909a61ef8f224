#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/validation.h"

namespace symembed {

int ValidateCommand(const Args& args) {
  ArgParser parser("validate",
                   "Load each mesh (OFF, OBJ, PLY, STL) and print its validation report: one "
                   "line per mesh, followed by one indented line per defect (non-manifold "
                   "edges/vertices, boundaries, components, degenerate and duplicate faces, "
                   "inconsistent orientation, NaN/Inf coordinates, unreferenced vertices). "
                   "Files that fail to load are reported and skipped. Exit status: 1 if any "
                   "file failed to load (or, with --strict, any mesh has a defect), else 0.");
  parser.Switch("strict", "also exit 1 when a mesh has a defect");
  parser.Switch("quiet", "print only meshes that have defects or fail to load");
  parser.Positionals("MESH...", "mesh files to validate", 1, -1);
  if (!parser.Parse(args)) return 0;
  const bool strict = parser.Flag("strict"), quiet = parser.Flag("quiet");
  int failed = 0, defective = 0;
  for (const std::string& path : parser.positionals()) {
    try {
      const MeshReport report = ValidateMesh(LoadSurface(path), path);
      if (!report.clean()) ++defective;
      if (!quiet || !report.clean()) std::cout << report.ToString();
    } catch (const Error& e) {
      // InvalidInputError or IoError; their messages start with the path.
      ++failed;
      std::string what = e.what();
      if (what.compare(0, path.size(), path) == 0) what = what.substr(path.size());
      if (!what.empty() && what[0] == ':') what = what.substr(1);
      // "12: problem" (a line number) reads better as "line 12: problem".
      const size_t digits = what.find_first_not_of("0123456789");
      if (digits > 0 && digits != std::string::npos && what[digits] == ':') what = "line " + what;
      while (!what.empty() && what[0] == ' ') what = what.substr(1);
      std::cout << path << ": cannot load: " << what << "\n";
    }
  }
  const size_t total = parser.positionals().size();
  std::cout << total << (total == 1 ? " mesh: " : " meshes: ") << total - failed - defective
            << " clean, " << defective << " with defects, " << failed << " failed to load\n";
  return failed > 0 || (strict && defective > 0) ? 1 : 0;
}

}  // namespace symembed
