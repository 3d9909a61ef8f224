#include <iostream>

#include "apps/commands.h"

namespace symembed {

int RunCommand(const Args& /*args*/) {
  std::cerr << "symembed run: not implemented yet. It will provide run CONFIG: the experiment runner (issue: runner and evaluator)\n";
  return 1;
}

}  // namespace symembed
