// Dataset loader `same_connectivity`: classes of meshes that share vertex ids (SCAPE, the
// original TOSCA meshes, any set of poses of one template), so the ground truth is the
// identity on all vertices.
//
// Layout under `root`:
//   <CLASS>/NAME.off|obj|ply  the meshes of a class; all must have the same vertex count.
//                             Shape names (file stems) must be unique across classes.
//   <CLASS>/sym.txt           optional: the left-right mirror of every vertex, one 1-based
//                             vertex id per line (line v: the mirror of vertex v), #V lines
//   <CLASS>/pairs.txt         optional: "A<TAB>B" per line (names of that class); when absent,
//                             all unordered pairs within the class
// With `pairs_file` (relative to root), that one file lists the pairs of every class instead.
//
// Options: root (required), classes, max_pairs, pairs_file. Errors name the file and line:
// unknown shape in a pairs file, a mesh whose vertex count differs from its class's, a
// sym.txt of the wrong length or with an id out of range.
#pragma once

#include <string>

#include "eval/datasets/dataset_files.h"
#include "registry/dataset.h"

namespace symembed {

struct SameConnectivityOptions {
  std::string root;
  DatasetRestrictions restrictions;
};

class SameConnectivityDataset : public Dataset {
 public:
  explicit SameConnectivityDataset(SameConnectivityOptions options)
      : options_(std::move(options)) {}
  DatasetIndex Load() const override;
  // ids: 0 .. num_vertices-1; sym_ids from <CLASS>/sym.txt when present.
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  SameConnectivityOptions options_;
};

SameConnectivityOptions ReadSameConnectivityOptions(OptionReader& options);

}  // namespace symembed
