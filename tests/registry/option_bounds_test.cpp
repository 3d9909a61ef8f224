// Every bounded stage option is checked against one declared Range by both its YAML reader and
// its options struct's IsValid: for each row of kBoundedOptions, values just inside and just
// outside each end of the range are accepted or rejected alike, with the same words, by the
// stage built from YAML and by IsValid. A new bounded option is covered by adding its row.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/fmap/zoomout.h"
#include "core/matching/deformed.h"
#include "core/matching/nearest.h"
#include "core/range.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "stages/embedding/lsmds.h"
#include "stages/flip/descriptor_map.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/hks.h"
#include "stages/flip/orientation.h"
#include "stages/flip/refined_agreement.h"
#include "stages/flip/term_refined_maps.h"
#include "stages/geodesics/fast_marching.h"
#include "stages/geodesics/heat.h"
#include "stages/preprocess/standard.h"
#include "stages/refine/discrete_opt.h"
#include "stages/refine/fmap_icp.h"
#include "stages/sampling/farthest_point.h"
#include "stages/symmetrize/ceres_symmetrize.h"
#include "stages/symmetry/plane2d.h"
#include "stages/symmetry/plane3d.h"

namespace symembed {
namespace {

// One bounded option: where the YAML reader finds it, and its options struct.
struct BoundedOption {
  std::string kind;  // stage kind ("dataset": read with `format` as the type key)
  std::string type;  // stage type
  // Further options of the stage that make the option read (e.g. the decision that has it).
  std::string context;
  std::string key;   // dotted path below the stage's map ("zoomout.samples")
  std::string name;  // the name IsValid gives it ("smacof: relaxation", "zoomout: samples")
  Range range;       // the declared range
  bool integer;
  // IsValid of the default options with the option set to the value.
  std::function<bool(double, std::string*)> is_valid;
};

#define BOUND(Struct, field, range, integer)         \
  range, integer, [](double v, std::string* error) { \
    Struct o;                                        \
    o.field = static_cast<decltype(o.field)>(v);     \
    return o.IsValid(error);                         \
  }

const std::vector<BoundedOption>& BoundedOptions() {
  using Lsmds = LsmdsOptions;
  using Smacof = SmacofOptions;
  using Oos = OutOfSampleOptions;
  using Search = ReflectionSearchOptions;
  using Spectral = SpectralSymmetryOptions;
  using Curv = ExtrinsicFlipOptions;
  using Desc = DescriptorMapOptions;
  using Maps = RefinedMapsTermOptions;
  using Agree = RefinedAgreementOptions;
  using Schedule = FlipZoomOutSchedule;
  static const std::vector<BoundedOption> rows = {
      {"preprocess", "standard", "", "max_removed_area", "max_removed_area",
       BOUND(StandardPreprocessOptions, max_removed_area,
             StandardPreprocessOptions::kMaxRemovedArea, false)},
      {"preprocess", "standard", "", "degenerate_tolerance", "degenerate_tolerance",
       BOUND(StandardPreprocessOptions, degenerate_tolerance,
             StandardPreprocessOptions::kDegenerateTolerance, false)},
      {"sampling", "farthest_point", "", "count", "count",
       BOUND(FarthestPointOptions, count, FarthestPointOptions::kCount, true)},
      {"geodesics", "fast_marching", "", "threads", "threads",
       BOUND(FastMarchingOptions, common.threads, GeodesicsCommonOptions::kThreads, true)},
      {"geodesics", "fast_marching", "", "max_unfold_steps", "max_unfold_steps",
       BOUND(FastMarchingOptions, max_unfold_steps, FastMarchingOptions::kMaxUnfoldSteps, true)},
      {"geodesics", "heat", "", "time_factor", "time_factor",
       BOUND(HeatOptions, time_factor, HeatOptions::kTimeFactor, false)},
      // embedding: lsmds
      {"embedding", "lsmds", "", "tolerance", "smacof: tolerance",
       BOUND(Lsmds, smacof.tolerance, Smacof::kTolerance, false)},
      {"embedding", "lsmds", "", "max_iterations", "smacof: max_iterations",
       BOUND(Lsmds, smacof.max_iterations, Smacof::kMaxIterations, true)},
      {"embedding", "lsmds", "", "weight_power", "smacof: weight_power",
       BOUND(Lsmds, smacof.weight_power, Smacof::kWeightPower, false)},
      {"embedding", "lsmds", "", "relaxation", "smacof: relaxation",
       BOUND(Lsmds, smacof.relaxation, Smacof::kRelaxation, false)},
      {"embedding", "lsmds", "", "anderson_window", "smacof: anderson_window",
       BOUND(Lsmds, smacof.anderson_window, Smacof::kAndersonWindow, true)},
      {"embedding", "lsmds", "", "neighbors", "out_of_sample: neighbors",
       BOUND(Lsmds, out_of_sample.neighbors, Oos::kNeighbors, true)},
      {"embedding", "lsmds", "", "out_of_sample_weight_power", "out_of_sample: weight_power",
       BOUND(Lsmds, out_of_sample.weight_power, Oos::kWeightPower, false)},
      {"embedding", "lsmds", "", "out_of_sample_iterations", "out_of_sample: max_iterations",
       BOUND(Lsmds, out_of_sample.max_iterations, Oos::kMaxIterations, true)},
      // symmetry: plane2d (the search options are plane3d's too)
      {"symmetry", "plane2d", "", "max_iterations", "max_iterations",
       BOUND(Plane2dOptions, search.max_iterations, Search::kMaxIterations, true)},
      {"symmetry", "plane2d", "", "trim_fraction", "trim_fraction",
       BOUND(Plane2dOptions, search.trim_fraction, Search::kTrimFraction, false)},
      {"symmetry", "plane2d", "", "outlier_distance", "outlier_distance",
       BOUND(Plane2dOptions, search.outlier_distance, Search::kOutlierDistance, false)},
      {"symmetry", "plane2d", "", "max_fixed_fraction", "max_fixed_fraction",
       BOUND(Plane2dOptions, search.max_fixed_fraction, Search::kMaxFixedFraction, false)},
      {"symmetry", "plane2d", "", "num_angles", "num_angles",
       BOUND(Plane2dOptions, num_angles, Plane2dOptions::kNumAngles, true)},
      {"symmetry", "plane2d", "", "intrinsic_weight", "intrinsic_weight",
       BOUND(Plane2dOptions, intrinsic.weight, IntrinsicCheckOptions::kWeight, false)},
      {"symmetry", "plane2d", "", "intrinsic_pairs", "intrinsic_pairs",
       BOUND(Plane2dOptions, intrinsic.pairs, IntrinsicCheckOptions::kPairs, true)},
      {"symmetry", "plane2d", "", "smacof_iterations", "smacof_iterations",
       BOUND(Plane2dOptions, smacof_iterations, Plane2dOptions::kSmacofIterations, true)},
      {"symmetry", "plane2d", "", "min_self_map_displacement", "min_self_map_displacement",
       BOUND(Plane2dOptions, min_self_map_displacement, Plane2dOptions::kMinSelfMapDisplacement,
             false)},
      {"symmetry", "plane2d", "", "second_plane_below", "second_plane_below",
       BOUND(Plane2dOptions, second_plane_below, Plane2dOptions::kSecondPlaneBelow, false)},
      {"symmetry", "plane2d", "", "refine_3d_iterations", "refine_3d_iterations",
       BOUND(Plane2dOptions, refine_3d_iterations, Plane2dOptions::kRefine3dIterations, true)},
      {"symmetry", "plane2d", "", "num_directions", "num_directions",
       BOUND(Plane2dOptions, num_directions, Plane2dOptions::kNumDirections, true)},
      {"symmetry", "plane2d", "", "spectral_eigenfunctions", "spectral_eigenfunctions",
       BOUND(Plane2dOptions, spectral.num_eigenfunctions, Spectral::kNumEigenfunctions, true)},
      {"symmetry", "plane2d", "", "spectral_candidates", "spectral_candidates",
       BOUND(Plane2dOptions, spectral.num_candidates, Spectral::kNumCandidates, true)},
      {"symmetry", "plane2d", "", "spectral_min_consistency", "spectral_min_consistency",
       BOUND(Plane2dOptions, spectral.min_consistency, Spectral::kMinConsistency, false)},
      {"symmetry", "plane2d", "", "spectral_weight", "spectral_weight",
       BOUND(Plane2dOptions, spectral.weight, Spectral::kWeight, false)},
      {"symmetry", "plane2d", "", "spectral_eigenvalue_tolerance", "spectral_eigenvalue_tolerance",
       BOUND(Plane2dOptions, spectral.eigenvalue_tolerance, Spectral::kEigenvalueTolerance, false)},
      {"symmetry", "plane2d", "", "distance_confidence", "distance_confidence",
       BOUND(Plane2dOptions, distance_confidence, Plane2dOptions::kDistanceConfidence, false)},
      {"symmetry", "plane2d", "", "threads", "threads",
       BOUND(Plane2dOptions, threads, Plane2dOptions::kThreads, true)},
      {"symmetry", "plane3d", "", "trim_fraction", "trim_fraction",
       BOUND(Plane3dOptions, search.trim_fraction, Search::kTrimFraction, false)},
      {"symmetry", "plane3d", "", "num_directions", "num_directions",
       BOUND(Plane3dOptions, num_directions, Plane3dOptions::kNumDirections, true)},
      {"symmetry", "plane3d", "", "intrinsic_weight", "intrinsic_weight",
       BOUND(Plane3dOptions, intrinsic.weight, IntrinsicCheckOptions::kWeight, false)},
      {"symmetry", "plane3d", "", "intrinsic_pairs", "intrinsic_pairs",
       BOUND(Plane3dOptions, intrinsic.pairs, IntrinsicCheckOptions::kPairs, true)},
      {"symmetry", "plane3d", "", "threads", "threads",
       BOUND(Plane3dOptions, threads, Plane3dOptions::kThreads, true)},
      // symmetrize: ceres
      {"symmetrize", "ceres", "", "symmetry_weight", "symmetry_weight",
       BOUND(CeresSymmetrizeOptions, symmetry_weight, CeresSymmetrizeOptions::kWeight, false)},
      {"symmetrize", "ceres", "", "plane_weight", "plane_weight",
       BOUND(CeresSymmetrizeOptions, plane_weight, CeresSymmetrizeOptions::kWeight, false)},
      {"symmetrize", "ceres", "", "anchor_weight", "anchor_weight",
       BOUND(CeresSymmetrizeOptions, anchor_weight, CeresSymmetrizeOptions::kWeight, false)},
      {"symmetrize", "ceres", "", "graph_neighbors", "graph_neighbors",
       BOUND(CeresSymmetrizeOptions, graph_neighbors, CeresSymmetrizeOptions::kGraphNeighbors,
             true)},
      {"symmetrize", "ceres", "", "mirror_neighbors", "mirror_neighbors",
       BOUND(CeresSymmetrizeOptions, mirror_neighbors, CeresSymmetrizeOptions::kMirrorNeighbors,
             true)},
      {"symmetrize", "ceres", "", "follow_neighbors", "follow_neighbors",
       BOUND(CeresSymmetrizeOptions, follow_neighbors, CeresSymmetrizeOptions::kFollowNeighbors,
             true)},
      {"symmetrize", "ceres", "", "max_iterations", "max_iterations",
       BOUND(CeresSymmetrizeOptions, max_iterations, CeresSymmetrizeOptions::kMaxIterations, true)},
      {"symmetrize", "ceres", "", "function_tolerance", "function_tolerance",
       BOUND(CeresSymmetrizeOptions, function_tolerance, CeresSymmetrizeOptions::kFunctionTolerance,
             false)},
      {"symmetrize", "ceres", "", "threads", "threads",
       BOUND(CeresSymmetrizeOptions, threads, CeresSymmetrizeOptions::kThreads, true)},
      {"symmetrize", "ceres", "", "warm_start_iterations", "warm_start_iterations",
       BOUND(CeresSymmetrizeOptions, warm_start_iterations,
             CeresSymmetrizeOptions::kWarmStartIterations, true)},
      {"symmetrize", "ceres", "", "warm_start_tolerance", "warm_start_tolerance",
       BOUND(CeresSymmetrizeOptions, warm_start_tolerance,
             CeresSymmetrizeOptions::kWarmStartTolerance, false)},
      // flip: hks, and the terms and decision of extrinsic
      {"flip", "hks", "", "eigenpairs", "eigenpairs",
       BOUND(HksFlipOptions, eigenpairs, HksFlipOptions::kEigenpairs, true)},
      {"flip", "hks", "", "num_times", "num_times",
       BOUND(HksFlipOptions, num_times, HksFlipOptions::kNumTimes, true)},
      {"flip", "hks", "", "threads", "threads",
       BOUND(HksFlipOptions, threads, HksFlipOptions::kThreads, true)},
      {"flip", "extrinsic", "", "terms.curvature.local_weight", "local_weight",
       BOUND(Curv, local_weight, Curv::kWeight, false)},
      {"flip", "extrinsic", "", "terms.curvature.chamfer_weight", "chamfer_weight",
       BOUND(Curv, chamfer_weight, Curv::kWeight, false)},
      {"flip", "extrinsic", "", "terms.curvature.profile_bins", "profile_bins",
       BOUND(Curv, profile_bins, Curv::kBins, true)},
      {"flip", "extrinsic", "", "terms.curvature.histogram_bins", "histogram_bins",
       BOUND(Curv, histogram_bins, Curv::kBins, true)},
      {"flip", "extrinsic", "", "terms.curvature.smoothing_rings", "smoothing_rings",
       BOUND(Curv, smoothing.rings, FeatureSmoothing::kRings, true)},
      {"flip", "extrinsic", "", "terms.curvature.smoothing_radius", "smoothing_radius",
       BOUND(Curv, smoothing.radius, FeatureSmoothing::kRadius, false)},
      {"flip", "extrinsic", "", "terms.descriptor.k", "k", BOUND(Desc, k, Desc::kK, true)},
      {"flip", "extrinsic", "", "terms.descriptor.eigenpairs", "eigenpairs",
       BOUND(Desc, eigenpairs, Desc::kEigenpairs, true)},
      {"flip", "extrinsic", "", "terms.descriptor.energies", "energies",
       BOUND(Desc, energies, Desc::kEnergies, true)},
      {"flip", "extrinsic", "", "terms.descriptor.sigma", "sigma",
       BOUND(Desc, sigma, Desc::kSigma, false)},
      {"flip", "extrinsic", "", "terms.descriptor.mu", "mu", BOUND(Desc, mu, Desc::kMu, false)},
      {"flip", "extrinsic", "", "terms.descriptor.samples", "samples",
       BOUND(Desc, samples, Desc::kSamples, true)},
      {"flip", "extrinsic", "", "terms.descriptor.axes", "axes",
       BOUND(Desc, axes, Desc::kAxes, true)},
      {"flip", "extrinsic", "", "terms.orientation.zoomout.k_start", "zoomout: k_start",
       BOUND(OrientationOptions, zoomout.k_start, Schedule::kKStart, true)},
      {"flip", "extrinsic", "", "terms.orientation.zoomout.k_end", "zoomout: k_end",
       BOUND(OrientationOptions, zoomout.k_end, Schedule::kKEnd, true)},
      {"flip", "extrinsic", "", "terms.orientation.zoomout.step", "zoomout: step",
       BOUND(OrientationOptions, zoomout.step, Schedule::kStep, true)},
      {"flip", "extrinsic", "", "terms.orientation.zoomout.samples", "zoomout: samples",
       BOUND(OrientationOptions, zoomout.samples, Schedule::kSamples, true)},
      {"flip", "extrinsic", "", "terms.orientation.zoomout.target_samples",
       "zoomout: target_samples",
       BOUND(OrientationOptions, zoomout.target_samples, Schedule::kTargetSamples, true)},
      {"flip", "extrinsic", "", "terms.refined_maps.sources", "sources",
       BOUND(Maps, sources, Maps::kSources, true)},
      {"flip", "extrinsic", "", "terms.refined_maps.targets", "targets",
       BOUND(Maps, targets, Maps::kTargets, true)},
      {"flip", "extrinsic", "", "terms.refined_maps.distortion_weight", "distortion_weight",
       BOUND(Maps, distortion_weight, Maps::kWeight, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.disagreement_weight", "disagreement_weight",
       BOUND(Maps, disagreement_weight, Maps::kWeight, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.orientation_weight", "orientation_weight",
       BOUND(Maps, orientation_weight, Maps::kWeight, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.long_axis_weight", "long_axis_weight",
       BOUND(Maps, long_axis_weight, Maps::kWeight, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.long_axis_time", "long_axis_time",
       BOUND(Maps, long_axis_time, Maps::kLongAxisTime, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.distortion_decides", "distortion_decides",
       BOUND(Maps, distortion_decides, Maps::kDistortionDecides, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.normal_weight", "normal_weight",
       BOUND(Maps, normal_weight, Maps::kNormalWeight, false)},
      {"flip", "extrinsic", "", "terms.refined_maps.zoomout.samples", "zoomout: samples",
       BOUND(Maps, zoomout.samples, Schedule::kSamples, true)},
      {"flip", "extrinsic", "decide: {type: refined_front_back}", "decide.margin", "margin",
       BOUND(Agree, margin, Agree::kMargin, false)},
      {"flip", "extrinsic", "decide: {type: refined_front_back}", "decide.normal_weight",
       "normal_weight", BOUND(Agree, normal_weight, Agree::kNormalWeight, false)},
      {"flip", "extrinsic", "decide: {type: refined_front_back}", "decide.zoomout.k_start",
       "zoomout: k_start", BOUND(Agree, zoomout.k_start, Schedule::kKStart, true)},
      // matching
      {"matching", "nearest_scaled", "", "iterations", "iterations",
       BOUND(ScaledIcpOptions, iterations, ScaledIcpOptions::kIterations, true)},
      {"matching", "nearest_scaled", "", "min_scale", "min_scale",
       BOUND(ScaledIcpOptions, min_scale, ScaledIcpOptions::kMinScale, false)},
      {"matching", "nearest_scaled", "", "max_scale", "max_scale",
       BOUND(ScaledIcpOptions, max_scale, ScaledIcpOptions::kMaxScale, false)},
      {"matching", "nearest_scaled", "", "normal_weight", "normal_weight",
       BOUND(ScaledIcpOptions, normal_weight, ScaledIcpOptions::kNormalWeight, false)},
      {"matching", "nearest_scaled", "", "threads", "threads",
       BOUND(ScaledIcpOptions, threads, ScaledIcpOptions::kThreads, true)},
      {"matching", "deformed", "", "k_start", "k_start",
       BOUND(DeformOptions, k_start, DeformOptions::kKStart, true)},
      {"matching", "deformed", "", "k_end", "k_end",
       BOUND(DeformOptions, k_end, DeformOptions::kKEnd, true)},
      {"matching", "deformed", "", "step", "step",
       BOUND(DeformOptions, step, DeformOptions::kStep, true)},
      {"matching", "deformed", "", "iterations", "iterations",
       BOUND(DeformOptions, iterations, DeformOptions::kIterations, true)},
      {"matching", "deformed", "", "smoothness", "smoothness",
       BOUND(DeformOptions, smoothness, DeformOptions::kSmoothness, false)},
      {"matching", "deformed", "", "samples", "samples",
       BOUND(DeformOptions, samples, DeformOptions::kSamples, true)},
      {"matching", "deformed", "", "normal_weight", "normal_weight",
       BOUND(DeformOptions, normal_weight, DeformOptions::kNormalWeight, false)},
      {"matching", "deformed", "", "threads", "threads",
       BOUND(DeformOptions, threads, DeformOptions::kThreads, true)},
      // refine
      {"refine", "zoomout", "", "k_start", "k_start",
       BOUND(ZoomOutOptions, k_start, ZoomOutOptions::kKStart, true)},
      {"refine", "zoomout", "", "k_end", "k_end",
       BOUND(ZoomOutOptions, k_end, ZoomOutOptions::kKEnd, true)},
      {"refine", "zoomout", "", "step", "step",
       BOUND(ZoomOutOptions, step, ZoomOutOptions::kStep, true)},
      {"refine", "discrete", "", "k_start", "k_start",
       BOUND(DiscreteOptOptions, k_start, DiscreteOptOptions::kKStart, true)},
      {"refine", "discrete", "", "k_end", "k_end",
       BOUND(DiscreteOptOptions, k_end, DiscreteOptOptions::kKEnd, true)},
      {"refine", "discrete", "", "step", "step",
       BOUND(DiscreteOptOptions, step, DiscreteOptOptions::kStep, true)},
      {"refine", "discrete", "", "descriptors", "descriptors",
       BOUND(DiscreteOptOptions, descriptors, DiscreteOptOptions::kDescriptors, true)},
      {"refine", "discrete", "", "weights.bijectivity", "weights.bijectivity",
       BOUND(DiscreteOptOptions, weights.bijectivity, DiscreteOptWeights::kWeight, false)},
      {"refine", "discrete", "", "weights.embedding", "weights.embedding",
       BOUND(DiscreteOptOptions, weights.embedding, DiscreteOptWeights::kWeight, false)},
      {"refine", "icp", "", "k", "k",
       BOUND(FunctionalMapIcpOptions, k, FunctionalMapIcpOptions::kK, true)},
      {"refine", "icp", "", "max_iterations", "max_iterations",
       BOUND(FunctionalMapIcpOptions, max_iterations, FunctionalMapIcpOptions::kMaxIterations,
             true)},
      // dataset: synthetic
      {"dataset", "synthetic", "", "poses", "poses",
       BOUND(SynthOptions, poses, SynthOptions::kPoses, true)},
      {"dataset", "synthetic", "", "vertices", "vertices",
       BOUND(SynthOptions, vertices, SynthOptions::kVertices, true)},
      {"dataset", "synthetic", "", "seed", "seed",
       BOUND(SynthOptions, seed, SynthOptions::kSeed, true)},
      {"dataset", "synthetic", "", "remesh", "remesh",
       BOUND(SynthOptions, remesh, SynthOptions::kRemesh, true)},
      {"dataset", "synthetic", "", "remesh_anisotropy", "remesh_anisotropy",
       BOUND(SynthOptions, remesh_anisotropy, SynthOptions::kRemeshAnisotropy, false)},
      {"dataset", "synthetic", "", "nonisometric", "nonisometric",
       BOUND(SynthOptions, nonisometric, SynthOptions::kNonisometric, false)},
      {"dataset", "synthetic", "", "noise", "noise",
       BOUND(SynthOptions, noise, SynthOptions::kNoise, false)},
      {"dataset", "synthetic", "", "partial", "partial",
       BOUND(SynthOptions, partial, SynthOptions::kFraction, false)},
      {"dataset", "synthetic", "", "plane_cuts", "plane_cuts",
       BOUND(SynthOptions, plane_cuts, SynthOptions::kFraction, false)},
      {"dataset", "synthetic", "", "holes", "holes",
       BOUND(SynthOptions, holes, SynthOptions::kFraction, false)},
      {"dataset", "synthetic", "", "glue", "glue",
       BOUND(SynthOptions, glue, SynthOptions::kFraction, false)},
      {"dataset", "synthetic", "", "glue_bridges", "glue_bridges",
       BOUND(SynthOptions, glue_bridges, SynthOptions::kGlueBridges, true)},
      {"dataset", "synthetic", "", "cross_class", "cross_class",
       BOUND(SynthOptions, cross_class, SynthOptions::kCrossClass, false)},
      {"dataset", "synthetic", "", "pairs", "pairs",
       BOUND(SynthOptions, pairs, SynthOptions::kPairs, true)},
  };
  return rows;
}

#undef BOUND

// Values just inside and just outside each finite end of the range: the end itself and its
// neighbour (the next integer, or a step of 1e-9 relative, which YAML carries exactly).
std::vector<double> Probes(const Range& range, bool integer) {
  std::vector<double> probes;
  const auto step = [&](double x) { return integer ? 1.0 : 1e-9 * std::max(1.0, std::fabs(x)); };
  if (std::isfinite(range.min())) {
    probes.push_back(range.min());
    probes.push_back(range.min_open() ? range.min() + step(range.min())
                                      : range.min() - step(range.min()));
  }
  if (std::isfinite(range.max())) {
    probes.push_back(range.max());
    probes.push_back(range.max_open() ? range.max() - step(range.max())
                                      : range.max() + step(range.max()));
  }
  return probes;
}

// {type: T, <context>, a: {b: value}} for the key "a.b".
std::string StageYaml(const BoundedOption& row, double value) {
  const std::string type_key = row.kind == "dataset" ? "format" : "type";
  std::string text =
      row.integer ? std::to_string(static_cast<long long>(value)) : FormatNumber(value);
  std::string key = row.key;
  int depth = 0;
  std::string nested;
  for (size_t dot; (dot = key.find('.')) != std::string::npos; key = key.substr(dot + 1)) {
    nested += key.substr(0, dot) + ": {";
    ++depth;
  }
  nested += key + ": " + text + std::string(depth, '}');
  // A context map shares the first key of the option (decide: {...}): merge the two.
  std::string yaml = "{" + type_key + ": " + row.type + ", ";
  if (!row.context.empty() && row.key.rfind("decide.", 0) == 0) {
    yaml += "decide: {type: refined_front_back, " + nested.substr(std::string("decide: {").size());
  } else {
    if (!row.context.empty()) yaml += row.context + ", ";
    yaml += nested;
  }
  return yaml + "}";
}

// The ConfigError of building the row's stage from YAML with the option at `value` ("" when it
// builds).
std::string YamlError(const Registry& registry, const BoundedOption& row, double value) {
  const std::string type_key = row.kind == "dataset" ? "format" : "type";
  try {
    registry.Create(row.kind, YAML::Load(StageYaml(row, value)), "t.yaml", "p", "", type_key);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionBounds, ReaderAndIsValidCheckTheSameDeclaredRange) {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const BoundedOption& row : BoundedOptions()) {
    const std::vector<double> probes = Probes(row.range, row.integer);
    ASSERT_FALSE(probes.empty()) << row.key << ": a bounded option has a finite end";
    for (double v : probes) {
      SCOPED_TRACE(row.kind + "/" + row.type + " " + row.key + " = " + FormatNumber(v) + " in " +
                   row.range.Text() + ": " + StageYaml(row, v));
      const auto has = [](const std::string& text, const std::string& part) {
        return text.find(part) != std::string::npos;
      };
      // Outside, the reader refuses the value naming file:line:col, the dotted key, the declared
      // range and the value; inside, it refuses no value of the key for its range (it may for
      // another option's sake, as k_start above the default k_end).
      const std::string yaml_error = YamlError(registry, row, v);
      const std::string key = "p." + row.key + ": ";
      if (row.range.Contains(v)) {
        EXPECT_FALSE(has(yaml_error, key + "must be in ")) << yaml_error;
      } else {
        EXPECT_TRUE(has(yaml_error, key + row.range.Violation(v))) << yaml_error;
        EXPECT_EQ(yaml_error.rfind("t.yaml:1:", 0), 0u) << yaml_error;
      }
      // IsValid the same, in the same words ("relaxation must be in [1, 2), got 2").
      std::string error;
      const bool valid = row.is_valid(v, &error);
      if (row.range.Contains(v)) {
        EXPECT_FALSE(has(error, row.name + " must be in ") || has(error, row.name + ": must be in "))
            << error;
      } else {
        EXPECT_FALSE(valid);
        EXPECT_TRUE(has(error, row.name + " " + row.range.Violation(v)) ||
                    has(error, row.name + ": " + row.range.Violation(v)))
            << error;
      }
    }
  }
}

}  // namespace
}  // namespace symembed
