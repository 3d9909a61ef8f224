#include "stages/flip/term_refined_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/mesh_graph.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/refined_agreement.h"

namespace symembed {
namespace {

// The key of a shape's graph geodesics from its first `sources` samples (#sources x #V).
ProductKey<Eigen::MatrixXd> SampleGeodesicsKey(int sources) {
  return {"sample_geodesics", "dijkstra sources=" + std::to_string(sources)};
}

// The deformation of the initial maps: the matching stage's defaults with the term's normals.
DeformOptions Deformation(const RefinedMapsTermOptions& options) {
  DeformOptions deform;
  deform.normal_weight = options.normal_weight;
  return deform;
}

}  // namespace

bool RefinedMapsTermOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  std::string schedule;
  if (!zoomout.IsValid(&schedule)) out << "zoomout: " << schedule;
  if (out.str().empty()) out << FieldViolation(*this);
  if (out.str().empty() && targets < sources) {
    out << "targets must be >= sources (" << sources << "), got " << targets;
  }
  if (out.str().empty() && targets > zoomout.samples) {
    out << "targets must be <= zoomout.samples (" << zoomout.samples << "), got " << targets;
  }
  return NoViolation(out.str(), error);
}

double GeodesicDistortion(const Eigen::MatrixXd& source_distances, const MeshGraph& target,
                          const std::vector<int>& samples, int targets,
                          const std::vector<int>& map) {
  const int sources = static_cast<int>(source_distances.rows());
  if (targets < sources || targets > static_cast<int>(samples.size())) {
    throw InvalidInputError("flip refined_maps: " + std::to_string(targets) + " target samples for " +
                            std::to_string(sources) + " sources and " +
                            std::to_string(samples.size()) + " samples");
  }
  const int nt = target.NumVertices();
  std::vector<int> images(sources);
  for (int j = 0; j < targets; ++j) {
    const int s = samples[j];
    if (s < 0 || s >= static_cast<int>(map.size()) || s >= source_distances.cols() ||
        map[s] < 0 || map[s] >= nt) {
      throw InvalidInputError("flip refined_maps: sample " + std::to_string(s) +
                              " or its image is out of range");
    }
    if (j < sources) images[j] = map[s];
  }
  const Eigen::MatrixXd target_distances = EdgeGraphDistances(target, images);
  double difference = 0.0, length = 0.0;
  for (int i = 0; i < sources; ++i) {
    for (int j = 0; j < targets; ++j) {
      const int s = samples[j];
      // Points in another component than the source (unreachable) do not count.
      const double ds = source_distances(i, s), dt = target_distances(i, map[s]);
      if (!std::isfinite(ds) || !std::isfinite(dt)) continue;
      difference += std::abs(ds - dt);
      length += ds;
    }
  }
  return length > 0.0 ? difference / length : 1.0;
}

RefinedMapsTerm::RefinedMapsTerm(double weight, const RefinedMapsTermOptions& options)
    : FlipTerm(weight), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip refined_maps: " + error);
}

void RefinedMapsTerm::AddNeeds(int, ShapeNeeds* needs) const {
  const int count = options_.sources;
  needs->products.push_back(NeedProduct(
      SampleGeodesicsKey(count), ProductInput::kSamples, 0,
      [count](const ShapeData& shape, const LaplaceBasis&) {
        const std::vector<int> sources = SamplePrefix(
            shape.samples, count, 1, "flip refined_maps: shape '" + shape.name + "'");
        return EdgeGraphDistances(shape.surface, sources);
      }));
  needs->products.push_back(CurvatureFeaturesNeed(options_.smoothing));
  if (options_.long_axis_weight > 0.0) {
    needs->products.push_back(DiffusedFeaturesNeed(options_.smoothing, options_.long_axis_time));
  }
}

int RefinedMapsTerm::BasisSize() const {
  return options_.deformed_start ? std::max(options_.zoomout.k_end, Deformation(options_).k_end)
                                 : options_.zoomout.k_end;
}

