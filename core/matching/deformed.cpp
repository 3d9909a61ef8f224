#include "core/matching/deformed.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <sstream>

#include "core/errors.h"
#include "core/knn.h"
#include "core/laplacian.h"
#include "core/procrustes.h"

namespace symembed {

bool DeformOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  out << FieldViolation(*this);
  if (out.str().empty() && k_end < k_start) {
    out << "k_end must be >= k_start (" << k_start << "), got " << k_end;
  }
  return NoViolation(out.str(), error);
}

namespace {

// The first `count` ids, each checked against n.
std::vector<int> Prefix(const std::vector<int>& ids, int count, int n, const char* which) {
  std::vector<int> out(ids.begin(), ids.begin() + std::min<size_t>(ids.size(), count));
  if (out.empty()) throw InvalidInputError(std::string("matching deformed: no ") + which + " samples");
  for (int v : out) {
    if (v < 0 || v >= n) {
      throw InvalidInputError(std::string("matching deformed: ") + which + " sample " +
                              std::to_string(v) + " outside [0, " + std::to_string(n) + ")");
    }
  }
  return out;
}

// Rows (y, w n) of the given vertices: the space MatchNearest compares in.
Eigen::MatrixXd Lifted(const Eigen::MatrixX3d& Y, const Eigen::MatrixX3d& N,
                       const std::vector<int>& ids, double w) {
  Eigen::MatrixXd X(ids.size(), w > 0.0 ? 6 : 3);
  for (size_t i = 0; i < ids.size(); ++i) {
    X.row(i).head<3>() = Y.row(ids[i]);
    if (w > 0.0) X.row(i).tail<3>() = w * N.row(ids[i]);
  }
  return X;
}

}  // namespace

DeformResult DeformSource(const EmbeddedPoints& source, const Eigen::MatrixX3i& F,
                          const LaplaceBasis& basis, const std::vector<int>& source_samples,
                          const EmbeddedPoints& target, const std::vector<int>& target_samples,
                          const DeformOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("matching deformed: " + error);
  const int ns = static_cast<int>(source.Y.rows());
  const int nt = static_cast<int>(target.Y.rows());
  if (ns == 0 || nt == 0 || !source.Y.allFinite() || !target.Y.allFinite()) {
    throw InvalidInputError("matching deformed: empty or non-finite embedding");
  }
  if (basis.NumVertices() != ns || basis.NumEigenpairs() < options.k_end) {
    throw InvalidInputError("matching deformed: the source basis has " +
                            std::to_string(basis.NumVertices()) + " rows and " +
                            std::to_string(basis.NumEigenpairs()) + " eigenpairs for " +
                            std::to_string(ns) + " vertices and k_end " +
                            std::to_string(options.k_end));
  }
  const bool with_normals = options.normal_weight > 0.0;
  if (with_normals && (source.N.rows() != ns || target.N.rows() != nt)) {
    throw InvalidInputError("matching deformed: normals do not match the points");
  }
  const std::vector<int> S = Prefix(source_samples, options.samples, ns, "source");
  const std::vector<int> T = Prefix(target_samples, options.samples, nt, "target");

  // Scale-free basis: Phi sqrt(A) has mean square 1 over the surface, lambda A is the
  // eigenvalue of the unit-area surface, so `smoothness` means the same whatever the mesh's size.
  const double area = basis.mass.sum();
  const int K = options.k_end;
  const Eigen::MatrixXd Phi = basis.evecs.leftCols(K) * std::sqrt(area);
  const Eigen::VectorXd lambda = basis.evals.head(K).cwiseMax(0.0) * area;

  const double w = options.normal_weight * RmsRadius(target.Y);
  const Eigen::MatrixXd target_lifted = Lifted(target.Y, target.N, T, w);
  const KnnIndex target_index(target_lifted);

  DeformResult result;
  result.Y = source.Y;
  result.N = source.N;
  std::vector<int> sizes;
  for (int k = options.k_start; k < options.k_end; k += options.step) sizes.push_back(k);
  sizes.push_back(options.k_end);
  bool first = true;
  for (int k : sizes) {
    for (int it = 0; it < options.iterations; ++it) {
      // Correspondences both ways on the samples: (source vertex, target vertex).
      const Eigen::MatrixXd source_lifted = Lifted(result.Y, result.N, S, w);
      std::vector<int> src, tgt;
      const std::vector<int> fwd = target_index.Nearest(source_lifted, nullptr, 1);
      for (size_t i = 0; i < S.size(); ++i) {
        src.push_back(S[i]);
        tgt.push_back(T[fwd[i]]);
      }
      const KnnIndex source_index(source_lifted);
      const std::vector<int> bwd = source_index.Nearest(target_lifted, nullptr, 1);
      for (size_t j = 0; j < T.size(); ++j) {
        src.push_back(S[bwd[j]]);
        tgt.push_back(T[j]);
      }
      // Each direction is a mean, so both weigh alike whatever the sample counts.
      const int m = static_cast<int>(src.size());
      Eigen::MatrixXd A(m, k);
      Eigen::MatrixX3d B(m, 3);
      Eigen::VectorXd weight(m);
      double residual = 0.0;
      for (int r = 0; r < m; ++r) {
        weight(r) = 1.0 / static_cast<double>(r < static_cast<int>(S.size()) ? S.size() : T.size());
        A.row(r) = Phi.row(src[r]).head(k);
        B.row(r) = target.Y.row(tgt[r]) - source.Y.row(src[r]);
        residual += weight(r) * (target.Y.row(tgt[r]) - result.Y.row(src[r])).squaredNorm();
      }
      if (first) result.residual_before = residual;
      first = false;
      result.residual_after = residual;
      Eigen::MatrixXd H = A.transpose() * weight.asDiagonal() * A;
      H.diagonal() += options.smoothness * lambda.head(k);
      // The constant eigenfunction has lambda ~ 0; a tiny ridge keeps H positive definite.
      H.diagonal().array() += 1e-12 * H.diagonal().maxCoeff();
      const Eigen::MatrixX3d D = H.ldlt().solve(A.transpose() * weight.asDiagonal() * B);
      result.Y = source.Y + Phi.leftCols(k) * D;
      if (with_normals) result.N = VertexNormals(result.Y, F);
    }
  }
  return result;
}

}  // namespace symembed
