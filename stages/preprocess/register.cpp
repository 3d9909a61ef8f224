#include "stages/register.h"

#include "stages/preprocess/standard.h"

namespace symembed {

void RegisterPreprocessStages(Registry& registry) { RegisterStandardPreprocess(registry); }

}  // namespace symembed
