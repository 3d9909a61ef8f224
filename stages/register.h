// Registration functions of the built-in stages, one per kind (defined in stages/<kind>/).
#pragma once

#include "registry/registry.h"

namespace symembed {

void RegisterPreprocessStages(Registry& registry);
void RegisterSamplingStages(Registry& registry);
void RegisterGeodesicsStages(Registry& registry);
void RegisterEmbeddingStages(Registry& registry);
void RegisterSymmetryStages(Registry& registry);
void RegisterSymmetrizeStages(Registry& registry);
void RegisterFlipStages(Registry& registry);
void RegisterMatchingStages(Registry& registry);
void RegisterRefineStages(Registry& registry);

}  // namespace symembed
