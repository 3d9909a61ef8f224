// Functional-map ICP: refinement of a point-to-point map at a fixed basis size.
//
// [Ovsjanikov et al. 2012] Functional maps: a flexible representation of maps between shapes,
// Sec. 6.1. Alternate (i) the orthogonal k x k functional map closest to the current
// point-to-point map (Procrustes, mass-weighted) and (ii) the point-to-point map of C by nearest
// neighbours in the k-dimensional spectral embedding, until the map stops changing. Convention of
// functional_map.h (C pulls target coefficients back to the source). The baseline that ZoomOut
// [Melzi et al. 2019] improves on.
#pragma once

#include <string>
#include <vector>

#include "core/range.h"
#include "core/spectral.h"
#include "registry/types.h"

namespace symembed {

struct FunctionalMapIcpOptions {
  int k = 50;  // basis size (both bases need k eigenpairs)
  static constexpr Range kK = Range::Closed(1, 1000);
  int max_iterations = 20;  // upper bound on Procrustes / nearest-neighbour rounds
  static constexpr Range kMaxIterations = Range::Closed(1, 10000);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("k", self.k, kK);
    visit("max_iterations", self.max_iterations, kMaxIterations);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

struct FunctionalMapIcpResult {
  std::vector<int> map;                   // #Vs: target vertex of each source vertex
  std::vector<double> spectral_residual;  // per iteration: mean squared NN spectral distance
  std::vector<int> changes;               // per iteration: source vertices whose target changed
  int changed = 0;                        // against the initial map
  StageStatus status;                     // converged: the map stopped changing
};

// source, target: bases with at least options.k eigenpairs. initial_map: #Vs entries in
// [0, #Vt). Throws ConfigError for invalid options, InvalidInputError for inconsistent inputs.
FunctionalMapIcpResult FunctionalMapIcp(const LaplaceBasis& source, const LaplaceBasis& target,
                                        const std::vector<int>& initial_map,
                                        const FunctionalMapIcpOptions& options);

}  // namespace symembed
