// Dataset loaders for two SHREC'16 tracks in the layouts they are distributed in:
//
// `shrec16_partial`: SHREC'16 Partial Matching of Deformable Shapes [Cosmo, Rodolà, Bronstein,
// Torsello, Cremers & Sahillioğlu 2016]. Layout under `root`:
//   null/CLASS.off                     the class's full shape (the "null" shape)
//   TRACK/TRACK_CLASS_shape_N.off      a partial shape (TRACK: cuts or holes)
//   TRACK/TRACK_CLASS_shape_N.baryc_gt one row per partial-shape vertex, "T W1 W2 W3": a 1-based
//                                      triangle index of null/CLASS.off and the barycentric
//                                      weights of the corresponding point in it
//   TRACK/..._shape_N.baryc_gt_sym     optional: the same against the left-right mirror
// Shapes: every partial shape (named by its file stem) and the null shape of each class that
// has one (named CLASS); pairs: each partial shape onto its class's null shape. The error of a
// partial vertex is measured on the null shape at the vertex of its ground-truth triangle with
// the largest barycentric weight (the benchmark's point, to within half an edge of the null
// mesh). Options: root (required), track (cuts | holes | auto, the default: the one of the two
// folders that exists), classes, max_pairs, pairs_file.
//
// `topkids`: SHREC'16 Matching of Deformable Shapes with Topological Noise [Lähner, Rodolà,
// Bronstein, Cremers et al. 2016]. Layout under `root`:
//   kidNN.off|obj|ply     the shapes; `null_shape` (default kid00) is the null shape
//   kidNN_ref.txt         ground truth of kidNN: rows "KID NULL", a 1-based vertex of kidNN and
//                         the 1-based vertex of the null shape it corresponds to
// Pairs: each other shape with a _ref.txt onto the null shape. Options: root (required),
// null_shape, classes, max_pairs, pairs_file.
//
// A shape named in many pairs (the null shapes) is one shape of the index, computed once.
// Load() checks the layout and that every partial shape's class has a null shape; GroundTruth()
// checks row counts, field counts, finite non-negative weights and every index against the
// meshes. Errors: InvalidInputError naming the file and line, IoError when a file cannot be read.
#pragma once

#include <Eigen/Core>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "eval/datasets/dataset_files.h"
#include "registry/dataset.h"

namespace symembed {

struct Shrec16PartialOptions {
  std::string root;
  std::string track = "auto";  // "cuts", "holes", or "auto": the one of the two folders that exists
  DatasetRestrictions restrictions;
};

class Shrec16PartialDataset : public Dataset {
 public:
  explicit Shrec16PartialDataset(Shrec16PartialOptions options) : options_(std::move(options)) {}
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  // The track folder in use ("auto" resolved).
  std::string Track() const;
  // The faces of a class's null shape, read once (every partial shape of the class needs them).
  std::shared_ptr<const Eigen::MatrixX3i> NullFaces(const std::string& class_name) const;
  Shrec16PartialOptions options_;
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const Eigen::MatrixX3i>> null_faces_;
};

Shrec16PartialOptions ReadShrec16PartialOptions(OptionReader& options);

// The class of a partial shape's file stem "TRACK_CLASS_shape_N"; empty when the stem does not
// have that form.
std::string Shrec16PartialClass(const std::string& stem, const std::string& track);

// Reads a .baryc_gt file: per row, the 0-based vertex of the null shape (faces: its #F x 3
// triangles) with the largest barycentric weight. rows: the partial shape's vertex count.
std::vector<int> ReadBarycentricTruth(const std::string& path, const Eigen::MatrixX3i& faces,
                                      int rows);

struct TopKidsOptions {
  std::string root;
  std::string null_shape = "kid00";
  DatasetRestrictions restrictions;
};

class TopKidsDataset : public Dataset {
 public:
  explicit TopKidsDataset(TopKidsOptions options) : options_(std::move(options)) {}
  DatasetIndex Load() const override;
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override;

 private:
  TopKidsOptions options_;
};

TopKidsOptions ReadTopKidsOptions(OptionReader& options);

}  // namespace symembed
