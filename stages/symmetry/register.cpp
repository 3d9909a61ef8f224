// The symmetry stages: thin adapters around DetectSymmetryPlane2d / DetectSymmetryPlane3d.
#include "stages/register.h"

#include <algorithm>
#include <memory>

#include "stages/symmetry/plane2d.h"
#include "stages/symmetry/plane3d.h"

namespace symembed {
namespace {

ReflectionSearchOptions ReadSearchOptions(OptionReader& o) {
  ReflectionSearchOptions s;
  using R = ReflectionSearchOptions;
  s.max_iterations = o.GetInt("max_iterations", s.max_iterations, R::kMaxIterations);
  s.trim_fraction = o.GetDouble("trim_fraction", s.trim_fraction, R::kTrimFraction);
  s.outlier_distance = o.GetDouble("outlier_distance", s.outlier_distance, R::kOutlierDistance);
  s.max_fixed_fraction =
      o.GetDouble("max_fixed_fraction", s.max_fixed_fraction, R::kMaxFixedFraction);
  return s;
}

class Plane2dStage;

// What Plane2dStage::Run keeps in its result: the candidates, from which RunAlternative chooses
// again when it is asked by the same stage about the same samples and embedding.
struct Plane2dDetection {
  const Plane2dStage* stage = nullptr;
  std::vector<int> samples;
  Eigen::MatrixXd Y;
  std::shared_ptr<const Plane2dCandidates> candidates;
};

class Plane2dStage : public SymmetryStage {
 public:
  explicit Plane2dStage(Plane2dOptions options) : options_(options) {}
  SymmetryResult Run(const SymmetryInput& in) const override {
    std::shared_ptr<const Plane2dCandidates> candidates = Search(in, options_);
    SymmetryResult result = ChoosePlane2d(*candidates, options_.min_self_map_displacement);
    result.detection = std::make_shared<const Plane2dDetection>(
        Plane2dDetection{this, in.samples, in.embedding.Y, std::move(candidates)});
    return result;
  }

  // Below second_plane_below, the best candidate that moves the samples at least that much;
  // above it, the nearly tied candidate that moves them clearly more (tie_displacement).
  SymmetryResult RunAlternative(const SymmetryInput& in,
                                const SymmetryResult& chosen) const override {
    const double bound = options_.second_plane_below;
    if (!(bound > 0.0) || chosen.sigma.empty()) return SymmetryResult{};
    double moves_at_least = chosen.tie_displacement;
    if (SampleSelfMapDisplacement(in.embedding.Y, in.samples, chosen.sigma) < bound) {
      moves_at_least = bound;
    }
    if (!(moves_at_least > 0.0)) return SymmetryResult{};
    const double bound2 = std::max(options_.min_self_map_displacement, moves_at_least);
    // The candidates do not depend on the bound: those of Run when it kept them.
    const auto* kept = std::any_cast<std::shared_ptr<const Plane2dDetection>>(&chosen.detection);
    const Plane2dDetection* d = kept ? kept->get() : nullptr;
    const bool same = d && d->stage == this && d->samples == in.samples &&
                      d->Y.rows() == in.embedding.Y.rows() &&
                      d->Y.cols() == in.embedding.Y.cols() && d->Y == in.embedding.Y;
    SymmetryResult second =
        same ? ChoosePlane2d(*d->candidates, bound2) : ChoosePlane2d(*Search(in, options_), bound2);
    if (second.sigma == chosen.sigma) return SymmetryResult{};
    second.status.message = "second plane: " + second.status.message;
    return second;
  }

 private:
  static std::shared_ptr<const Plane2dCandidates> Search(const SymmetryInput& in,
                                                         const Plane2dOptions& options) {
    const int k = options.spectral.num_eigenfunctions;
    Eigen::VectorXd evals;
    const Eigen::MatrixXd G =
        k > 0 ? SampleSpectralCoordinates(in.surface, in.samples, k, &evals) : Eigen::MatrixXd();
    return SearchPlane2d(in.D, in.samples, in.embedding.Y, options, G, evals);
  }

  Plane2dOptions options_;
};

class Plane3dStage : public SymmetryStage {
 public:
  explicit Plane3dStage(Plane3dOptions options) : options_(options) {}
  SymmetryResult Run(const SymmetryInput& in) const override {
    return DetectSymmetryPlane3d(in.D, in.samples, in.embedding.Y, options_);
  }

