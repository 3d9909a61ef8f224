#include "stages/register.h"

#include "stages/geodesics/dijkstra.h"
#include "stages/geodesics/fast_marching.h"

namespace symembed {

void RegisterGeodesicsStages(Registry& registry) {
  RegisterDijkstraGeodesics(registry);
  RegisterFastMarchingGeodesics(registry);
}

}  // namespace symembed
