// Registration of the built-in dataset loaders (kind `dataset`).
#pragma once

#include "registry/registry.h"

namespace symembed {

void RegisterDatasetLoaders(Registry& registry);

}  // namespace symembed
