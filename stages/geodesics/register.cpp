#include "stages/register.h"

#include "stages/geodesics/dijkstra.h"

namespace symembed {

void RegisterGeodesicsStages(Registry& registry) { RegisterDijkstraGeodesics(registry); }

}  // namespace symembed
