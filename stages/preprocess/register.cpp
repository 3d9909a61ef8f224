#include "stages/register.h"

namespace symembed {

// No preprocess implementation is built in yet.
void RegisterPreprocessStages(Registry& /*registry*/) {}

}  // namespace symembed
