#include "harness/eval_setup.h"

#include <filesystem>

#include "core/errors.h"
#include "core/files.h"
#include "eval/json.h"

namespace symembed {

EvalSetup MakeEvalSetup(const std::string& dataset_arg, const Registry& registry) {
  EvalSetup s;
  if (std::filesystem::is_regular_file(dataset_arg)) {
    const ExperimentConfig config = LoadExperimentConfig(dataset_arg, registry);
    Pipeline pipeline = BuildPipeline(config, config.variants.front(), registry);
    s.dataset = std::move(pipeline.dataset);
    s.preprocess = std::move(pipeline.preprocess);
    s.geodesics = std::move(pipeline.evaluation_geodesics);
    s.evaluation = pipeline.evaluation;
  } else if (std::filesystem::is_directory(dataset_arg)) {
    YAML::Node node;
    node["format"] = "pairs_vts";
    node["root"] = dataset_arg;
    s.dataset = registry.CreateAs<Dataset>("dataset", node, "--dataset", "dataset", "", "format");
    s.preprocess =
        registry.CreateAs<PreprocessStage>("preprocess", YAML::Node(), "--dataset",
                                           "pipeline.preprocess", DefaultStageType("preprocess"));
  } else {
    throw IoError(dataset_arg + ": no such config file or dataset folder");
  }
  return s;
}

std::string EvalSourcePath(const std::string& out_dir) { return out_dir + "/eval.json"; }

void WriteEvalSource(const std::string& out_dir, const EvalSource& source) {
  const auto absolute = [](const std::string& path) {
    return std::filesystem::absolute(path).lexically_normal().string();
  };
  JsonValue j = JsonValue::Object();
  j.Set("dataset", JsonValue::String(absolute(source.dataset)));
  j.Set("maps", JsonValue::String(absolute(source.maps_dir)));
  j.Set("base", JsonValue::Number(source.base));
  j.Set("reverse", JsonValue::Bool(source.reverse));
  WriteFileAtomically(EvalSourcePath(out_dir), WriteJson(j) + "\n");
}

EvalSource ReadEvalSource(const std::string& path) {
  const JsonValue j = ParseJson(ReadFileOrThrow(path), path);
  EvalSource source;
  try {
    source.dataset = j.Get("dataset").AsString();
    source.maps_dir = j.Get("maps").AsString();
    source.base = static_cast<int>(j.Get("base").AsNumber());
    source.reverse = j.Get("reverse").AsBool();
  } catch (const InvalidInputError& e) {
    throw InvalidInputError(path +
                            ": expected dataset, maps (strings), base (number) and "
                            "reverse (boolean): " +
                            e.what());
  }
  return source;
}

}  // namespace symembed
