// Registration functions of the built-in stages, one per kind (defined in stages/<kind>/).
#pragma once

#include <memory>

#include "registry/options.h"
#include "registry/registry.h"
#include "registry/stage_kinds.h"

namespace symembed {

// void Register<Name>Stages(Registry& registry), one per row of SYMEMBED_STAGE_KINDS.
#define SYMEMBED_DECLARE_REGISTER(name, Name, scope, default_type) \
  void Register##Name##Stages(Registry& registry);
SYMEMBED_STAGE_KINDS(SYMEMBED_DECLARE_REGISTER)
#undef SYMEMBED_DECLARE_REGISTER

// The factory of a stage built from its options alone: reads Options through their Fields and
// IsValid (ReadValidFields), then returns StageType(options).
template <typename StageType, typename Options>
Registry::Factory FieldsFactory() {
  return [](OptionReader& reader) -> std::unique_ptr<Stage> {
    Options options;
    ReadValidFields(reader, &options);
    return std::make_unique<StageType>(options);
  };
}

}  // namespace symembed
