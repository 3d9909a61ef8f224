#include <iostream>

#include "apps/commands.h"

namespace symembed {

int EvalCommand(const Args& /*args*/) {
  std::cerr << "symembed eval: not implemented yet. It will provide eval: score a folder of maps (issue: runner and evaluator)\n";
  return 1;
}

}  // namespace symembed
