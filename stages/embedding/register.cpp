#include "stages/register.h"

namespace symembed {

// No embedding implementation is built in yet.
void RegisterEmbeddingStages(Registry& /*registry*/) {}

}  // namespace symembed
