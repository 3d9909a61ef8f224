#include "eval/datasets/register.h"

namespace symembed {

// No dataset loader is built in yet.
void RegisterDatasetLoaders(Registry& /*registry*/) {}

}  // namespace symembed
