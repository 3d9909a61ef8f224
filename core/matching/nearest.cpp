#include "core/matching/nearest.h"

#include <algorithm>
#include <sstream>

#include "core/errors.h"
#include "core/knn.h"
#include "core/procrustes.h"

namespace symembed {

namespace {

void CheckEmbedding(const Eigen::MatrixX3d& Y, const char* which) {
  if (Y.rows() == 0) throw InvalidInputError(std::string("matching: empty ") + which + " embedding");
  if (!Y.allFinite()) {
    throw InvalidInputError(std::string("matching: non-finite ") + which + " embedding");
  }
}

// map[i] = the nearest row of T to row i of S (any dimension); residual: the mean distance.
MatchResult NearestRows(const Eigen::MatrixXd& S, const Eigen::MatrixXd& T, int threads) {
  const KnnIndex index(T);
  Eigen::VectorXd dist;
  MatchResult result;
  result.map = index.Nearest(S, &dist, threads);
  result.status.residual = dist.mean();
  return result;
}

}  // namespace

MatchResult MatchNearest(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt, int threads) {
  CheckEmbedding(Ys, "source");
  CheckEmbedding(Yt, "target");
  return NearestRows(Ys, Yt, threads);
}

MatchResult MatchNearest(const EmbeddedPoints& source, const EmbeddedPoints& target,
                         double normal_weight, int threads) {
  if (!(normal_weight >= 0.0)) {
    throw ConfigError("matching: normal_weight must be >= 0, got " +
                      std::to_string(normal_weight));
  }
  if (normal_weight == 0.0) return MatchNearest(source.Y, target.Y, threads);
  CheckEmbedding(source.Y, "source");
  CheckEmbedding(target.Y, "target");
  const std::pair<const EmbeddedPoints*, const char*> sides[] = {{&source, "source"},
                                                                  {&target, "target"}};
  for (const auto& [points, which] : sides) {
    if (points->N.rows() != points->Y.rows() || !points->N.allFinite()) {
      throw InvalidInputError(std::string("matching: the ") + which + " normals (" +
                              std::to_string(points->N.rows()) + " rows) do not match its " +
                              std::to_string(points->Y.rows()) + " points or are not finite");
    }
  }
  const double w = normal_weight * RmsRadius(target.Y);
  auto lift = [w](const EmbeddedPoints& p) {
    Eigen::MatrixXd X(p.Y.rows(), 6);
    X << p.Y, w * p.N;
    return X;
  };
  return NearestRows(lift(source), lift(target), threads);
}

ScaledAlignment AlignScaled(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                            const ScaledIcpOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("matching nearest_scaled: " + error);
  CheckEmbedding(Ys, "source");
  CheckEmbedding(Yt, "target");
  const KnnIndex target_index(Yt);
  ScaledAlignment a;
  for (int it = 0; it < options.iterations; ++it) {
    const Eigen::MatrixX3d Z =
        (Ys.array().rowwise() * a.scale.transpose().array()).rowwise() + a.translation.transpose().array();
    // Pairs (source point, target point) in both directions.
    std::vector<int> src, tgt;
    const std::vector<int> fwd = target_index.Nearest(Z, nullptr, options.threads);
    for (int i = 0; i < Ys.rows(); ++i) {
      src.push_back(i);
      tgt.push_back(fwd[i]);
    }
    if (options.symmetric) {
      const KnnIndex source_index(Z);
      const std::vector<int> bwd = source_index.Nearest(Yt, nullptr, options.threads);
      for (int j = 0; j < Yt.rows(); ++j) {
        src.push_back(bwd[j]);
        tgt.push_back(j);
      }
    }
    // Per axis: t = s y + b by least squares.
    Eigen::Vector3d scale, translation;
    const double m = static_cast<double>(src.size());
    for (int c = 0; c < 3; ++c) {
      double sy = 0, st = 0, syy = 0, syt = 0;
      for (size_t k = 0; k < src.size(); ++k) {
        const double y = Ys(src[k], c), t = Yt(tgt[k], c);
        sy += y;
        st += t;
        syy += y * y;
        syt += y * t;
      }
      const double var = syy / m - (sy / m) * (sy / m);
      const double cov = syt / m - (sy / m) * (st / m);
      double s = var > 0.0 ? cov / var : 1.0;
      s = std::clamp(s, options.min_scale, options.max_scale);
      scale(c) = s;
      translation(c) = st / m - s * sy / m;
    }
    const bool still = (scale - a.scale).cwiseAbs().maxCoeff() < 1e-9 &&
                       (translation - a.translation).cwiseAbs().maxCoeff() < 1e-12;
    a.scale = scale;
    a.translation = translation;
    a.iterations = it + 1;
    if (still) break;
  }
  return a;
}

MatchResult MatchNearestScaled(const EmbeddedPoints& source, const EmbeddedPoints& target,
                               const ScaledIcpOptions& options, ScaledAlignment* alignment) {
  const ScaledAlignment a = AlignScaled(source.Y, target.Y, options);
  EmbeddedPoints moved;
  moved.Y = (source.Y.array().rowwise() * a.scale.transpose().array()).rowwise() +
            a.translation.transpose().array();
  // y -> s .* y + b maps normals to n ./ s (the inverse transpose), renormalised.
  moved.N = source.N.array().rowwise() / a.scale.transpose().array();
  moved.N.rowwise().normalize();
  MatchResult result = MatchNearest(moved, target, options.normal_weight, options.threads);
  result.status.iterations = a.iterations;
  std::ostringstream message;
  message << "scale " << a.scale.transpose() << ", translation " << a.translation.transpose();
  result.status.message = message.str();
  if (alignment) *alignment = a;
  return result;
}

}  // namespace symembed
