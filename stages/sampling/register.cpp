#include "stages/register.h"

#include "stages/sampling/farthest_point.h"

namespace symembed {

void RegisterSamplingStages(Registry& registry) {
  RegisterAllSampling(registry);
  RegisterFarthestPointSampling(registry);
}

}  // namespace symembed
