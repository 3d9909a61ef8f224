// The symmetrize stages: thin adapters around SymmetrizeCeres / SymmetrizeAverage /
// SymmetrizeNone.
#include <memory>

#include "stages/register.h"
#include "stages/symmetrize/ceres_symmetrize.h"
#include "stages/symmetrize/simple_symmetrize.h"
#include "stages/symmetrize/symmetrize_common.h"

namespace symembed {
namespace {

class CeresStage : public SymmetrizeStage {
 public:
  explicit CeresStage(CeresSymmetrizeOptions options) : options_(options) {}
  SymmetrizeResult Run(const SymmetryInput& in, const SymmetryResult& sym) const override {
    CheckSymmetrizeInput(in, sym);
    return SymmetrizeCeres(in.embedding.Y, in.samples, sym, options_);
  }

 private:
  CeresSymmetrizeOptions options_;
};

class AverageStage : public SymmetrizeStage {
 public:
  explicit AverageStage(int follow_neighbors) : follow_neighbors_(follow_neighbors) {}
  SymmetrizeResult Run(const SymmetryInput& in, const SymmetryResult& sym) const override {
    CheckSymmetrizeInput(in, sym);
    return SymmetrizeAverage(in.embedding.Y, in.samples, sym, follow_neighbors_);
  }

 private:
  int follow_neighbors_;
};

class NoneStage : public SymmetrizeStage {
 public:
  SymmetrizeResult Run(const SymmetryInput& in, const SymmetryResult& sym) const override {
    CheckSymmetrizeInput(in, sym);
    return SymmetrizeNone(in.embedding.Y, in.samples, sym);
  }
};

}  // namespace

void RegisterSymmetrizeStages(Registry& registry) {
  registry.Add(
      "symmetrize", "ceres",
      "Ceres: stress on a sample k-NN graph + symmetry_weight * ||M y_i - y_sigma(i)||^2; "
      "dense vertices follow the samples",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        using C = CeresSymmetrizeOptions;
        CeresSymmetrizeOptions c;
        c.symmetry_weight = o.GetDouble("symmetry_weight", c.symmetry_weight, C::kWeight);
        c.plane_weight = o.GetDouble("plane_weight", c.plane_weight, C::kWeight);
        c.anchor_weight = o.GetDouble("anchor_weight", c.anchor_weight, C::kWeight);
        c.graph_neighbors = o.GetInt("graph_neighbors", c.graph_neighbors, C::kGraphNeighbors);
        c.mirror_neighbors = o.GetInt("mirror_neighbors", c.mirror_neighbors, C::kMirrorNeighbors);
        c.follow_neighbors = o.GetInt("follow_neighbors", c.follow_neighbors, C::kFollowNeighbors);
        c.max_iterations = o.GetInt("max_iterations", c.max_iterations, C::kMaxIterations);
        c.function_tolerance =
            o.GetDouble("function_tolerance", c.function_tolerance, C::kFunctionTolerance);
        c.threads = o.GetInt("threads", c.threads, C::kThreads);
        c.warm_start_iterations =
            o.GetInt("warm_start_iterations", c.warm_start_iterations, C::kWarmStartIterations);
        c.warm_start_tolerance =
            o.GetDouble("warm_start_tolerance", c.warm_start_tolerance, C::kWarmStartTolerance);
        std::string error;
        if (!c.IsValid(&error)) o.Fail("", error);
        return std::make_unique<CeresStage>(c);
      });
  registry.Add("symmetrize", "average",
               "closed form y_i <- (y_i + M y_sigma(i)) / 2 on the samples; dense vertices follow",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 return std::make_unique<AverageStage>(
                     o.GetInt("follow_neighbors", 8, Range::Closed(1, 1000)));
               });
  registry.Add("symmetrize", "none", "plane moved to x = 0, no deformation",
               [](OptionReader&) -> std::unique_ptr<Stage> {
                 return std::make_unique<NoneStage>();
               });
}

}  // namespace symembed
