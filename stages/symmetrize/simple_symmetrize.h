// Symmetrize stages `average` and `none` (ablation baselines of `ceres`).
//
// `average`: closed form x_i = (y_i + M y_sigma(i)) / 2 on the samples (exactly symmetric where
// sigma is an involution), dense vertices follow the samples. `none`: the plane moved to x = 0,
// nothing else. Both report the asymmetry before and after (mean ||M y_i - y_sigma(i)|| / size).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "registry/types.h"

namespace symembed {

// Y: #V x 3; samples: #S ids; symmetry: plane in Y's coordinates and sigma (#S).
// follow_neighbors: nearest samples a dense vertex follows.
SymmetrizeResult SymmetrizeAverage(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                   const SymmetryResult& symmetry, int follow_neighbors = 8);

SymmetrizeResult SymmetrizeNone(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                const SymmetryResult& symmetry);

}  // namespace symembed
