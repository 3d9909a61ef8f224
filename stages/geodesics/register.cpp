#include "stages/register.h"

namespace symembed {

// No geodesics implementation is built in yet.
void RegisterGeodesicsStages(Registry& /*registry*/) {}

}  // namespace symembed
