// The sampling stages: geodesic farthest points, or every vertex.
#include "stages/register.h"

#include <cstdint>
#include <memory>

#include "stages/sampling/farthest_point.h"

namespace symembed {

namespace {

class FarthestPointStage : public SamplingStage {
 public:
  explicit FarthestPointStage(const FarthestPointOptions& options) : options_(options) {}
  SamplingResult Run(const Surface& surface) const override {
    return FarthestPointSampling(surface, options_);
  }

 private:
  FarthestPointOptions options_;
};

class AllSamplingStage : public SamplingStage {
 public:
  SamplingResult Run(const Surface& surface) const override { return AllVerticesSampling(surface); }
};

}  // namespace

void RegisterSamplingStages(Registry& registry) {
  registry.Add(
      "sampling", "all", "every vertex is a sample",
      [](OptionReader&) -> std::unique_ptr<Stage> { return std::make_unique<AllSamplingStage>(); });
  registry.Add("sampling", "farthest_point",
               "geodesic farthest point sampling from a seeded start (options: count, seed)",
               FieldsFactory<FarthestPointStage, FarthestPointOptions>());
}

}  // namespace symembed
