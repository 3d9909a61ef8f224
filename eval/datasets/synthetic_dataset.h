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

#include "eval/datasets/generated_dataset.h"
#include "eval/synthetic/synthetic.h"
#include "registry/dataset.h"

namespace symembed {

class SyntheticDataset : public GeneratedDataset {
 public:
  SyntheticDataset(SynthOptions generator, std::string cache, DatasetRestrictions restrictions);

 private:
  void Write(const std::string& dir) const override;
  SynthOptions generator_;
};

// 16 hex digits identifying a generator option set (and the generator version).
std::string SynthOptionsHash(const SynthOptions& options);

std::unique_ptr<SyntheticDataset> CreateSyntheticDataset(OptionReader& options);

}  // namespace symembed
