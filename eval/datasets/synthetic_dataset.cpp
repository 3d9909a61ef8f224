#include "eval/datasets/synthetic_dataset.h"

#include "core/errors.h"
#include "eval/synthetic/dataset_writer.h"

namespace symembed {

namespace {

// Bump when the generator's output changes for the same options, so stale caches are not used.
constexpr const char* kGeneratorVersion = "synthetic-generator-2";

}  // namespace

std::string SynthOptionsHash(const SynthOptions& options) {
  return HashHex(std::string(kGeneratorVersion) + "\n" + SynthOptionsText(options));
}

SyntheticDataset::SyntheticDataset(SynthOptions generator, std::string cache,
                                   DatasetRestrictions restrictions)
    : GeneratedDataset(std::move(cache), std::move(restrictions)),
      generator_(std::move(generator)) {}

void SyntheticDataset::Write(const std::string& dir) const {
  WriteSyntheticDataset(dir, generator_);
}

std::unique_ptr<SyntheticDataset> CreateSyntheticDataset(OptionReader& options) {
  SynthOptions g;
  g.kinds.clear();
  for (const std::string& name : options.GetStringList("kinds", {"humanoid"})) {
    if (name != "humanoid" && name != "quadruped") {
      options.Fail("kinds", "invalid kind '" + name + "'; expected one of: humanoid, quadruped");
    }
    g.kinds.push_back(FigureKindFromName(name));
  }
  ReadFields(options, &g);
  if (g.poses < 2)
    options.Fail("poses",
                 "pairs are formed between poses: needs >= 2, got " + std::to_string(g.poses));
  RequireValid(options, g);
  std::string cache = options.GetString("cache", "");
  if (cache.empty()) cache = "results/.cache/synthetic/" + SynthOptionsHash(g);
  DatasetRestrictions restrictions = ReadRestrictions(options);
  return std::make_unique<SyntheticDataset>(g, cache, restrictions);
}

}  // namespace symembed
