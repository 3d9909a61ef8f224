#include "stages/flip/flip_common.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "core/knn.h"
#include "core/procrustes.h"

namespace symembed {

CandidateMaps ComputeCandidateMaps(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                   int threads) {
  // ||R y_t - y_s|| = ||y_t - R^T y_s||: one tree on Yt, queries R^T y_s (rows y_s^T R).
  const KnnIndex index(Yt);
  const auto rotations = CandidateRotations();
  CandidateMaps out;
  for (int k = 0; k < 4; ++k) {
    const Eigen::MatrixX3d Q = Ys * rotations[k];
    out.map[k] = index.Nearest(Q, &out.dist[k], threads);
  }
  return out;
}

std::array<double, 4> ChamferScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    int threads) {
  const CandidateMaps forward = ComputeCandidateMaps(Ys, Yt, threads);
  const KnnIndex source_index(Ys);
  const auto rotations = CandidateRotations();
  const double size = 0.5 * (RmsRadius(Ys) + RmsRadius(Yt));
  std::array<double, 4> scores{};
  for (int k = 0; k < 4; ++k) {
    Eigen::VectorXd back;
    source_index.Nearest(Yt * rotations[k].transpose(), &back, threads);
    scores[k] = (forward.dist[k].mean() + back.mean()) / std::max(size, 1e-300);
  }
  return scores;
}

std::array<int, 4> CandidateOrder(const std::array<double, 4>& scores) {
  std::array<int, 4> order{0, 1, 2, 3};
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return scores[a] < scores[b]; });
  return order;
}

std::vector<int> SamplePrefix(const std::vector<int>& samples, int count, int k_end,
                              const std::string& what) {
  if (static_cast<int>(samples.size()) < k_end) {
    throw InvalidInputError(what + " has " + std::to_string(samples.size()) +
                            " samples, fewer than k_end");
  }
  return {samples.begin(), samples.begin() + std::min<size_t>(samples.size(), count)};
}

FlipResult MakeFlipResult(const std::array<double, 4>& scores, const std::string& name,
                          int chosen) {
  FlipResult result;
  result.scores = scores;
  if (chosen >= 0) {
    result.chosen = chosen;
  } else {
    for (int k = 1; k < 4; ++k) {
      if (scores[k] < scores[result.chosen]) result.chosen = k;
    }
  }
  std::ostringstream message;
  message << name << " scores [";
  for (int k = 0; k < 4; ++k) message << (k > 0 ? ", " : "") << kCandidateNames[k];
  message << "]:";
  for (double s : scores) message << " " << s;
  result.status.message = message.str();
  result.status.residual = scores[result.chosen];
  return result;
}

void CheckFlipPair(const PairInput& pair) {
  for (const ShapeData* shape : {&pair.source, &pair.target}) {
    if (shape->Y.rows() == 0 || shape->Y.rows() != shape->surface.NumVertices()) {
      throw InvalidInputError("flip: shape '" + shape->name + "' has a canonical embedding of " +
                              std::to_string(shape->Y.rows()) + " rows for " +
                              std::to_string(shape->surface.NumVertices()) + " vertices");
    }
  }
}

}  // namespace symembed
