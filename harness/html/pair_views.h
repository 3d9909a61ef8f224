// The 3D data of the HTML report's pair view: one side file per shape (mesh and ground truth,
// shared by every pair and variant) and one per distinct map (a pair's map and its per-point
// errors), in the encoding of harness/html/side_files.h. Meshes are read from the dataset files
// the run used, in their input vertex ids (the ids of the map files and the ground truth).
#pragma once

#include <string>
#include <vector>

#include "eval/pair_names.h"
#include "registry/dataset.h"

namespace symembed {

struct ShapeView {
  std::string key;  // the page's id of this mesh: the name, or the name and a digest of its path
  std::string name;
  std::string class_name;
  int vertices = 0;
  std::vector<int> faces;  // #F x 3 vertex ids, row-major (the map's coding needs them)
  ShapeGroundTruth truth;  // input ids; empty when the dataset has none for this shape
  std::string error;       // why the shape cannot be shown; empty when it can
  std::string script;      // its side file text: symembedData("shape", key, payload)
};

// Reads the shape's mesh file and ground truth. payload: name, class, vertices, positions
// (EncodePositions), faces (#F x 3 vertex ids, row-major, EncodeIds), and when the dataset has
// ground truth, gt and gt_sym (EncodeIds: the vertex of each ground-truth line, -1 where the
// shape lacks it; gt_sym absent without a symmetric ground truth). Never throws: a mesh that
// cannot be read sets `error` (naming the file); missing ground truth only leaves it out.
// key: the page's id of the mesh (ShapeViewKey); empty: the shape's name.
ShapeView BuildShapeView(const Dataset& dataset, const DatasetShape& shape,
                         const std::string& key = "");

// Where a variant's maps are: a run's maps/STEM.map (base 1) with pairs/STEM.rec records, or the
// maps folder of `symembed eval` (its base; reverse: the file named for A -> B maps B to A),
// without records. names: the stems of the pairs the files were named for (in the files'
// orientation: the pairs of the folder's pairs.csv, reversed with `reverse`); Stem, MapPath
// and RecordPath throw InternalError for a pair not among them.
struct MapSource {
  std::string maps_dir;
  int base = 1;
  bool reverse = false;
  std::string records_dir;  // empty: no per-pair records, hence no per-point errors
  PairNames names;
  // The file stem of the pair source -> target, and its files.
  std::string Stem(const std::string& source, const std::string& target) const;
  std::string MapPath(const std::string& source, const std::string& target) const;
  std::string RecordPath(const std::string& source, const std::string& target) const;
};

struct PairView {
  std::string key;     // side file stem: "A_B-" + 8 hex digits of the payload's hash
  std::string script;  // symembedData("pair", key, payload); empty when error is set
  std::string error;   // why the pair cannot be shown (names the file); empty when it can
};

// payload: map (EncodeVertexMap: the target vertex of each source vertex), and
// either errors (EncodeUnitValues(errors_direct of the pair's record, max_error): one per line
// of PairLines(source.truth, target.truth), in that order) or errors_note (why there are none:
// no record, no ground truth, evaluation.points = N). A map file of the wrong length, with a
// bad id, or missing sets `error`. Never throws.
PairView BuildPairView(const ShapeView& source, const ShapeView& target, const MapSource& maps,
                       double max_error);

}  // namespace symembed
