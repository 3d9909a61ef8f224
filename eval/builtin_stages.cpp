// RegisterBuiltinStages lives in the top library because it must see every stage kind and the
// dataset loaders (which sit above the stages in the dependency ladder).
#include "eval/datasets/register.h"
#include "registry/registry.h"
#include "stages/register.h"

namespace symembed {

void RegisterBuiltinStages(Registry& registry) {
  RegisterPreprocessStages(registry);
  RegisterSamplingStages(registry);
  RegisterGeodesicsStages(registry);
  RegisterEmbeddingStages(registry);
  RegisterSymmetryStages(registry);
  RegisterSymmetrizeStages(registry);
  RegisterFlipStages(registry);
  RegisterMatchingStages(registry);
  RegisterRefineStages(registry);
  RegisterDatasetLoaders(registry);
}

}  // namespace symembed
