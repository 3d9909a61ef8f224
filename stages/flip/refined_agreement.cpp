#include "stages/flip/refined_agreement.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "core/errors.h"
#include "core/laplacian.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/orientation.h"
#include "stages/matching/nearest.h"
#include "stages/refine/zoomout.h"

namespace symembed {
namespace {
// Nearest samples whose pairs make the triangles of MapOrientation.
constexpr int kNeighbors = 6;
}  // namespace

bool RefinedAgreementOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  if (k_start < 1 || k_end < k_start) out << "need 1 <= k_start <= k_end";
  else if (step < 1) out << "step must be >= 1, got " << step;
  else if (samples < k_end) out << "samples must be >= k_end (" << k_end << "), got " << samples;
  else if (candidates < 1 || candidates > 4)
    out << "candidates must be in [1, 4], got " << candidates;
  else if (target_samples < k_end)
    out << "target_samples must be >= k_end (" << k_end << "), got " << target_samples;
  else if (!(normal_weight >= 0.0)) out << "normal_weight must be >= 0";
  if (error) *error = out.str();
  return out.str().empty();
}

RefinedScores AddRefinedTerm(const std::array<double, 4>& scores, double weight,
                             const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                             const Surface& source,
                             const Surface& target, const LaplaceBasis& source_basis,
                             const LaplaceBasis& target_basis, const Eigen::MatrixXd& Fs,
                             const Eigen::MatrixXd& Ft, const std::vector<int>& samples,
                             const std::vector<int>& target_samples,
                             const RefinedAgreementOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip refined: " + error);
  if (!(weight >= 0.0)) throw ConfigError("flip refined: weight must be >= 0");
  if (Fs.rows() != source.NumVertices() || Ft.rows() != target.NumVertices()) {
    throw InvalidInputError("flip refined: features do not match the surfaces");
  }
  for (const auto* s : {&samples, &target_samples}) {
    if (static_cast<int>(s->size()) < options.k_end) {
      throw InvalidInputError(std::string("flip refined: the ") +
                              (s == &samples ? "source" : "target") + " has " +
                              std::to_string(s->size()) + " samples, fewer than k_end");
    }
  }
  const std::vector<int> prefix(
      samples.begin(), samples.begin() + std::min<size_t>(samples.size(), options.samples));
  const std::vector<int> target_prefix(
      target_samples.begin(),
      target_samples.begin() + std::min<size_t>(target_samples.size(), options.target_samples));
  ZoomOutOptions zoomout;
  zoomout.k_start = options.k_start;
  zoomout.k_end = options.k_end;
  zoomout.step = options.step;
  zoomout.dense_result = false;
  const std::array<double, 2> scales = FeatureScales(Fs, Ft);
  // ZoomOut reads the initial map at the samples only: match those.
  const Eigen::MatrixX3d source_normals = VertexNormals(Ys, source.F);
  EmbeddedPoints source_points;
  source_points.Y.resize(prefix.size(), 3);
  source_points.N.resize(prefix.size(), 3);
  for (size_t i = 0; i < prefix.size(); ++i) {
    source_points.Y.row(i) = Ys.row(prefix[i]);
    source_points.N.row(i) = source_normals.row(prefix[i]);
  }
  const Eigen::MatrixX3d target_embedded_normals = VertexNormals(Yt, target.F);
  const auto rotations = CandidateRotations();

  std::array<int, 4> order{0, 1, 2, 3};
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return scores[a] < scores[b]; });
  RefinedScores out;
  out.total = scores;
  out.disagreement.fill(std::numeric_limits<double>::quiet_NaN());
  out.orientation.fill(std::numeric_limits<double>::quiet_NaN());
  std::array<double, 4> score{};
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < options.candidates; ++r) {
    const int k = order[r];
    // The candidate's rotation applied to the target (y' = R y), as in the matching stage.
    const EmbeddedPoints turned{Yt * rotations[k].transpose(),
                                target_embedded_normals * rotations[k].transpose()};
    const MatchResult matched =
        MatchNearest(source_points, turned, options.normal_weight, /*threads=*/1);
    std::vector<int> initial(source.NumVertices(), 0);
    for (size_t i = 0; i < prefix.size(); ++i) initial[prefix[i]] = matched.map[i];
    const ZoomOutResult refined =
        ZoomOut(source_basis, target_basis, initial, prefix, zoomout, target_prefix);
    out.disagreement[k] = FeatureDisagreement(Fs, Ft, refined.map, scales, prefix);
    out.orientation[k] = MapOrientation(source, target, refined.map, prefix, kNeighbors);
    score[k] = out.disagreement[k] + (1.0 - out.orientation[k]) / 4.0;
    best = std::min(best, score[k]);
  }
  for (int r = 0; r < options.candidates; ++r) {
    const int k = order[r];
    out.total[k] += weight * (score[k] - best);
  }
  return out;
}

}  // namespace symembed
