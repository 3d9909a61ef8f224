#include "eval/datasets/generated_dataset.h"

#include "eval/synthetic/dataset_writer.h"

namespace symembed {

GeneratedDataset::GeneratedDataset(std::string cache, DatasetRestrictions restrictions)
    : cache_(std::move(cache)), reader_(PairsVtsOptions{cache_, std::move(restrictions)}) {}

void GeneratedDataset::EnsureGenerated() const {
  GenerateOnce(cache_, [&](const std::string& dir) { Write(dir); });
}

DatasetIndex GeneratedDataset::Load() const {
  EnsureGenerated();
  return reader_.Load();
}

ShapeGroundTruth GeneratedDataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  EnsureGenerated();
  return reader_.GroundTruth(shape, num_vertices);
}

}  // namespace symembed
