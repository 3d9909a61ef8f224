#include "python/src/pipeline.h"

#include <yaml-cpp/yaml.h>

#include <cmath>

#include "core/errors.h"
#include "harness/shape_pipeline.h"
#include "registry/stage_kinds.h"

namespace symembed::python {
namespace {

// The config a dict of overrides applies to: every stage at its default; the dataset only
// names a loader (a config needs one) and is never read.
constexpr char kDefaultConfig[] = "name: python\ndataset: {format: synthetic}\n";

YAML::Node YamlNode(const py::handle& value, const std::string& key) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) {
    return YAML::Node(value.cast<bool>() ? "true" : "false");
  }
  if (py::isinstance<py::int_>(value)) return YAML::Node(py::str(value).cast<std::string>());
  if (py::isinstance<py::float_>(value)) {
    const double x = value.cast<double>();
    if (std::isnan(x)) return YAML::Node(".nan");
    if (std::isinf(x)) return YAML::Node(x > 0 ? ".inf" : "-.inf");
    return YAML::Node(py::repr(value).cast<std::string>());
  }
  if (py::isinstance<py::str>(value)) {
    YAML::Node node(value.cast<std::string>());
    return node;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    YAML::Node node(YAML::NodeType::Sequence);
    for (const py::handle item : value) node.push_back(YamlNode(item, key));
    return node;
  }
  if (py::isinstance<py::dict>(value)) {
    YAML::Node node(YAML::NodeType::Map);
    for (const auto& [k, v] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k)) throw py::type_error(key + ": map keys must be strings");
      const std::string name = k.cast<std::string>();
      node[name] = YamlNode(v, key + "." + name);
    }
    return node;
  }
  throw py::type_error(key + ": cannot be set from a value of type " +
                       py::str(value.get_type().attr("__name__")).cast<std::string>() +
                       " (expected None, bool, int, float, str, list or dict)");
}

}  // namespace

const Registry& BuiltinRegistry() {
  static const Registry* registry = [] {
    auto* r = new Registry;
    RegisterBuiltinStages(*r);
    return r;
  }();
  return *registry;
}

std::string YamlText(const py::handle& value, const std::string& key) {
  const YAML::Node node = YamlNode(value, key);
  // A string is emitted, so that it is quoted where plain text would read as something else
  // ("true", "1", "a: b", ""); other scalars as they are.
  if (node.IsScalar() && !py::isinstance<py::str>(value)) return node.Scalar();
  if (node.IsNull()) return "null";
  YAML::Emitter emitter;
  emitter << YAML::Flow << node;
  return emitter.c_str();
}

std::vector<std::string> Overrides(const py::handle& set) {
  std::vector<std::string> overrides;
  if (set.is_none()) return overrides;
  if (!py::isinstance<py::dict>(set)) {
    throw py::type_error("expected a dict {dotted.path: value} of options, got " +
                         py::str(set.get_type().attr("__name__")).cast<std::string>());
  }
  for (const auto& [k, v] : set.cast<py::dict>()) {
    if (!py::isinstance<py::str>(k)) {
      throw py::type_error(
          "option names must be strings (dotted paths such as "
          "'pipeline.flip.type'), got " +
          py::repr(k).cast<std::string>());
    }
    const std::string key = k.cast<std::string>();
    overrides.push_back(key + "=" + YamlText(v, key));
  }
  return overrides;
}

std::string PathOf(const py::handle& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

std::shared_ptr<const LoadedPipeline> LoadPipeline(const py::object& config, const py::object& set,
                                                   const std::string& variant) {
  std::vector<std::string> overrides;
  auto loaded = std::make_shared<LoadedPipeline>();
  const Registry& registry = BuiltinRegistry();
  if (config.is_none() || py::isinstance<py::dict>(config)) {
    overrides = Overrides(config);
    const std::vector<std::string> more = Overrides(set);
    overrides.insert(overrides.end(), more.begin(), more.end());
    loaded->config = ParseExperimentConfig(kDefaultConfig, "config", registry, overrides);
  } else if (py::isinstance<py::str>(config) || py::hasattr(config, "__fspath__")) {
    overrides = Overrides(set);
    loaded->config = LoadExperimentConfig(PathOf(config), registry, overrides, variant);
  } else {
    throw py::type_error("config: expected None, a dict of options or a config file's path, got " +
                         py::str(config.get_type().attr("__name__")).cast<std::string>());
  }
  const VariantConfig& chosen = loaded->config.Get(variant);
  loaded->pipeline = BuildPipeline(loaded->config, chosen, registry);
  loaded->resolved = ResolvedConfigYaml(loaded->config, chosen, loaded->pipeline);
  Pipeline::ForEachStage(loaded->pipeline, [&](const char* kind, const auto& stage) {
    loaded->stages += std::string(kind) + ": " + OptionsText(*stage) + "\n";
  });
  loaded->stages += "evaluation: " + OptionsText(*loaded->pipeline.evaluation_geodesics) + "\n";
  return loaded;
}

}  // namespace symembed::python
