#include <filesystem>
#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "eval/synthetic/dataset_writer.h"
#include "eval/synthetic/remesh_dataset.h"

namespace symembed {

int RemeshCommand(const Args& args) {
  ArgParser parser("remesh",
                   "Writes a remeshed copy of a ground-truth dataset in the pairs_vts layout "
                   "(TOSCA, FAUST, SMAL):\nevery shape decimated independently, optionally "
                   "anisotropically, the ground truth carried over exactly\n(lines whose vertex "
                   "was collapsed away are 0 and not scored). Runs read it with\n`dataset: "
                   "{format: pairs_vts, root: DIR}`.");
  parser.Option("in", "root of the input dataset: shapes/, corres/, test_pairs.txt (required)", "");
  parser.Option("out", "output directory (required)", "");
  parser.Option("vertices", "target vertex count of every shape", "2500");
  parser.Option("anisotropy",
                "> 1: edges measured this many times longer along a random direction per shape, "
                "so that the edges along it stay short",
                "1");
  parser.Option("subdivide",
                "Loop subdivision levels (0-2) before the decimation, to remesh denser than the "
                "input (each level about 4 times the vertices)",
                "0");
  parser.Option("seed", "random seed (same input, options and seed: byte-identical files)", "1");
  parser.Switch("force",
                "write into a non-empty output directory (replaces shapes/, corres/, "
                "test_pairs.txt, README.md)");
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("in")) throw UsageError{"missing required option --in ROOT"};
  if (!parser.Given("out")) throw UsageError{"missing required option --out DIR"};
  RemeshDatasetOptions options;
  options.vertices = parser.GetInt("vertices");
  options.anisotropy = parser.GetDouble("anisotropy");
  options.subdivide = parser.GetInt("subdivide");
  options.seed = parser.GetInt("seed");
  std::string error;
  if (!options.IsValid(&error)) throw UsageError{error};

  namespace fs = std::filesystem;
  const fs::path in = parser.Get("in"), out = parser.Get("out");
  std::error_code ec;
  if (fs::equivalent(in, out, ec)) {
    throw UsageError{"--out must not be the input dataset " + in.string()};
  }
  PrepareDatasetOutput(out, parser.Flag("force"));
  const RemeshDatasetSummary s = WriteRemeshedDataset(in.string(), out.string(), options);
  std::cout << "wrote " << s.shapes << " shapes (" << s.remeshed << " remeshed) and " << s.pairs
            << " pairs to " << out.string() << "\n";
  return 0;
}

}  // namespace symembed
