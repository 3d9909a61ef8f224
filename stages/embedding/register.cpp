// Registered adapters of the embedding stages; the algorithms are in lsmds.h and isomap.h.
#include "stages/register.h"

#include <memory>

#include "core/errors.h"
#include "stages/embedding/isomap.h"
#include "stages/embedding/lsmds.h"

namespace symembed {
namespace {

class LsmdsStage : public EmbeddingStage {
 public:
  explicit LsmdsStage(LsmdsOptions options) : options_(std::move(options)) {}
  EmbeddingResult Run(const EmbeddingInput& input) const override {
    return LsmdsEmbedding(input, options_);
  }

 private:
  LsmdsOptions options_;
};

class IsomapStage : public EmbeddingStage {
 public:
  explicit IsomapStage(IsomapOptions options) : options_(std::move(options)) {}
  EmbeddingResult Run(const EmbeddingInput& input) const override {
    return IsomapEmbedding(input, options_);
  }

 private:
  IsomapOptions options_;
};

// The embedding functions take any dimension, but the stages after the embedding (symmetry
// plane, symmetrization, canonical frame, flip, matching) work in 3D: another value could only
// fail later, on every shape.
int ReadDims(OptionReader& reader, int default_dims) {
  const int dims = reader.GetInt("dims", default_dims, Range::Closed(1, 100));
  if (dims != 3) {
    reader.Fail("dims", "the pipeline's symmetry, frame and matching stages need a 3D "
                        "embedding; only 3 is supported, got " + std::to_string(dims));
  }
  return dims;
}

std::unique_ptr<Stage> MakeLsmds(OptionReader& reader) {
  LsmdsOptions o;
  o.dims = ReadDims(reader, o.dims);
  o.init = reader.GetEnum<LsmdsInit>("init", o.init,
                                     {{"original", LsmdsInit::kOriginal},
                                      {"isomap", LsmdsInit::kIsomap},
                                      {"random", LsmdsInit::kRandom}});
  ReadValidFields(reader, &o);
  return std::make_unique<LsmdsStage>(o);
}

std::unique_ptr<Stage> MakeIsomap(OptionReader& reader) {
  IsomapOptions o;
  o.dims = ReadDims(reader, o.dims);
  o.fix_orientation = reader.GetBool("fix_orientation", o.fix_orientation);
  RequireValid(reader, o);
  return std::make_unique<IsomapStage>(o);
}

}  // namespace

void RegisterEmbeddingStages(Registry& registry) {
  registry.Add("embedding", "lsmds",
               "least-squares MDS (SMACOF) of the sample geodesics from the input coordinates, "
               "out-of-sample placement of every vertex; keeps the surface's orientation",
               MakeLsmds);
  registry.Add("embedding", "isomap",
               "classical MDS of the sample geodesics + landmark MDS of every vertex; "
               "eigenvector signs arbitrary, so it may reflect",
               MakeIsomap);
}

}  // namespace symembed
