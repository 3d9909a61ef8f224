// Scoring a folder of map files `A_B.map` (symembed's own or other methods') against a
// dataset's ground truth, with the same Evaluator a run uses (`symembed eval`). The files are
// named as a run names its maps (eval/pair_names.h, among the dataset's pairs): `A_B.map`,
// unless that name is ambiguous in the dataset (p_q1 -> r1 and p -> q1_r1 are both
// p_q1_r1.map) or holds '%'; then the escaped name (p%5Fq1_r1.map, p_q1_r1.map) is read, and
// never the plain one.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "eval/evaluator.h"
#include "eval/metrics.h"
#include "registry/dataset.h"

namespace symembed {

struct ScoreMapsOptions {
  std::string maps_dir;  // folder with a map file for each of the dataset's pairs (A, B)
  int base = 1;          // 0 or 1: id of the first vertex in the map files
  bool reverse = false;  // A_B.map maps B to A (the pair is scored as B -> A)
  int threads = 0;       // 0 = DefaultThreadCount()

  bool IsValid(std::string* error) const;
};

// Reads a mesh of the dataset (default: LoadSurface(shape.mesh_path)).
using DatasetMeshLoader = std::function<Surface(const DatasetShape& shape)>;

struct ScoreMapsResult {
  std::vector<PairEvaluation> pairs;  // one per dataset pair, sorted by (source, target)
  VariantTimings timings;             // per-shape load/preprocess times, total wall time
  // e.g. base 0 while no map uses id 0; each ambiguous plain name, with the escaped names read
  std::vector<std::string> warnings;
};

// For every pair of the dataset: reads its map file, checks it (one entry per source input
// vertex, integral ids in range, no NaN; see ParseMap) and scores it on the preprocessed
// target. A missing or malformed map file, or a shape that fails to load, preprocess or give
// ground truth, fails only the pairs concerned (ok = false, message names the file and line).
// Throws only for a dataset index that cannot be read.
ScoreMapsResult ScoreMaps(const Dataset& dataset, const PreprocessStage& preprocess,
                          const Evaluator& evaluator, const ScoreMapsOptions& options,
                          const DatasetMeshLoader& load = DatasetMeshLoader());

}  // namespace symembed
