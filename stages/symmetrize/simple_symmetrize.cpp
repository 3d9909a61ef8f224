#include "stages/symmetrize/simple_symmetrize.h"

#include <sstream>

#include "stages/symmetrize/symmetrize_common.h"

namespace symembed {

SymmetrizeResult SymmetrizeAverage(const Eigen::MatrixXd& Y_in, const std::vector<int>& samples,
                                   const SymmetryResult& symmetry, int follow_neighbors) {
  const Eigen::MatrixX3d Y = MovePlaneToX0(Y_in, symmetry.normal, symmetry.offset);
  const Eigen::MatrixX3d P = SampleRows3(Y, samples);
  const Eigen::Matrix3d M = MirrorX();
  Eigen::MatrixX3d X(P.rows(), 3);
  for (int i = 0; i < P.rows(); ++i) {
    X.row(i) = 0.5 * (P.row(i) + P.row(symmetry.sigma[i]) * M);
  }
  SymmetrizeResult result;
  result.asymmetry_before = Asymmetry(P, symmetry.sigma);
  result.asymmetry_after = Asymmetry(X, symmetry.sigma);
  result.Y = FollowSamples(Y, samples, X, follow_neighbors);
  std::ostringstream message;
  message << "asymmetry " << result.asymmetry_before << " -> " << result.asymmetry_after;
  result.status.message = message.str();
  return result;
}

SymmetrizeResult SymmetrizeNone(const Eigen::MatrixXd& Y_in, const std::vector<int>& samples,
                                const SymmetryResult& symmetry) {
  SymmetrizeResult result;
  result.Y = MovePlaneToX0(Y_in, symmetry.normal, symmetry.offset);
  result.asymmetry_before = Asymmetry(SampleRows3(result.Y, samples), symmetry.sigma);
  result.asymmetry_after = result.asymmetry_before;
  return result;
}

}  // namespace symembed
