// What a stage or an iterative solver reports about its numerical outcome: data, not an
// exception (registry/types.h passes it on with every stage result).
#pragma once

#include <string>

namespace symembed {

struct StageStatus {
  bool converged = true;
  int iterations = 0;
  double residual = 0.0;
  std::string message;
};

}  // namespace symembed
