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

// Ground truth of one shape, in one of two forms.
// As lines: line i of every shape of a class names the same point. ids are 0-based vertex ids
// of the input mesh; -1 marks a line the shape does not have.
// Onto one other shape (layouts that give each shape's correspondence to a reference shape,
// such as SHREC'16's partial and topology tracks onto their null shapes): vertex
// onto_lines.source_ids[r] of this shape corresponds to vertex onto_lines.target_ids[r] (and
// to onto_lines.target_sym_ids[r] under the left-right symmetry) of the shape named `onto`.
struct ShapeGroundTruth {
  std::vector<int> ids;
  std::vector<int> sym_ids;  // the left-right mirrored ground truth; empty when unknown
  std::string onto;          // empty: no ground truth onto another shape
  InputGroundTruth onto_lines;
};

// Pairs the lines of two shapes' ground truth (both present); the result is in input ids.
InputGroundTruth PairLines(const ShapeGroundTruth& source, const ShapeGroundTruth& target);

// The ground truth of the pair source -> target in input ids: the source's lines onto the
// target when it has them (`onto` == target_name); the target's onto the source, reversed
// (without the symmetric ground truth) when it has those; else PairLines.
InputGroundTruth PairGroundTruth(const ShapeGroundTruth& source, const std::string& source_name,
                                 const ShapeGroundTruth& target, const std::string& target_name);

class Dataset : public Stage {
 public:
  // Reads and validates the index; throws InvalidInputError or IoError naming the file and line.
  virtual DatasetIndex Load() const = 0;
  // Reads and validates one shape's ground truth (num_vertices: of its input mesh).
  virtual ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const = 0;
};

}  // namespace symembed
