#include "stages/symmetrize/symmetrize_common.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/knn.h"
#include "core/procrustes.h"

namespace symembed {

Eigen::MatrixX3d MovePlaneToX0(const Eigen::MatrixXd& Y, const Eigen::Vector3d& normal,
                               double offset) {
  if (Y.cols() != 3) throw InvalidInputError("symmetrize: the embedding must be 3D");
  const double length = normal.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InvalidInputError("symmetrize: the symmetry plane normal is zero or not finite");
  }
  const Eigen::Vector3d n = normal / length;
  const Eigen::Matrix3d Q =
      Eigen::Quaterniond::FromTwoVectors(n, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::RowVector3d shift = (offset / length) * n.transpose();
  return (Y.rowwise() - shift) * Q.transpose();
}

double Asymmetry(const Eigen::MatrixX3d& P, const std::vector<int>& sigma) {
  if (P.rows() == 0) return 0.0;
  const double size = RmsRadius(P);
  const Eigen::Matrix3d M = MirrorX();
  double sum = 0.0;
  for (int i = 0; i < P.rows(); ++i) {
    sum += (M * P.row(i).transpose() - P.row(sigma[i]).transpose()).norm();
  }
  return size > 0.0 ? sum / P.rows() / size : 0.0;
}

Eigen::MatrixX3d SampleRows3(const Eigen::MatrixX3d& Y, const std::vector<int>& samples) {
  Eigen::MatrixX3d P(samples.size(), 3);
  for (size_t i = 0; i < samples.size(); ++i) P.row(i) = Y.row(samples[i]);
  return P;
}

Eigen::MatrixX3d FollowSamples(const Eigen::MatrixX3d& Y, const std::vector<int>& samples,
                               const Eigen::MatrixX3d& P_new, int k) {
  const Eigen::MatrixX3d P_old = SampleRows3(Y, samples);
  const Eigen::MatrixX3d U = P_new - P_old;
  const KnnIndex index(P_old);
  k = std::max(1, std::min<int>(k, static_cast<int>(samples.size())));
  Eigen::MatrixXi nn;
  Eigen::MatrixXd dist;
  index.Query(Y, k, &nn, &dist, 1);
  Eigen::MatrixX3d out = Y;
  for (int v = 0; v < Y.rows(); ++v) {
    Eigen::RowVector3d u = Eigen::RowVector3d::Zero();
    double w_sum = 0.0;
    for (int j = 0; j < k; ++j) {
      const double w = 1.0 / (dist(v, j) * dist(v, j) + 1e-300);
      u += w * U.row(nn(v, j));
      w_sum += w;
    }
    out.row(v) += u / w_sum;
  }
  // Sample vertices exactly where their sample went (also for duplicate positions).
  for (size_t i = 0; i < samples.size(); ++i) out.row(samples[i]) = P_new.row(i);
  return out;
}

void CheckSymmetrizeInput(const SymmetryInput& input, const SymmetryResult& symmetry) {
  const Eigen::MatrixXd& Y = input.embedding.Y;
  if (Y.cols() != 3) throw InvalidInputError("symmetrize: the embedding must be 3D");
  const int num_samples = static_cast<int>(input.samples.size());
  if (num_samples < 1) throw InvalidInputError("symmetrize: no samples");
  for (int s : input.samples) {
    if (s < 0 || s >= Y.rows()) throw InvalidInputError("symmetrize: sample id out of range");
  }
  if (static_cast<int>(symmetry.sigma.size()) != num_samples) {
    throw InvalidInputError("symmetrize: sigma has " + std::to_string(symmetry.sigma.size()) +
                            " entries for " + std::to_string(num_samples) + " samples");
  }
  for (int j : symmetry.sigma) {
    if (j < 0 || j >= num_samples) throw InvalidInputError("symmetrize: sigma out of range");
  }
  if (symmetry.confidence.size() != 0 && symmetry.confidence.size() != num_samples) {
    throw InvalidInputError("symmetrize: confidence has the wrong size");
  }
}

}  // namespace symembed
