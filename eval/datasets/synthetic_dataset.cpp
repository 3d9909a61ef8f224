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
  g.poses = options.GetInt("poses", 8, 2, 10000);  // pairs are formed between poses
  g.vertices = options.GetInt("vertices", 5000, 100, 10000000);
  g.seed = options.GetInt("seed", 1, 0);
  g.remesh = options.GetInt("remesh", 0, 0);
  g.remesh_anisotropy = options.GetDouble("remesh_anisotropy", 1.0, 1.0, 20.0);
  g.nonisometric = options.GetDouble("nonisometric", 0.0, 0.0, 0.49);
  g.noise = options.GetDouble("noise", 0.0, 0.0, 1.0);
  g.partial = options.GetDouble("partial", 0.0, 0.0, 1.0);
  g.pairs = options.GetInt("pairs", 0, 0);
  // The failure modes are read (and so resolved) only when given, so that the resolved config of
  // every dataset without them stays what it was.
  g.plane_cuts = options.GetDoubleIfGiven("plane_cuts", g.plane_cuts, 0.0, 1.0);
  g.holes = options.GetDoubleIfGiven("holes", g.holes, 0.0, 1.0);
  g.glue = options.GetDoubleIfGiven("glue", g.glue, 0.0, 1.0);
  g.glue_bridges = options.GetIntIfGiven("glue_bridges", g.glue_bridges, 0, 1000);
  g.cross_class = options.GetDoubleIfGiven("cross_class", g.cross_class, 0.0, 0.49);
  std::string error;
  if (!g.IsValid(&error)) options.Fail("", error);
  std::string cache = options.GetString("cache", "");
  if (cache.empty()) cache = "results/.cache/synthetic/" + SynthOptionsHash(g);
  DatasetRestrictions restrictions = ReadRestrictions(options);
  return std::make_unique<SyntheticDataset>(g, cache, restrictions);
}

}  // namespace symembed
