// The matching stages: thin adapters around MatchNearest / MatchNearestScaled.
#include <memory>

#include "stages/matching/nearest.h"
#include "stages/register.h"

namespace symembed {
namespace {

class NearestStage : public MatchingStage {
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

class NearestScaledStage : public MatchingStage {
 public:
  explicit NearestScaledStage(ScaledIcpOptions options) : options_(options) {}
  MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const override {
    return MatchNearestScaled(source, target, options_);
  }

 private:
  ScaledIcpOptions options_;
};

}  // namespace

void RegisterMatchingStages(Registry& registry) {
  registry.Add("matching", "nearest", "nearest neighbour in the aligned embeddings (FLANN kd-tree)",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 const double normal_weight =
                     o.GetDouble("normal_weight", kDefaultNormalWeight, 0.0);
                 return std::make_unique<NearestStage>(normal_weight,
                                                       o.GetInt("threads", 1, 0, 256));
               });
  registry.Add("matching", "nearest_scaled",
               "ICP up to per-axis scale and translation, then nearest neighbour",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 ScaledIcpOptions s;
                 s.iterations = o.GetInt("iterations", s.iterations, 0, 1000);
                 s.symmetric = o.GetBool("symmetric", s.symmetric);
                 s.min_scale = o.GetDouble("min_scale", s.min_scale, 1e-3, 1.0);
                 s.max_scale = o.GetDouble("max_scale", s.max_scale, 1.0, 1e3);
                 s.normal_weight = o.GetDouble("normal_weight", s.normal_weight, 0.0);
                 s.threads = o.GetInt("threads", 1, 0, 256);
                 std::string error;
                 if (!s.IsValid(&error)) o.Fail("", error);
                 return std::make_unique<NearestScaledStage>(s);
               });
}

}  // namespace symembed
