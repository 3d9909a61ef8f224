// The options of a registered stage with their defaults, as `symembed stages --options` and
// `--markdown` list them and the Python module's symembed.stages() returns them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "registry/registry.h"

namespace symembed {

// A dotted option name ("decide.type", as in a config's pipeline.KIND section) and its default
// as YAML text in flow style ("300", "[humanoid]").
using StageOption = std::pair<std::string, std::string>;

// Every option of a registered stage with its default, in the order the stage reads them, as
// the stage resolves an empty section (`type` alone; `type` itself is left out). A dataset
// loader that needs a root is created with a placeholder, listed as "(required)". Throws
// ConfigError when the stage cannot be created from its defaults.
std::vector<StageOption> StageDefaultOptions(const Registry& registry,
                                             const Registry::Entry& entry);

}  // namespace symembed
