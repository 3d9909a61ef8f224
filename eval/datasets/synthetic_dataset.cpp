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
  g.poses = options.GetInt("poses", 8, SynthOptions::kPoses);
  if (g.poses < 2)
    options.Fail("poses",
                 "pairs are formed between poses: needs >= 2, got " + std::to_string(g.poses));
  g.vertices = options.GetInt("vertices", 5000, SynthOptions::kVertices);
  g.seed = options.GetInt("seed", 1, SynthOptions::kSeed);
  g.remesh = options.GetInt("remesh", 0, SynthOptions::kRemesh);
  g.remesh_anisotropy =
      options.GetDouble("remesh_anisotropy", 1.0, SynthOptions::kRemeshAnisotropy);
  g.nonisometric = options.GetDouble("nonisometric", 0.0, SynthOptions::kNonisometric);
  g.noise = options.GetDouble("noise", 0.0, SynthOptions::kNoise);
  g.partial = options.GetDouble("partial", 0.0, SynthOptions::kFraction);
  g.pairs = options.GetInt("pairs", 0, SynthOptions::kPairs);
  // The failure modes are read (and so resolved) only when given, so that the resolved config of
  // every dataset without them stays what it was.
  g.plane_cuts = options.GetDoubleIfGiven("plane_cuts", g.plane_cuts, SynthOptions::kFraction);
  g.holes = options.GetDoubleIfGiven("holes", g.holes, SynthOptions::kFraction);
  g.glue = options.GetDoubleIfGiven("glue", g.glue, SynthOptions::kFraction);
  g.glue_bridges =
      options.GetIntIfGiven("glue_bridges", g.glue_bridges, SynthOptions::kGlueBridges);
  g.cross_class = options.GetDoubleIfGiven("cross_class", g.cross_class, SynthOptions::kCrossClass);
  std::string error;
  if (!g.IsValid(&error)) options.Fail("", error);
  std::string cache = options.GetString("cache", "");
  if (cache.empty()) cache = "results/.cache/synthetic/" + SynthOptionsHash(g);
  DatasetRestrictions restrictions = ReadRestrictions(options);
  return std::make_unique<SyntheticDataset>(g, cache, restrictions);
}

}  // namespace symembed
