// The flip stages: the extrinsic stage (extrinsic_stage.h) and thin adapters around the other
// scorers (chamfer, hks, oracle).
#include <memory>

#include "stages/flip/extrinsic_stage.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/hks.h"
#include "stages/flip/oracle.h"
#include "stages/register.h"

namespace symembed {
namespace {

class ChamferStage : public FlipStage {
 public:
  explicit ChamferStage(int threads) : threads_(threads) {}
  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    return MakeFlipResult(ChamferScores(pair.source.Y, pair.target.Y, threads_), "chamfer");
  }

 private:
  int threads_;
};

class HksStage : public FlipStage {
 public:
  explicit HksStage(HksFlipOptions options) : options_(options) {}
  ShapeNeeds Needs() const override {
    ShapeNeeds needs;
    needs.basis = options_.eigenpairs;
    return needs;
  }
  FlipResult Run(const PairInput& pair) const override {
    CheckFlipPair(pair);
    LaplaceBasis source, target;
    ShapeBasis(pair.source, options_.eigenpairs, &source);
    ShapeBasis(pair.target, options_.eigenpairs, &target);
    return MakeFlipResult(
        HksFlipScores(pair.source.Y, pair.target.Y, source, target, options_), "hks");
  }

 private:
  HksFlipOptions options_;
};

class OracleStage : public FlipStage {
 public:
  explicit OracleStage(int threads) : threads_(threads) {}
  FlipResult Run(const PairInput& pair) const override {
    return MakeFlipResult(OracleFlipScores(pair, threads_), "oracle");
  }

 private:
  int threads_;
};

}  // namespace

void RegisterFlipStages(Registry& registry) {
  registry.Add("flip", "extrinsic",
               "a sum of terms per candidate, then a decision: curvature features of the "
               "original surfaces compared locally through each candidate's NN map and "
               "globally (the paper's), the agreement with a wave-kernel-signature functional "
               "map, and the orientation of each candidate's map after a short ZoomOut; the "
               "best candidate's front-back partner replaces it when their maps, after ZoomOut "
               "from k = 20, say so clearly (decide: refined_front_back) or not (argmin)",
               ReadExtrinsicStage);
  registry.Add(
      "flip", "chamfer", "symmetric Chamfer distance of the embeddings only",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        return std::make_unique<ChamferStage>(o.GetInt("threads", 1, Range::Closed(0, 256)));
      });
  registry.Add("flip", "hks",
               "heat kernel signatures (Laplace-Beltrami eigenpairs) compared through each "
               "candidate's NN map",
               FieldsFactory<HksStage, HksFlipOptions>());
  registry.Add(
      "flip", "oracle", "lowest ground-truth error (evaluation only; fails without ground truth)",
      [](OptionReader& o) -> std::unique_ptr<Stage> {
        return std::make_unique<OracleStage>(o.GetInt("threads", 1, Range::Closed(0, 256)));
      });
}

}  // namespace symembed
