// A geodesics stage for tests on flat surfaces, where geodesic distance equals Euclidean
// distance: exact, so expected errors can be computed by hand. Counts single-source solves.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "registry/stages.h"

namespace symembed::testing {

class EuclideanSolver : public GeodesicSolver {
 public:
  EuclideanSolver(const Surface& s, std::atomic<int>* solves) : V_(s.V), solves_(solves) {}
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const override {
    Eigen::MatrixXd D(sources.size(), V_.rows());
    for (size_t k = 0; k < sources.size(); ++k) {
      D.row(k) = (V_.rowwise() - V_.row(sources[k])).rowwise().norm().transpose();
    }
    *solves_ += static_cast<int>(sources.size());
    return D;
  }

 private:
  Eigen::MatrixX3d V_;
  std::atomic<int>* solves_;
};

class EuclideanGeodesics : public GeodesicsStage {
 public:
  std::unique_ptr<GeodesicSolver> Prepare(const Surface& surface) const override {
    return std::make_unique<EuclideanSolver>(surface, &solves);
  }
  mutable std::atomic<int> solves{0};
};

}  // namespace symembed::testing