void RefinedMapsTerm::Score(const FlipTermContext& context, std::array<double, 4>* total,
                         std::ostringstream* detail) const {
  const ShapeData& source = context.pair.source;
  const ShapeData& target = context.pair.target;
  const Eigen::MatrixXd& source_distances =
      ProductOf(source, SampleGeodesicsKey(options_.sources));
  const Eigen::MatrixXd& Fs = ProductOf(source, CurvatureFeaturesKey(options_.smoothing));
  const Eigen::MatrixXd& Ft = ProductOf(target, CurvatureFeaturesKey(options_.smoothing));
  // Shapes with fewer samples than the options ask for use all of theirs.
  const int sources = std::min<int>(options_.sources, source.samples.size());
  if (source_distances.rows() != sources ||
      source_distances.cols() != source.surface.NumVertices()) {
    throw InvalidInputError("flip refined_maps: shape '" + source.name +
                            "' has geodesics that do not match the options");
  }
  const DeformOptions deform = Deformation(options_);
  const RefinedCandidates candidates(source, target, context.source_basis, context.target_basis,
                                     options_.zoomout, options_.normal_weight, "flip refined_maps",
                                     options_.deformed_start ? &deform : nullptr);
  const std::vector<int>& prefix = candidates.samples();
  const std::array<double, 2> scales = FeatureScales(Fs, Ft);
  const int targets = std::max(sources, std::min<int>(options_.targets, prefix.size()));
  const bool long_axis = options_.long_axis_weight > 0.0;
  const Eigen::MatrixXd* Cs = nullptr;
  const Eigen::MatrixXd* Ct = nullptr;
  std::array<double, 2> long_axis_scales{};
  if (long_axis) {
    const auto key = DiffusedFeaturesKey(options_.smoothing, options_.long_axis_time);
    Cs = &ProductOf(source, key);
    Ct = &ProductOf(target, key);
    long_axis_scales = FeatureScales(*Cs, *Ct);
  }
  std::array<double, 4> distortion{}, disagreement{}, orientation{}, diffused{}, vote{};
  std::array<std::vector<int>, 4> maps;
  // The target's edge graph once for the four candidates' distances.
  const MeshGraph target_graph = BuildMeshGraph(target.surface);
  for (int k = 0; k < 4; ++k) {
    ZoomOutResult refined = candidates.Refine(k);
    distortion[k] =
        GeodesicDistortion(source_distances, target_graph, prefix, targets, refined.map);
    disagreement[k] = FeatureDisagreement(Fs, Ft, refined.map, scales, prefix);
    orientation[k] = candidates.Orientation(refined.map);
    if (long_axis) {
      diffused[k] = FeatureDisagreement(*Cs, *Ct, refined.map, long_axis_scales, prefix);
    }
    maps[k] = std::move(refined.map);
  }
  const bool voting = options_.front_back_vote > 0.0;
  if (voting) {
    // The partner's vote is the candidate's, negated (exactly: the same terms summed).
    for (const int k : {0, 1}) {
      vote[k] = FeatureVote(Fs, Ft, maps[k], maps[FrontBackPartner(k)], scales, prefix);
      vote[FrontBackPartner(k)] = -vote[k];
    }
  }
  // The lower distortion of each pair of partners (k and FrontBackPartner(k)), and the pair it
  // rules out, if any.
  std::array<double, 4> pair_distortion{};
  for (int k = 0; k < 4; ++k) {
    pair_distortion[k] = std::min(distortion[k], distortion[FrontBackPartner(k)]);
  }
  static_assert(FrontBackPartner(0) != 1, "candidates 0 and 1 lie in different pairs");
  const double lower = std::min(pair_distortion[0], pair_distortion[1]);
  const double higher = std::max(pair_distortion[0], pair_distortion[1]);
  const bool ruled = options_.distortion_decides > 0.0 &&
                     higher >= options_.distortion_decides * lower && higher > lower;
  for (int k = 0; k < 4; ++k) {
    const int partner = FrontBackPartner(k);
    const double g = options_.distortion_front_back ? distortion[k] : pair_distortion[k];
    const double c = voting ? std::min(disagreement[k], disagreement[partner]) +
                                  options_.front_back_vote * std::max(0.0, -vote[k])
                            : disagreement[k];
    (*total)[k] += weight() * (options_.distortion_weight * g + options_.disagreement_weight * c +
                               options_.orientation_weight * (1.0 - orientation[k]));
    if (long_axis) {
      (*total)[k] +=
          weight() * options_.long_axis_weight * std::min(diffused[k], diffused[partner]);
    }
  }
  if (ruled) {
    // Above every candidate of the better pair, each by its distortion gap.
    double kept_highest = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
      if (pair_distortion[k] == lower) kept_highest = std::max(kept_highest, (*total)[k]);
    }
    for (int k = 0; k < 4; ++k) {
      if (pair_distortion[k] == lower) continue;
      (*total)[k] = std::max((*total)[k], kept_highest + weight() * options_.distortion_weight *
                                                             (pair_distortion[k] - lower));
    }
  }
  // Distortion / disagreement / orientation of each candidate's refined map, and its disagreement
  // of the diffused features.
  *detail << "; refined_maps";
  for (int k = 0; k < 4; ++k) {
    *detail << " " << distortion[k] << "/" << disagreement[k] << "/" << orientation[k];
  }
  if (long_axis) {
    *detail << "; long_axis";
    for (int k = 0; k < 4; ++k) *detail << " " << diffused[k];
  }
  if (ruled) *detail << "; long axis by distortion";
  if (voting) {
    *detail << "; front_back_vote";
    for (int k = 0; k < 4; ++k) *detail << " " << vote[k];
  }
}

std::unique_ptr<FlipTerm> ReadRefinedMapsTerm(OptionReader& o, double weight) {
  RefinedMapsTermOptions r;
  r.zoomout = ReadFlipZoomOutSchedule(o, "zoomout", r.zoomout);
  ReadValidFields(o, &r);
  return std::make_unique<RefinedMapsTerm>(weight, r);
}

}  // namespace symembed
