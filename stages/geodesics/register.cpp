#include "stages/register.h"

#include "stages/geodesics/dijkstra.h"
#include "stages/geodesics/fast_marching.h"
#include "stages/geodesics/heat.h"

namespace symembed {

void RegisterGeodesicsStages(Registry& registry) {
  RegisterDijkstraGeodesics(registry);
  RegisterFastMarchingGeodesics(registry);
  RegisterHeatGeodesics(registry);
}

}  // namespace symembed
