// The dataset interface (kind `dataset`): an index of shapes and pairs plus per-shape ground
// truth, read from one of the layouts researchers keep on disk (or generated).
#pragma once

#include <string>
#include <vector>

#include "registry/stages.h"

namespace symembed {

struct DatasetShape {
  std::string name;        // unique within the dataset
  std::string class_name;  // pairs are formed within a class
  std::string mesh_path;
};

struct DatasetPair {
  std::string source;
  std::string target;
};

struct DatasetIndex {
  std::vector<DatasetShape> shapes;
  std::vector<DatasetPair> pairs;
  const DatasetShape* Find(const std::string& name) const;
};

// Ground truth of one shape as lines: line i of every shape of a class names the same point.
// ids are 0-based vertex ids of the input mesh; -1 marks a line the shape does not have.
struct ShapeGroundTruth {
  std::vector<int> ids;
  std::vector<int> sym_ids;  // the left-right mirrored ground truth; empty when unknown
};

// Pairs the lines of two shapes' ground truth (both present); the result is in input ids.
InputGroundTruth PairLines(const ShapeGroundTruth& source, const ShapeGroundTruth& target);

class Dataset : public Stage {
 public:
  // Reads and validates the index; throws InvalidInputError or IoError naming the file and line.
  virtual DatasetIndex Load() const = 0;
  // Reads and validates one shape's ground truth (num_vertices: of its input mesh).
  virtual ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const = 0;
};

}  // namespace symembed
