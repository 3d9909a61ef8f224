#include "stages/flip/oracle.h"

#include <cmath>

#include "core/errors.h"
#include "core/knn.h"
#include "stages/flip/flip_common.h"

namespace symembed {

std::array<double, 4> OracleFlipScores(const PairInput& pair, int threads) {
  CheckFlipPair(pair);
  const PreprocessedGroundTruth* gt = pair.ground_truth;
  if (gt == nullptr) {
    throw InvalidInputError("flip oracle: pair '" + pair.source.name + "' -> '" + pair.target.name +
                            "' has no ground truth; the oracle scorer is "
                            "for evaluation on datasets with ground truth only");
  }
  if (gt->source_ids.empty() || gt->source_ids.size() != gt->target_ids.size()) {
    throw InvalidInputError("flip oracle: empty or inconsistent ground truth for '" +
                            pair.source.name + "' -> '" + pair.target.name + "'");
  }
  const int num = static_cast<int>(gt->source_ids.size());
  const int vs = pair.source.surface.NumVertices(), vt = pair.target.surface.NumVertices();
  Eigen::MatrixX3d Q(num, 3);
  for (int i = 0; i < num; ++i) {
    const int s = gt->source_ids[i], t = gt->target_ids[i];
    if (s < 0 || s >= vs || t < 0 || t >= vt) {
      throw InvalidInputError("flip oracle: ground-truth vertex id out of range");
    }
    Q.row(i) = pair.source.Y.row(s);
  }
  const KnnIndex index(pair.target.Y);
  const auto rotations = CandidateRotations();
  const Eigen::MatrixX3d& Vt = pair.target.surface.V;
  const double unit = std::sqrt(std::max(TotalArea(pair.target.surface), 1e-300));
  std::array<double, 4> scores{};
  for (int k = 0; k < 4; ++k) {
    const std::vector<int> map = index.Nearest(Q * rotations[k], nullptr, threads);
    double sum = 0.0;
    for (int i = 0; i < num; ++i) sum += (Vt.row(map[i]) - Vt.row(gt->target_ids[i])).norm();
    scores[k] = sum / num / unit;
  }
  return scores;
}

}  // namespace symembed
