// RegisterBuiltinStages lives in the top library because it must see every stage kind and the
// dataset loaders (which sit above the stages in the dependency ladder).
#include "eval/datasets/register.h"
#include "registry/registry.h"
#include "registry/stage_kinds.h"
#include "stages/register.h"

namespace symembed {

void RegisterBuiltinStages(Registry& registry) {
#define SYMEMBED_CALL_REGISTER(name, Name, scope, default_type) Register##Name##Stages(registry);
  SYMEMBED_STAGE_KINDS(SYMEMBED_CALL_REGISTER)
#undef SYMEMBED_CALL_REGISTER
  RegisterDatasetLoaders(registry);
}

}  // namespace symembed
