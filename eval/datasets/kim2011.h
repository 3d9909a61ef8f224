// Dataset loader `kim2011`: the layout of the correspondence benchmark of [Kim, Lipman &
// Funkhouser 2011] "Blended intrinsic maps": sparse named landmarks per mesh, and the pairs of
// landmarks that are each other's left-right mirror.
//
// Accepted layout under `root` (each SET is a class; the benchmark's sets are SCAPE, TOSCA,
// SHREC, ...):
//   Data/<SET>/Meshes/NAME.off        meshes; NAME must be unique across the selected sets
//   Data/<SET>/Landmarks/NAME.vts     one landmark per line: "<vertex id> <landmark name>",
//                                     ids 0-based (option id_base: 1 for 1-based); a mesh may
//                                     lack some of its set's landmarks; blank lines and lines
//                                     starting with '#' are skipped
//   Data/<SET>/symmetric_landmarks.txt optional: "<left name> <right name>" per line; the
//                                     landmarks not listed are their own mirror images
//   Data/<SET>/pairs.txt              optional: "A B" per line; else all pairs within the set
// Ground-truth line i of every mesh of a set is the i-th landmark name of the set (sorted union
// over its landmark files): its vertex id, or -1 where the mesh lacks it; the mirrored line is
// the vertex of the mirror landmark (-1 when missing). Without symmetric_landmarks.txt there is
// no mirrored ground truth.
//
// Options: root (required), classes (sets), max_pairs, pairs_file, id_base (0 or 1).
// Errors name the file and line: a mesh without a landmark file or a landmark file without a
// mesh, a landmark named twice in one file, a mirror pair naming an unknown landmark or one
// landmark twice, an id out of range, a pair naming an unknown shape.
#pragma once

#include <string>

#include "eval/datasets/dataset_files.h"
#include "registry/dataset.h"

namespace symembed {

struct Kim2011Options {
  std::string root;
  int id_base = 0;
  DatasetRestrictions restrictions;
};

class Kim2011Dataset : public Dataset {
 public:
  explicit Kim2011Dataset(Kim2011Options options) : options_(std::move(options)) {}
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  Kim2011Options options_;
};

Kim2011Options ReadKim2011Options(OptionReader& options);

}  // namespace symembed
