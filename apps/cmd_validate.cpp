#include <iostream>

#include "apps/commands.h"

namespace symembed {

int ValidateCommand(const Args& /*args*/) {
  std::cerr << "symembed validate: not implemented yet. It will provide validate MESH...: per-mesh validation report (issue: foundation)\n";
  return 1;
}

}  // namespace symembed
