#include <iostream>

#include "apps/commands.h"

namespace symembed {

int MergeCommand(const Args& /*args*/) {
  std::cerr << "symembed merge: not implemented yet. It will provide merge DIR...: join shard outputs (issue: runner and evaluator)\n";
  return 1;
}

}  // namespace symembed
