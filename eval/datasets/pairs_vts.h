// Dataset loader `pairs_vts`: the layout of the TOSCA / FAUST remeshed benchmarks of Ren et al.
// 2018 ("Continuous and orientation-preserving correspondences via functional maps") and of
// the synthetic benchmark (eval/synthetic/synthetic.h).
//
// Layout under `root`:
//   shapes/NAME.off|obj|ply   one mesh per shape; the class of NAME is NAME without its
//                             trailing digits (cat10 -> cat)
//   corres/NAME.vts           ground truth: one 1-based vertex id per line; line i of A.vts
//                             and line i of B.vts are the same point. Not a bijection in
//                             general (several lines may name one vertex). 0 = the shape does
//                             not have line i (synthetic remeshed / partial shapes) -> id -1.
//   corres/NAME.sym.vts       optional: the left-right mirrored ground truth, same form
//   test_pairs.txt            "A<TAB>B" per line, blank lines ignored (TOSCA ends with one);
//                             when absent (and no pairs_file is given): all unordered pairs
//                             within each class
// Other files in corres/ (CLASS_sampleID.vts) are ignored.
//
// Options: root (required), classes, max_pairs, pairs_file (DatasetRestrictions); remesh,
// remesh_anisotropy, remesh_seed and cache read the dataset through an independent remeshing of
// every shape (eval/datasets/remeshed_dataset.h).
// Load() checks that every pair names two shapes with meshes and ground truth, and that the
// .vts (and .sym.vts) files of the two shapes of a pair have the same number of lines;
// GroundTruth() checks every id against the mesh's vertex count. Errors: InvalidInputError or
// IoError naming the file and line.
#pragma once

#include <string>

#include "eval/datasets/dataset_files.h"
#include "registry/dataset.h"

namespace symembed {

struct PairsVtsOptions {
  std::string root;
  DatasetRestrictions restrictions;
};

class PairsVtsDataset : public Dataset {
 public:
  explicit PairsVtsDataset(PairsVtsOptions options) : options_(std::move(options)) {}
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  PairsVtsOptions options_;
};

// Reads `root` (required) and the restrictions.
PairsVtsOptions ReadPairsVtsOptions(OptionReader& options);

}  // namespace symembed