 private:
  Plane3dOptions options_;
};

}  // namespace

void RegisterSymmetryStages(Registry& registry) {
  registry.Add(
      "symmetry", "plane2d",
      "reflection line in a 2D LS-MDS embedding of the samples (angle sweep, "
      "reflect/NN/refit, intrinsic and spectral checks, eigenfunction sign-flip "
      "candidates), lifted to a plane in the 3D embedding",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        using P = Plane2dOptions;
        using S = SpectralSymmetryOptions;
        Plane2dOptions p;
        p.search = ReadSearchOptions(o);
        p.num_angles = o.GetInt("num_angles", p.num_angles, P::kNumAngles);
        p.intrinsic_weight =
            o.GetDouble("intrinsic_weight", p.intrinsic_weight, P::kIntrinsicWeight);
        p.intrinsic_pairs = o.GetInt("intrinsic_pairs", p.intrinsic_pairs, P::kIntrinsicPairs);
        p.seed = o.GetInt("seed", p.seed);
        p.smacof_iterations =
            o.GetInt("smacof_iterations", p.smacof_iterations, P::kSmacofIterations);
        p.min_self_map_displacement = o.GetDouble(
            "min_self_map_displacement", p.min_self_map_displacement, P::kMinSelfMapDisplacement);
        p.second_plane_below =
            o.GetDouble("second_plane_below", p.second_plane_below, P::kSecondPlaneBelow);
        p.second_plane_tie =
            o.GetDouble("second_plane_tie", p.second_plane_tie, P::kSecondPlaneTie);
        p.refine_3d_iterations =
            o.GetInt("refine_3d_iterations", p.refine_3d_iterations, P::kRefine3dIterations);
        p.candidates_3d = o.GetBool("candidates_3d", p.candidates_3d);
        p.num_directions = o.GetInt("num_directions", p.num_directions, P::kNumDirections);
        p.spectral.num_eigenfunctions = o.GetInt(
            "spectral_eigenfunctions", p.spectral.num_eigenfunctions, S::kNumEigenfunctions);
        p.spectral.num_candidates =
            o.GetInt("spectral_candidates", p.spectral.num_candidates, S::kNumCandidates);
        p.spectral.min_consistency =
            o.GetDouble("spectral_min_consistency", p.spectral.min_consistency, S::kMinConsistency);
        p.spectral.weight = o.GetDouble("spectral_weight", p.spectral.weight, S::kWeight);
        p.spectral.eigenvalue_tolerance =
            o.GetDouble("spectral_eigenvalue_tolerance", p.spectral.eigenvalue_tolerance,
                        S::kEigenvalueTolerance);
        // Read (and so written to the resolved config) only when given: off, the
        // stage's resolved options, and with them every cache key, stay as they were.
        p.distance_confidence = o.GetDoubleIfGiven("distance_confidence", p.distance_confidence,
                                                   P::kDistanceConfidence);
        p.threads = o.GetInt("threads", p.threads, P::kThreads);
        std::string error;
        if (!p.IsValid(&error)) o.Fail("", error);
        return std::make_unique<Plane2dStage>(p);
      });
  registry.Add("symmetry", "plane3d",
               "reflection plane searched in the 3D embedding (principal axes + sphere of "
               "normals, reflect/NN/refit, trimmed score, intrinsic check)",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 using P = Plane3dOptions;
                 Plane3dOptions p;
                 p.search = ReadSearchOptions(o);
                 p.num_directions = o.GetInt("num_directions", p.num_directions, P::kNumDirections);
                 p.intrinsic_weight =
                     o.GetDouble("intrinsic_weight", p.intrinsic_weight, P::kIntrinsicWeight);
                 p.intrinsic_pairs =
                     o.GetInt("intrinsic_pairs", p.intrinsic_pairs, P::kIntrinsicPairs);
                 p.seed = o.GetInt("seed", p.seed);
                 p.threads = o.GetInt("threads", p.threads, P::kThreads);
                 std::string error;
                 if (!p.IsValid(&error)) o.Fail("", error);
                 return std::make_unique<Plane3dStage>(p);
               });
}

}  // namespace symembed
