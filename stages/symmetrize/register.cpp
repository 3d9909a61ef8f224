#include "stages/register.h"

namespace symembed {

// No symmetrize implementation is built in yet.
void RegisterSymmetrizeStages(Registry& /*registry*/) {}

}  // namespace symembed
