#include "stages/flip/refined_agreement.h"

#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/laplacian.h"
#include "registry/pair_pipeline.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/orientation.h"
#include "stages/matching/nearest.h"
#include "stages/refine/zoomout.h"

namespace symembed {
namespace {
// Nearest samples whose pairs make the triangles of the orientation (orientation.h).
constexpr int kNeighbors = 6;
}  // namespace

bool RefinedAgreementOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  std::string schedule;
  if (!zoomout.IsValid(&schedule)) out << "zoomout: " << schedule;
  else if (!(margin >= 0.0)) out << "margin must be >= 0";
  else if (!(normal_weight >= 0.0)) out << "normal_weight must be >= 0";
  if (error) *error = out.str();
  return out.str().empty();
}

RefinedChoice RefinedFrontBackChoice(const std::array<double, 4>& scores,
                                     const ShapeData& source, const ShapeData& target,
                                     const LaplaceBasis& source_basis,
                                     const LaplaceBasis& target_basis, const Eigen::MatrixXd& Fs,
                                     const Eigen::MatrixXd& Ft,
                                     const RefinedAgreementOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip refined: " + error);
  if (Fs.rows() != source.surface.NumVertices() || Ft.rows() != target.surface.NumVertices()) {
    throw InvalidInputError("flip refined: features do not match the surfaces");
  }
  const std::vector<int> prefix =
      SamplePrefix(source.samples, options.zoomout.samples, options.zoomout.k_end,
                   "flip refined: shape '" + source.name + "'");
  const std::vector<int> target_prefix =
      options.zoomout.TargetPrefix(target.samples, "flip refined: shape '" + target.name + "'");
  // What does not depend on the candidate, once: ZoomOut's setup, the feature scales, the
  // embedded points of the source samples (ZoomOut reads the initial map at the samples only) and
  // of the target, and the triangles and normals of the orientation.
  const ZoomOutSetup zoomout_setup(source_basis, target_basis, prefix, options.zoomout.ZoomOut(),
                                   target_prefix);
  const std::array<double, 2> scales = FeatureScales(Fs, Ft);
  const EmbeddedPoints source_all = EmbeddedShape(source);
  EmbeddedPoints source_points;
  source_points.Y.resize(prefix.size(), 3);
  source_points.N.resize(prefix.size(), 3);
  for (size_t i = 0; i < prefix.size(); ++i) {
    source_points.Y.row(i) = source_all.Y.row(prefix[i]);
    source_points.N.row(i) = source_all.N.row(prefix[i]);
  }
  const EmbeddedPoints target_points = EmbeddedShape(target);
  const SourceTriangles triangles = MakeSourceTriangles(source.surface, prefix, kNeighbors);
  const Eigen::MatrixX3d target_normals = VertexNormals(target.surface);
  const auto rotations = CandidateRotations();

  RefinedChoice out;
  out.best = CandidateOrder(scores)[0];
  out.partner = FrontBackPartner(out.best);
  out.disagreement.fill(std::numeric_limits<double>::quiet_NaN());
  out.orientation.fill(std::numeric_limits<double>::quiet_NaN());
  out.score.fill(std::numeric_limits<double>::quiet_NaN());
  for (const int k : {out.best, out.partner}) {
    // The candidate's rotation applied to the target, as the matching stage gets it.
    const MatchResult matched = MatchNearest(source_points, Rotated(target_points, rotations[k]),
                                             options.normal_weight, /*threads=*/1);
    std::vector<int> initial(source.surface.NumVertices(), 0);
    for (size_t i = 0; i < prefix.size(); ++i) initial[prefix[i]] = matched.map[i];
    const ZoomOutResult refined = zoomout_setup.Run(initial);
    out.disagreement[k] = FeatureDisagreement(Fs, Ft, refined.map, scales, prefix);
    out.orientation[k] =
        TriangleOrientation(triangles, target.surface, target_normals, refined.map);
    out.score[k] = out.disagreement[k] + (1.0 - out.orientation[k]) / 4.0;
  }
  out.chosen = out.score[out.best] - out.score[out.partner] >= options.margin ? out.partner
                                                                               : out.best;
  return out;
}

}  // namespace symembed
