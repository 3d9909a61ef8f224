// The preprocess stage: StandardPreprocess with its options.
#include "stages/register.h"

#include <memory>

#include "stages/preprocess/standard.h"

namespace symembed {

namespace {

class StandardPreprocessStage : public PreprocessStage {
 public:
  explicit StandardPreprocessStage(const StandardPreprocessOptions& options) : options_(options) {}
  PreprocessResult Run(const Surface& input) const override {
    return StandardPreprocess(input, options_);
  }

 private:
  StandardPreprocessOptions options_;
};

}  // namespace

void RegisterPreprocessStages(Registry& registry) {
  registry.Add("preprocess", "standard",
               "weld boundary duplicates, drop degenerate/duplicate faces, keep the largest "
               "component (failing past max_removed_area), orient consistently "
               "(outward when closed), drop unreferenced vertices, centre and scale to unit area, "
               "cut the handles of a surface of genus > 0 (topological noise)",
               FieldsFactory<StandardPreprocessStage, StandardPreprocessOptions>());
}

}  // namespace symembed
