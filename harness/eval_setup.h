// The inputs of `symembed eval` beside the maps: the dataset with its preprocess stage and the
// evaluation's geodesics and options, from a config or a dataset folder; and eval.json, which
// keeps them in the eval's output folder so that `symembed report` finds the meshes and maps.
#pragma once

#include <memory>
#include <string>

#include "harness/config.h"
#include "registry/dataset.h"
#include "registry/registry.h"

namespace symembed {

// What scoring maps needs besides the maps, from the --dataset of `symembed eval`: an experiment
// config (its dataset, preprocess, evaluation geodesics and options) or a dataset folder in the
// pairs_vts layout (the default preprocess; geodesics null and default evaluation options).
// Throws IoError when the path is neither, ConfigError for a bad config.
struct EvalSetup {
  std::unique_ptr<Dataset> dataset;
  std::unique_ptr<PreprocessStage> preprocess;
  std::unique_ptr<GeodesicsStage> geodesics;
  EvaluationOptions evaluation;
};
EvalSetup MakeEvalSetup(const std::string& dataset_arg, const Registry& registry);

// The inputs of a `symembed eval`, kept beside its outputs as eval.json so that the meshes and
// maps can be found again (`symembed report`): {"dataset", "maps", "base", "reverse"}, the
// paths absolute.
struct EvalSource {
  std::string dataset;  // the --dataset argument
  std::string maps_dir;
  int base = 1;
  bool reverse = false;
};
std::string EvalSourcePath(const std::string& out_dir);  // OUT/eval.json
// Throws IoError.
void WriteEvalSource(const std::string& out_dir, const EvalSource& source);
// Throws IoError or InvalidInputError naming the file.
EvalSource ReadEvalSource(const std::string& path);

}  // namespace symembed
