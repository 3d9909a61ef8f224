#include "eval/datasets/synthetic_dataset.h"

#include <cstdio>
#include <filesystem>
#include <random>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// Bump when the generator's output changes for the same options, so stale caches are not used.
constexpr const char* kGeneratorVersion = "synthetic-generator-2";

}  // namespace

std::string SynthOptionsHash(const SynthOptions& options) {
  const std::string text = std::string(kGeneratorVersion) + "\n" + SynthOptionsText(options);
  uint64_t h = 1469598103934665603ULL;  // FNV-1a
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

SyntheticDataset::SyntheticDataset(SynthOptions generator, std::string cache,
                                   DatasetRestrictions restrictions)
    : generator_(std::move(generator)),
      cache_(std::move(cache)),
      reader_(PairsVtsOptions{cache_, std::move(restrictions)}) {}

void SyntheticDataset::EnsureGenerated() const {
  if (fs::exists(fs::path(cache_) / "README.md")) return;
  const fs::path target(cache_);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  std::random_device rd;
  const fs::path tmp = target.string() + ".tmp" + std::to_string(rd());
  WriteSyntheticDataset(tmp.string(), generator_);
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove_all(tmp);
    // Another process may have finished first; anything else is an error.
    if (!fs::exists(target / "README.md")) {
      throw IoError("cannot move the generated dataset to " + cache_ + ": " + ec.message());
    }
  }
}

DatasetIndex SyntheticDataset::Load() const {
  EnsureGenerated();
  return reader_.Load();
}

ShapeGroundTruth SyntheticDataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  EnsureGenerated();
  return reader_.GroundTruth(shape, num_vertices);
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
  std::string error;
  if (!g.IsValid(&error)) options.Fail("", error);
  std::string cache = options.GetString("cache", "");
  if (cache.empty()) cache = "results/.cache/synthetic/" + SynthOptionsHash(g);
  DatasetRestrictions restrictions = ReadRestrictions(options);
  return std::make_unique<SyntheticDataset>(g, cache, restrictions);
}

}  // namespace symembed
