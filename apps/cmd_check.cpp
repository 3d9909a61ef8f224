#include <iostream>

#include "apps/commands.h"

namespace symembed {

int CheckCommand(const Args& /*args*/) {
  std::cerr << "symembed check: not implemented yet. It will provide check SUMMARY --baseline FILE: accuracy regression (issue: runner and evaluator)\n";
  return 1;
}

}  // namespace symembed
