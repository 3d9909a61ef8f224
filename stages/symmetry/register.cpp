#include "stages/register.h"

namespace symembed {

// No symmetry implementation is built in yet.
void RegisterSymmetryStages(Registry& /*registry*/) {}

}  // namespace symembed
