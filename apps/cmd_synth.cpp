#include <filesystem>
#include <iostream>
#include <sstream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "eval/synthetic/dataset_writer.h"
#include "eval/synthetic/synthetic.h"

namespace symembed {

namespace {

std::vector<FigureKind> ParseKinds(const std::string& text) {
  std::vector<FigureKind> kinds;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item != "humanoid" && item != "quadruped") {
      throw UsageError{"option --kind expects humanoid, quadruped or a comma-separated list, got '" +
                       text + "'"};
    }
    kinds.push_back(FigureKindFromName(item));
  }
  if (kinds.empty()) throw UsageError{"option --kind needs a value"};
  return kinds;
}

}  // namespace

int SynthCommand(const Args& args) {
  ArgParser parser("synth",
                   "Writes a synthetic ground-truth dataset (pairs_vts layout: shapes/, corres/, "
                   "test_pairs.txt, README.md):\nposes of a bilaterally symmetric articulated "
                   "figure with exact direct and mirrored ground truth.");
  parser.Option("kind", "figure: humanoid, quadruped, or a comma-separated list (one class each)",
                "humanoid");
  parser.Option("poses", "shapes per class", "8");
  parser.Option("out", "output directory (required)", "");
  parser.Option("vertices", "approximate vertex count of the rest shape", "5000");
  parser.Option("seed", "random seed (same options and seed: byte-identical files)", "1");
  parser.Option("remesh", "decimate every pose independently to N vertices (0: off)", "0");
  parser.Option("remesh-anisotropy",
                "> 1: the remeshing measures edges this many times longer along a random direction "
                "per pose, keeping the edges along it short (needs --remesh)",
                "1");
  parser.Option("nonisometric", "per-pose bone length/thickness factors in [1-R, 1+R] (0: off)", "0");
  parser.Option("noise", "normal noise amplitude, fraction of the mean edge length (0: off)", "0");
  parser.Option("partial", "fraction of poses with a hand, foot or head cut away (0: off)", "0");
  parser.Option("plane-cuts", "fraction of poses cut by a plane (10-40% of the vertices; 0: off)",
                "0");
  parser.Option("holes", "fraction of poses with 1-3 holes of several sizes (0: off)", "0");
  parser.Option("glue", "fraction of poses posed for contact and glued there (topological "
                "noise; 0: off)", "0");
  parser.Option("glue-bridges", "tubes per glued pose (0: the contact poses unglued)", "8");
  parser.Option("cross-class",
                "R > 0: every kind also gets a class KIND_cross of another body plan (bone "
                "factors in [1-R, 1+R], bent forwards) and the pairs cross classes (0: off)",
                "0");
  parser.Option("pairs", "pairs per class in test_pairs.txt (0: all unordered pairs; with "
                "--cross-class, per kind)", "0");
  parser.Switch("force", "write into a non-empty output directory (replaces shapes/, corres/, "
                         "test_pairs.txt, README.md)");
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("out")) throw UsageError{"missing required option --out DIR"};

  SynthOptions options;
  options.kinds = ParseKinds(parser.Get("kind"));
  options.poses = parser.GetInt("poses");
  options.vertices = parser.GetInt("vertices");
  options.seed = parser.GetInt("seed");
  options.remesh = parser.GetInt("remesh");
  options.remesh_anisotropy = parser.GetDouble("remesh-anisotropy");
  options.nonisometric = parser.GetDouble("nonisometric");
  options.noise = parser.GetDouble("noise");
  options.partial = parser.GetDouble("partial");
  options.plane_cuts = parser.GetDouble("plane-cuts");
  options.holes = parser.GetDouble("holes");
  options.glue = parser.GetDouble("glue");
  options.glue_bridges = parser.GetInt("glue-bridges");
  options.cross_class = parser.GetDouble("cross-class");
  options.pairs = parser.GetInt("pairs");
  std::string error;
  if (!options.IsValid(&error)) throw UsageError{error};

  namespace fs = std::filesystem;
  const fs::path out = parser.Get("out");
  PrepareDatasetOutput(out, parser.Flag("force"));
  WriteSyntheticDataset(out.string(), options);
  std::cout << "wrote "
            << options.poses * options.kinds.size() * (options.cross_class > 0.0 ? 2 : 1)
            << " shapes to " << out.string()
            << "\n";
  return 0;
}

}  // namespace symembed
