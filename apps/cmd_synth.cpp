#include <iostream>

#include "apps/commands.h"

namespace symembed {

int SynthCommand(const Args& /*args*/) {
  std::cerr << "symembed synth: not implemented yet. It will provide synth: the synthetic ground-truth generator (issue: synthetic benchmark)\n";
  return 1;
}

}  // namespace symembed
