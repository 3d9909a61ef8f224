#include "eval/synthetic/remesh_dataset.h"

#include <exception>
#include <filesystem>
#include <sstream>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/parallel.h"
#include "eval/datasets/pairs_vts.h"
#include "eval/synthetic/dataset_writer.h"
#include "eval/synthetic/random.h"
#include "eval/synthetic/variations.h"

namespace symembed {

namespace fs = std::filesystem;

bool RemeshDatasetOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  if (!kVertices.Contains(vertices))
    out << "vertices: " << kVertices.Violation(vertices)
        << " (a target below 50 vertices is degenerate)";
  else if (!kAnisotropy.Contains(anisotropy))
    out << "anisotropy: " << kAnisotropy.Violation(anisotropy);
  else if (!kSubdivide.Contains(subdivide))
    out << "subdivide: Loop subdivision levels " << kSubdivide.Violation(subdivide);
  if (error) *error = out.str();
  return out.str().empty();
}

RemeshDatasetSummary WriteRemeshedDataset(const std::string& input_root,
                                          const std::string& output_dir,
                                          const RemeshDatasetOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("remesh: " + error);
  PairsVtsOptions input;
  input.root = input_root;
  const PairsVtsDataset dataset(input);
  const DatasetIndex index = dataset.Load();

  const fs::path root(output_dir);
  CreateDatasetFolders(root);

  const uint64_t seed = static_cast<uint64_t>(options.seed);
  // The loader lists exactly the shapes its pairs name.
  const std::vector<DatasetShape>& shapes = index.shapes;
  const int n = static_cast<int>(shapes.size());
  std::vector<int> before(n), after(n);
  std::vector<std::exception_ptr> failures(n);
  ParallelFor(n, [&](int i) {
    try {
      const DatasetShape& shape = shapes[i];
      TrackedSurface tracked{LoadSurface(shape.mesh_path), {}};
      const int nv = tracked.surface.NumVertices();
      const ShapeGroundTruth truth = dataset.GroundTruth(shape, nv);
      tracked.rest_ids.resize(nv);
      for (int v = 0; v < nv; ++v) tracked.rest_ids[v] = v;
      // The mesh operations' errors say what failed, not in which file.
      const auto named = [&](const char* what, auto&& operation) {
        try {
          tracked = operation();
        } catch (const Error& e) {
          throw InvalidInputError(shape.mesh_path + ": cannot be " + what + " (" + e.what() +
                                  "); `symembed validate` lists what is wrong with it");
        }
      };
      named("subdivided", [&] { return Subdivide(tracked, options.subdivide); });
      if (options.vertices < tracked.surface.NumVertices()) {
        const Eigen::Vector3d direction =
            options.anisotropy > 1.0 ? RandomUnitVector(DeriveSeed(seed, "remesh_direction", i))
                                     : Eigen::Vector3d::UnitX();
        named("remeshed", [&] {
          return Remesh(tracked, options.vertices, DeriveSeed(seed, "remesh", i),
                        options.anisotropy, direction);
        });
      }
      SaveMesh((root / "shapes" / (shape.name + ".off")).string(), tracked.surface);
      WriteDatasetFile(root / "corres" / (shape.name + ".vts"),
                       VtsText(tracked.rest_ids, truth.ids, nv));
      if (!truth.sym_ids.empty()) {
        WriteDatasetFile(root / "corres" / (shape.name + ".sym.vts"),
                         VtsText(tracked.rest_ids, truth.sym_ids, nv));
      }
      before[i] = nv;
      after[i] = tracked.surface.NumVertices();
    } catch (...) {
      failures[i] = std::current_exception();
    }
  });
  for (const std::exception_ptr& failure : failures) {
    if (failure) std::rethrow_exception(failure);
  }

  RemeshDatasetSummary summary;
  summary.shapes = n;
  summary.pairs = static_cast<int>(index.pairs.size());
  std::string pairs_text;
  for (const DatasetPair& p : index.pairs) pairs_text += p.source + "\t" + p.target + "\n";
  WriteDatasetFile(root / "test_pairs.txt", pairs_text);
  std::ostringstream readme;
  readme << "# Remeshed dataset (symembed remesh)\n\n"
         << "Every shape of `" << input_root << "` decimated independently to " << options.vertices
         << " vertices";
  if (options.subdivide > 0) {
    readme << " after " << options.subdivide
           << " level(s) of Loop subdivision (old vertices moved by Loop's rule, new ones without "
           << "ground truth)";
  }
  if (options.anisotropy > 1.0) {
    readme << ", edges measured " << options.anisotropy
           << " times longer along a random direction per shape";
  }
  readme << " (seed " << options.seed << "); the ground truth carried over exactly: a line whose "
         << "vertex was collapsed away is 0. Layout: pairs_vts (`shapes/`, `corres/`, "
         << "`test_pairs.txt`).\n\n| shape | vertices before | after |\n| --- | --- | --- |\n";
  for (int i = 0; i < n; ++i) {
    readme << "| " << shapes[i].name << " | " << before[i] << " | " << after[i] << " |\n";
    summary.remeshed += after[i] != before[i];
  }
  WriteDatasetFile(root / "README.md", readme.str());
  return summary;
}

}  // namespace symembed
