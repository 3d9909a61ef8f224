#include "apps/stage_options.h"

#include <algorithm>

#include "core/errors.h"
#include "registry/stages.h"

namespace symembed {
namespace {

// The resolved options of a node as dotted names and YAML values, in the node's order; a list
// is one value in flow style.
void Flatten(const YAML::Node& node, const std::string& prefix, std::vector<StageOption>* out) {
  for (const auto& item : node) {
    const std::string name = prefix + item.first.Scalar();
    if (item.second.IsMap()) {
      Flatten(item.second, name + ".", out);
    } else {
      YAML::Emitter emitter;
      emitter << YAML::Flow << item.second;
      out->emplace_back(name, emitter.c_str());
    }
  }
}

}  // namespace

std::vector<StageOption> StageDefaultOptions(const Registry& registry,
                                             const Registry::Entry& entry) {
  const bool dataset = entry.kind == "dataset";
  const std::string type_key = dataset ? "format" : "type";
  const auto resolve = [&](bool with_root) {
    YAML::Node node;
    node[type_key] = entry.name;
    if (with_root) node["root"] = "(required)";
    std::vector<StageOption> options;
    const auto stage = registry.Create(entry.kind, node, "(defaults)", entry.kind, "", type_key);
    Flatten(stage->resolved_options(), "", &options);
    Flatten(stage->unset_defaults(), "", &options);
    return options;
  };
  std::vector<StageOption> options;
  try {
    options = resolve(false);
  } catch (const ConfigError&) {
    if (!dataset) throw;
    options = resolve(true);
  }
  options.erase(std::remove_if(options.begin(), options.end(),
                               [&](const StageOption& o) { return o.first == type_key; }),
                options.end());
  return options;
}

}  // namespace symembed
