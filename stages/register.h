// Registration functions of the built-in stages, one per kind (defined in stages/<kind>/).
#pragma once

#include "registry/registry.h"
#include "registry/stage_kinds.h"

namespace symembed {

// void Register<Name>Stages(Registry& registry), one per row of SYMEMBED_STAGE_KINDS.
#define SYMEMBED_DECLARE_REGISTER(name, Name, scope, default_type) \
  void Register##Name##Stages(Registry& registry);
SYMEMBED_STAGE_KINDS(SYMEMBED_DECLARE_REGISTER)
#undef SYMEMBED_DECLARE_REGISTER

}  // namespace symembed
