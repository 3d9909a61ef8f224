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
  registry.Add("symmetrize", "ceres",
               "stress on a sample k-NN graph + symmetry_weight * ||M y_i - y_sigma(i)||^2, by "
               "stress majorization (then max_iterations of Ceres); dense vertices follow the "
               "samples",
               FieldsFactory<CeresStage, CeresSymmetrizeOptions>());
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
