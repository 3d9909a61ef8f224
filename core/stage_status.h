// What a stage or an iterative solver reports about its numerical outcome: data, not an
// exception (registry/types.h passes it on with every stage result).
#pragma once

#include <string>
#include <tuple>

namespace symembed {

struct StageStatus {
  bool converged = true;
  int iterations = 0;
  double residual = 0.0;
  std::string message;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&StageStatus::converged, &StageStatus::iterations,
                           &StageStatus::residual, &StageStatus::message);
  }
};

}  // namespace symembed
