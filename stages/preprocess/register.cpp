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
               [](OptionReader& reader) -> std::unique_ptr<Stage> {
                 StandardPreprocessOptions options;
                 options.orient = reader.GetBool("orient", options.orient);
                 options.weld_boundary_duplicates = reader.GetBool(
                     "weld_boundary_duplicates", options.weld_boundary_duplicates);
                 options.keep_largest_component =
                     reader.GetBool("keep_largest_component", options.keep_largest_component);
                 options.max_removed_area =
                     reader.GetDouble("max_removed_area", options.max_removed_area,
                                      StandardPreprocessOptions::kMaxRemovedArea);
                 options.normalize = reader.GetBool("normalize", options.normalize);
                 options.degenerate_tolerance =
                     reader.GetDouble("degenerate_tolerance", options.degenerate_tolerance,
                                      StandardPreprocessOptions::kDegenerateTolerance);
                 options.cut_handles = reader.GetBool("cut_handles", options.cut_handles);
                 options.cap_cut_handles =
                     reader.GetBool("cap_cut_handles", options.cap_cut_handles);
                 return std::make_unique<StandardPreprocessStage>(options);
               });
}

}  // namespace symembed
