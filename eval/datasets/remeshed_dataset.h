// The `pairs_vts` loader's remeshing: with `remesh: N` (> 0) the dataset under `root` is read
// through a remeshed copy (eval/synthetic/remesh_dataset.h: every shape decimated independently
// to N vertices, anisotropically with `remesh_anisotropy` A > 1 along a random direction per
// shape, seeded by `remesh_seed`, after `remesh_subdivide` levels of Loop subdivision; the
// ground truth carried over exactly) written on first use
// into a cache folder, `cache` (default results/.cache/remeshed/<hash>, relative to the working
// directory). The hash covers the options, the root's absolute path and the name, size and
// modification time of every file of its shapes/ and corres/ and of test_pairs.txt, so an edited
// dataset is remeshed again. A cache folder holds one remeshing, written to a temporary sibling
// and renamed into place. The restrictions (classes, max_pairs, pairs_file relative to `root`)
// apply as without remeshing. Errors: those of the pairs_vts loader and of the remeshing, naming
// the input file.
#pragma once

#include <memory>
#include <string>

#include "eval/datasets/generated_dataset.h"
#include "eval/synthetic/remesh_dataset.h"
#include "registry/dataset.h"

namespace symembed {

class RemeshedDataset : public GeneratedDataset {
 public:
  RemeshedDataset(std::string root, RemeshDatasetOptions remesh, std::string cache,
                  DatasetRestrictions restrictions);

 private:
  void Write(const std::string& dir) const override;
  std::string root_;
  RemeshDatasetOptions remesh_;
};

// The cache folder's name for a remeshing of the dataset under root: 16 hex digits.
std::string RemeshedDatasetHash(const std::string& root, const RemeshDatasetOptions& remesh);

// The `pairs_vts` loader: a PairsVtsDataset, or a RemeshedDataset when `remesh` > 0.
std::unique_ptr<Dataset> CreatePairsVtsDataset(OptionReader& options);

}  // namespace symembed
