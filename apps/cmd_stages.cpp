#include <algorithm>
#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "registry/registry.h"

namespace symembed {

int StagesCommand(const Args& args) {
  ArgParser parser("stages", "List every registered stage and dataset loader: kind, name, "
                             "description, sorted by kind and name.");
  if (!parser.Parse(args)) return 0;
  Registry registry;
  RegisterBuiltinStages(registry);
  size_t kind_width = 4, name_width = 4;
  for (const auto& e : registry.List()) {
    kind_width = std::max(kind_width, e.kind.size());
    name_width = std::max(name_width, e.name.size());
  }
  for (const auto& e : registry.List()) {
    std::cout << e.kind << std::string(kind_width + 2 - e.kind.size(), ' ') << e.name
              << std::string(name_width + 2 - e.name.size(), ' ') << e.description << "\n";
  }
  return 0;
}

}  // namespace symembed
