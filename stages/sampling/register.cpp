#include "stages/register.h"

namespace symembed {

// No sampling implementation is built in yet.
void RegisterSamplingStages(Registry& /*registry*/) {}

}  // namespace symembed
