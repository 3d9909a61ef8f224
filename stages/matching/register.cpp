#include "stages/register.h"

namespace symembed {

// No matching implementation is built in yet.
void RegisterMatchingStages(Registry& /*registry*/) {}

}  // namespace symembed
