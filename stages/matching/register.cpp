// The matching stages: thin adapters around MatchNearest / MatchNearestScaled / DeformSource,
// each matching a pair with a partial shape by MatchPartial instead.
#include <memory>

#include "core/matching/deformed.h"
#include "core/matching/nearest.h"
#include "core/matching/partial.h"
#include "registry/hash.h"
#include "registry/product_needs.h"
#include "stages/register.h"

namespace symembed {
namespace {

// A matching stage that matches a pair with a partial shape on the surfaces (MatchPartial,
// in the shapes' input units).
class PartialAwareMatchingStage : public MatchingStage {
 public:
  void set_partial(const PartialMatchOptions& partial) { partial_ = partial; }
  bool MatchSurfaces(const PairInput& pair, const std::vector<int>& seed,
                     SurfaceMatch* out) const override {
    const Surface& source = pair.source.surface;
    const Surface& target = pair.target.surface;
    if (!IsPartialPair(source, target, partial_)) return false;
    const PartialRows rows{rows_.get(), ContentKey(source), ContentKey(target),
                           shape_index_.get()};
    const double source_unit = 1.0 / pair.source.scale, target_unit = 1.0 / pair.target.scale;
    out->result = MatchPartial(source, pair.source.samples, source_unit, target,
                               pair.target.samples, target_unit, partial_, &seed, rows,
                               {&pair.source.symmetry.sigma, &pair.target.symmetry.sigma});
    auto distortion = [&](const std::vector<int>& map) {
      return LandmarkDistortion(source, pair.source.samples, source_unit, target,
                                pair.target.samples, target_unit, map, 40, rows);
    };
    out->distortion = distortion(out->result.map);
    out->seed_distortion = distortion(seed);
    return true;
  }

 private:
  // The shape's key among the rows kept: its vertices and faces.
  static uint64_t ContentKey(const Surface& surface) {
    return Hasher()
        .AddU64(static_cast<uint64_t>(surface.V.rows()))
        .AddBytes(surface.V.data(), sizeof(double) * surface.V.size())
        .AddBytes(surface.F.data(), sizeof(int) * surface.F.size())
        .Digest();
  }

  PartialMatchOptions partial_;
  // The distance rows of the shapes of partial pairs, kept across the pairs of a run: a whole
  // shape's samples are the same in every pair it is in. The cache is thread-safe, so matching
  // stays const.
  std::unique_ptr<EdgeDistanceCache> rows_ =
      std::make_unique<EdgeDistanceCache>(size_t{384} << 20);
  // Their smoothed shape indices, likewise (a whole shape's is the same in every pair).
  std::unique_ptr<ShapeIndexCache> shape_index_ =
      std::make_unique<ShapeIndexCache>(size_t{64} << 20);
};

// Reads the option of the partial route and returns the stage with it.
std::unique_ptr<Stage> WithPartialRoute(OptionReader& o,
                                        std::unique_ptr<PartialAwareMatchingStage> stage) {
  PartialMatchOptions partial;
  partial.boundary_ratio = o.GetDouble("partial_boundary_ratio", partial.boundary_ratio,
                                       PartialMatchOptions::kBoundaryRatio);
  stage->set_partial(partial);
  return stage;
}

class NearestStage : public PartialAwareMatchingStage {
 public:
  NearestStage(double normal_weight, int threads)
      : normal_weight_(normal_weight), threads_(threads) {}
  MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const override {
    return MatchNearest(source, target, normal_weight_, threads_);
  }

 private:
  double normal_weight_;
  int threads_;
};

class NearestScaledStage : public PartialAwareMatchingStage {
 public:
  explicit NearestScaledStage(ScaledIcpOptions options) : options_(options) {}
  MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const override {
    return MatchNearestScaled(source, target, options_);
  }

 private:
  ScaledIcpOptions options_;
};

class DeformedStage : public PartialAwareMatchingStage {
 public:
  explicit DeformedStage(DeformOptions options) : options_(options) {}
  ShapeNeeds Needs() const override {
    ShapeNeeds needs;
    needs.basis = options_.k_end;
    return needs;
  }
  bool Align(const PairInput& pair, const EmbeddedPoints& source, const EmbeddedPoints& target,
             EmbeddedPoints* moved) const override {
    // DeformSource reads the first k_end eigenpairs of the basis it is given.
    const LaplaceBasis& basis = ShapeBasisWithAtLeast(pair.source, options_.k_end);
    DeformResult d = DeformSource(source, pair.source.surface.F, basis, pair.source.samples,
                                  target, pair.target.samples, options_);
    moved->Y = std::move(d.Y);
    moved->N = std::move(d.N);
    return true;
  }
  MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const override {
    return MatchNearest(source, target, options_.normal_weight, options_.threads);
  }

 private:
  DeformOptions options_;
};

}  // namespace

void RegisterMatchingStages(Registry& registry) {
  registry.Add("matching", "nearest", "nearest neighbour in the aligned embeddings (FLANN kd-tree); a pair with a partial shape "
               "(partial_boundary_ratio) by geodesic landmarks on the surfaces",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 const double normal_weight =
                     o.GetDouble("normal_weight", kDefaultNormalWeight, Range::AtLeast(0.0));
                 return WithPartialRoute(
                     o, std::make_unique<NearestStage>(
                            normal_weight, o.GetInt("threads", 1, Range::Closed(0, 256))));
               });
  registry.Add(
      "matching", "nearest_scaled",
      "ICP up to per-axis scale and translation, then nearest neighbour; a pair with a partial "
      "shape (partial_boundary_ratio) by geodesic landmarks on the surfaces",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        ScaledIcpOptions s;
        s.threads = 1;  // pairs run side by side
        ReadValidFields(o, &s);
        return WithPartialRoute(o, std::make_unique<NearestScaledStage>(s));
      });
  registry.Add(
      "matching", "deformed",
      "the source embedding bent onto the target's by a deformation smooth along the "
      "source surface (non-rigid ICP in its Laplace-Beltrami basis), then nearest neighbour; a "
      "pair with a partial shape (partial_boundary_ratio) by geodesic landmarks on the surfaces",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        DeformOptions d;
        ReadValidFields(o, &d);
        return WithPartialRoute(o, std::make_unique<DeformedStage>(d));
      });
}

}  // namespace symembed
