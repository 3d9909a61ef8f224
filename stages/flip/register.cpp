// The flip stages: thin adapters around the scorers (extrinsic, chamfer, oracle).
#include <memory>

#include "stages/flip/flip_common.h"
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
  registry.Add("flip", "chamfer", "symmetric Chamfer distance of the embeddings only",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 return std::make_unique<ChamferStage>(o.GetInt("threads", 1, 0, 256));
               });
  registry.Add("flip", "oracle",
               "lowest ground-truth error (evaluation only; fails without ground truth)",
               [](OptionReader& o) -> std::unique_ptr<Stage> {
                 return std::make_unique<OracleStage>(o.GetInt("threads", 1, 0, 256));
               });
}

}  // namespace symembed
