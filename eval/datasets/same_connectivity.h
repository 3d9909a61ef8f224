// Dataset loader `same_connectivity`: classes of meshes that share vertex ids (SCAPE, the
// original TOSCA meshes, any set of poses of one template), so the ground truth is the
// identity on all vertices.
//
// Layout under `root`:
//   <CLASS>/NAME.off|obj|ply  the meshes of a class, sharing the vertex ids of the class's
//                             template (the vertex count most of them have). Shape names (file
//                             stems) must be unique across classes.
//   <CLASS>/sym.txt           optional: the left-right mirror of every vertex, one 1-based
//                             vertex id per line (line v: the mirror of vertex v), #V lines
//   <CLASS>/pairs.txt         optional: "A<TAB>B" per line (names of that class); when absent,
//                             all unordered pairs within the class
// With `pairs_file` (relative to root), that one file lists the pairs of every class instead.
//
// Options: root (required), classes, max_pairs, pairs_file. Errors name the file and line:
// Load() throws for an unknown shape in a pairs file and a sym.txt whose length is not the
// template's vertex count or with an id out of range. A mesh whose vertex count differs from
// its class's template does not stop Load(): GroundTruth() throws for it (naming the mesh, its
// count and the template's), so the run fails that shape and its pairs only.
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
  // ids: 0 .. num_vertices-1; sym_ids from <CLASS>/sym.txt when present. Throws
  // InvalidInputError when num_vertices is not the class template's vertex count.
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  SameConnectivityOptions options_;
};

SameConnectivityOptions ReadSameConnectivityOptions(OptionReader& options);

}  // namespace symembed
