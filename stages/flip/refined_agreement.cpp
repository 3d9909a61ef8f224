#include "stages/flip/refined_agreement.h"

#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/zoomout.h"
#include "core/laplacian.h"
#include "core/matching/nearest.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/orientation.h"

namespace symembed {
namespace {
// Nearest samples whose pairs make the triangles of the orientation (orientation.h).
constexpr int kNeighbors = 6;

// The rows of `points` (positions and normals) at the given vertices.
EmbeddedPoints PointsAt(const EmbeddedPoints& points, const std::vector<int>& vertices) {
  EmbeddedPoints out;
  out.Y.resize(vertices.size(), 3);
  out.N.resize(vertices.size(), 3);
  for (size_t i = 0; i < vertices.size(); ++i) {
    out.Y.row(i) = points.Y.row(vertices[i]);
    out.N.row(i) = points.N.row(vertices[i]);
  }
  return out;
}
}  // namespace

bool RefinedAgreementOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  std::string schedule;
  if (!zoomout.IsValid(&schedule)) out << "zoomout: " << schedule;
  if (out.str().empty()) out << FieldViolation(*this);
  return NoViolation(out.str(), error);
}

RefinedCandidates::RefinedCandidates(const ShapeData& source, const ShapeData& target,
                                     const LaplaceBasis& source_basis,
                                     const LaplaceBasis& target_basis,
                                     const FlipZoomOutSchedule& schedule, double normal_weight,
                                     const std::string& what, const DeformOptions* deform)
    : source_(source), target_(target), source_basis_(source_basis), normal_weight_(normal_weight) {
  if (deform) deform_ = *deform;
  prefix_ = SamplePrefix(source.samples, schedule.samples, schedule.k_end,
                         what + ": shape '" + source.name + "'");
  target_prefix_ = schedule.TargetPrefix(target.samples, what + ": shape '" + target.name + "'");
  zoomout_ = std::make_unique<ZoomOutSetup>(source_basis, target_basis, prefix_,
                                            schedule.ZoomOut(), target_prefix_);
  source_all_ = EmbeddedShape(source);
  source_points_ = PointsAt(source_all_, prefix_);
  target_points_ = EmbeddedShape(target);
  triangles_ = MakeSourceTriangles(source.surface, prefix_, kNeighbors);
  target_normals_ = VertexNormals(target.surface);
}

ZoomOutResult RefinedCandidates::Refine(int k) const {
  const EmbeddedPoints target = Rotated(target_points_, CandidateRotations()[k]);
  MatchResult matched;
  if (deform_) {
    // The deformation fits the shapes' own samples (the first deform_->samples of each), as the
    // matching stage does, so that the candidates start where the pipeline's map would.
    DeformResult bent = DeformSource(source_all_, source_.surface.F, source_basis_, source_.samples,
                                     target, target_.samples, *deform_);
    const EmbeddedPoints moved{std::move(bent.Y), std::move(bent.N)};
    matched = MatchNearest(PointsAt(moved, prefix_), target, normal_weight_, /*threads=*/1);
  } else {
    matched = MatchNearest(source_points_, target, normal_weight_, /*threads=*/1);
  }
  std::vector<int> initial(source_.surface.NumVertices(), 0);
  for (size_t i = 0; i < prefix_.size(); ++i) initial[prefix_[i]] = matched.map[i];
  return zoomout_->Run(initial);
}

double RefinedCandidates::Orientation(const std::vector<int>& map) const {
  return TriangleOrientation(triangles_, target_.surface, target_normals_, map);
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
  const RefinedCandidates candidates(source, target, source_basis, target_basis, options.zoomout,
                                     options.normal_weight, "flip refined");
  const std::array<double, 2> scales = FeatureScales(Fs, Ft);

  RefinedChoice out;
  out.best = CandidateOrder(scores)[0];
  out.partner = FrontBackPartner(out.best);
  out.disagreement.fill(std::numeric_limits<double>::quiet_NaN());
  out.orientation.fill(std::numeric_limits<double>::quiet_NaN());
  out.score.fill(std::numeric_limits<double>::quiet_NaN());
  for (const int k : {out.best, out.partner}) {
    const ZoomOutResult refined = candidates.Refine(k);
    out.disagreement[k] = FeatureDisagreement(Fs, Ft, refined.map, scales, candidates.samples());
    out.orientation[k] = candidates.Orientation(refined.map);
    out.score[k] = out.disagreement[k] + (1.0 - out.orientation[k]) / 4.0;
  }
  out.chosen = out.score[out.best] - out.score[out.partner] >= options.margin ? out.partner
                                                                               : out.best;
  return out;
}

}  // namespace symembed
