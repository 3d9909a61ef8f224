// A dataset generated once into a cache folder in the pairs_vts layout and read from there: the
// base of the `synthetic` loader (generated figures) and of the `pairs_vts` loader's remeshing.
// The folder holds one generation, written to a temporary sibling and renamed into place
// (GenerateOnce, eval/synthetic/dataset_writer.h), so concurrent users see it complete or not at
// all; the restrictions apply to what was generated.
#pragma once

#include <string>

#include "eval/datasets/pairs_vts.h"
#include "registry/dataset.h"

namespace symembed {

class GeneratedDataset : public Dataset {
 public:
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

  const std::string& cache() const { return cache_; }
  // Generates into the cache folder unless it is there already.
  void EnsureGenerated() const;

 protected:
  GeneratedDataset(std::string cache, DatasetRestrictions restrictions);
  // Writes the whole dataset into the empty folder dir.
  virtual void Write(const std::string& dir) const = 0;

 private:
  std::string cache_;
  PairsVtsDataset reader_;
};

}  // namespace symembed
