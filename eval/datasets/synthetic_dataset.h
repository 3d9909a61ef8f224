// Dataset loader `synthetic`: the synthetic ground-truth benchmark (eval/synthetic/synthetic.h)
// generated in-process into a cache folder on first use, then read with the pairs_vts loader.
//
// Options: kinds (list of humanoid, quadruped; default [humanoid]), poses (8), vertices (5000),
// seed (1), remesh (0), remesh_anisotropy (1), nonisometric (0), noise (0), partial (0), pairs (0)
// — the generator options of `symembed synth` — and cache (default results/.cache/synthetic/<hash
// of the generator options>, relative to the working directory), plus the restrictions classes,
// max_pairs, pairs_file. A cache folder holds exactly one option set: it is written to a
// temporary sibling and renamed into place, so concurrent users see it complete or not at all.
#pragma once

#include <memory>
#include <string>

#include "eval/datasets/pairs_vts.h"
#include "eval/synthetic/synthetic.h"
#include "registry/dataset.h"

namespace symembed {

class SyntheticDataset : public Dataset {
 public:
  SyntheticDataset(SynthOptions generator, std::string cache, DatasetRestrictions restrictions);
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

  const std::string& cache() const { return cache_; }
  // Generates into the cache folder unless it is there already.
  void EnsureGenerated() const;

 private:
  SynthOptions generator_;
  std::string cache_;
  PairsVtsDataset reader_;
};

// 16 hex digits identifying a generator option set (and the generator version).
std::string SynthOptionsHash(const SynthOptions& options);

std::unique_ptr<SyntheticDataset> CreateSyntheticDataset(OptionReader& options);

}  // namespace symembed
