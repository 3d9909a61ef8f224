// Dataset loader `kim2011`: the correspondence benchmark of [Kim, Lipman & Funkhouser 2011]
// "Blended intrinsic maps", as distributed (users download it themselves): its SCAPE, TOSCA and
// SHREC'07 Watertight sets with sparse landmarks, their left-right mirrors and the meshes to
// evaluate.
//
// Layout under `root` (file formats: eval/datasets/kim2011_files.h):
//   Data/<SET>/Meshes/NAME.off|obj|ply  the set's meshes. Files named *.hks.off (heat kernel
//                                       signatures) and anything else (camera*.txt) are not
//                                       meshes. NAME must be unique across the selected sets.
//   Data/<SET>/Corrs/CLASS.pid          landmarks of a class of meshes that share vertex ids:
//                                       line k = the vertex id (0-based) of landmark k on every
//                                       mesh of the class. The class of mesh NAME is NAME without
//                                       its trailing digits (TOSCA: cat10 -> cat.pid); when no
//                                       mesh name matches a class file and the set has exactly
//                                       one, it is the class of every mesh (SCAPE: 1.pid).
//   Data/<SET>/Corrs/NAME.vts           landmarks of mesh NAME alone (Watertight: 7.vts for
//                                       7.off); used instead of a class file when present. Line
//                                       k of the meshes of one class is the same landmark; the
//                                       class of a numbered mesh N is its block of 20
//                                       (1-20, 21-40, ...: the Watertight set's 20 classes of 20
//                                       meshes), of any other its name without trailing digits.
//   Data/<SET>/Corrs/CLASS.sym.info     optional (NAME.sym.info beside NAME.vts): the landmark
//                                       lines that mirror each other. Without it the class has
//                                       no mirrored ground truth.
//   Data/<SET>/Corrs/CLASS.info         the landmarks' names ("0: toe in right leg"); not read.
//   Results/Corr_*.query                the meshes to evaluate: groups of three lines, set name
//                                       (the Data/<SET> folder, any case), 1, mesh index. The
//                                       index counts the set's meshes from 0 in natural name
//                                       order (digit runs compare as numbers: SCAPE index 5 is
//                                       mesh005, Watertight index 0 is 1.off, TOSCA cat2 comes
//                                       before cat10).
// Pairs: every two queried meshes of one class (source: the one queried first), in query
// order; a set no query file names gives all unordered pairs within each of its classes.
// With `pairs_file` (relative to root: "A B" shape names per line) that file gives the pairs.
//
// Shapes: name NAME, class "<SET>/<CLASS>" (SCAPE/1, TOSCA/cat, Watertight/1-20). Ground truth
// line k is landmark line k (0-based input vertex ids); the mirrored line k is the vertex of
// landmark k's mirror, -1 for a landmark the mirror file does not list (the evaluation then
// leaves that line out).
//
// Options: root (required); classes (set names or <SET>/<CLASS> names), max_pairs, pairs_file.
// Load() reads the index and every landmark and mirror file a pair needs, and throws
// InvalidInputError or IoError naming the file and line for: a query group naming no set under
// Data/, an index with no mesh, a mesh queried twice, malformed landmark, mirror or query files,
// two meshes of a pair whose own landmark files differ in length, an unknown shape or a pair
// across classes in pairs_file, a `classes` entry naming no set. GroundTruth() throws, failing
// that shape and its pairs only, for a mesh without landmarks, a landmark id out of the mesh's
// range, and a mesh of a class file whose vertex count differs from the class's template (the
// count most of the class's meshes have).
#pragma once

#include <string>

#include "eval/datasets/dataset_files.h"
#include "registry/dataset.h"

namespace symembed {

struct Kim2011Options {
  std::string root;
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

// Reads `root` (required) and the restrictions.
Kim2011Options ReadKim2011Options(OptionReader& options);

}  // namespace symembed
