// The symmetry stages: thin adapters around DetectSymmetryPlane2d / DetectSymmetryPlane3d.
#include "stages/register.h"

#include <algorithm>
#include <memory>

#include "stages/symmetry/plane2d.h"
#include "stages/symmetry/plane3d.h"

namespace symembed {
namespace {

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
  registry.Add("symmetry", "plane2d",
               "reflection line in a 2D LS-MDS embedding of the samples (angle sweep, "
               "reflect/NN/refit, intrinsic and spectral checks, eigenfunction sign-flip "
               "candidates), lifted to a plane in the 3D embedding",
               FieldsFactory<Plane2dStage, Plane2dOptions>());
  registry.Add("symmetry", "plane3d",
               "reflection plane searched in the 3D embedding (principal axes + sphere of "
               "normals, reflect/NN/refit, trimmed score, intrinsic check)",
               FieldsFactory<Plane3dStage, Plane3dOptions>());
}

}  // namespace symembed
