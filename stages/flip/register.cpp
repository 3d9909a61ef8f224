#include "stages/register.h"

namespace symembed {

// No flip implementation is built in yet.
void RegisterFlipStages(Registry& /*registry*/) {}

}  // namespace symembed
