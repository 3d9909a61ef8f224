#include "stages/register.h"

namespace symembed {

// No refine implementation is built in yet.
void RegisterRefineStages(Registry& /*registry*/) {}

}  // namespace symembed
