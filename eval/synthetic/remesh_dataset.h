// A remeshed copy of a ground-truth dataset: every shape of a `pairs_vts` dataset (TOSCA, FAUST,
// SMAL in the layout of eval/datasets/pairs_vts.h) decimated independently, optionally
// anisotropically, with its ground truth carried over exactly. It tests how a pipeline's
// results depend on the meshing on real shapes, as the synthetic benchmark's `remesh` and
// `remesh_anisotropy` options do on generated ones.
//
// With `subdivide` L > 0 every shape is first Loop-subdivided L times (Subdivide in
// eval/synthetic/variations.h: each level about 4 times the vertices, the old vertices moved by a
// fraction of an edge and keeping their ids, the new ones without ground truth) and then
// decimated, so a dataset can be remeshed denser than it is distributed (12,000 vertices from
// 5,000: subdivide 1, vertices 12000).
//
// Each shape is decimated with Remesh (eval/synthetic/variations.h): halfedge collapses only, so
// every kept vertex keeps its position, and a ground-truth line whose vertex is kept names it in
// the new mesh; a line whose vertex was collapsed away is written as 0 ("the shape does not have
// it"), which the evaluator skips. Two shapes decimated to a fraction f of their vertices keep
// about f^2 of their common lines. Per shape (in the dataset's order) the collapse jitter and the
// anisotropy's direction come from their own seeded streams: the same input and options give
// byte-identical files.
#pragma once

#include <string>

#include "core/range.h"

namespace symembed {

struct RemeshDatasetOptions {
  // Target vertex count of every shape (larger shapes only; a smaller target is degenerate).
  int vertices = 2500;
  static constexpr Range kVertices = Range::AtLeast(50);
  // > 1: edges measured this many times longer along a random direction per shape (kept short
  // along it).
  double anisotropy = 1.0;
  static constexpr Range kAnisotropy = Range::Closed(1.0, 20.0);
  int subdivide = 0;  // Loop subdivision levels before the decimation
  static constexpr Range kSubdivide = Range::Closed(0, 2);
  int seed = 1;

  bool IsValid(std::string* error) const;
};

struct RemeshDatasetSummary {
  int shapes = 0;
  int pairs = 0;
  int remeshed = 0;  // shapes that had more vertices than the target
};

// Reads the pairs_vts dataset under input_root and writes the remeshed copy under output_dir
// (shapes/NAME.off, corres/NAME.vts and NAME.sym.vts where the input has it, test_pairs.txt with
// the input's pairs, README.md with the options and the source). A shape with no more vertices
// than the target (after the subdivision) is written as it is. Throws ConfigError for invalid
// options, InvalidInputError / IoError naming the file for a dataset or mesh that cannot be read
// or remeshed (a non-manifold mesh), IoError when the output cannot be written.
RemeshDatasetSummary WriteRemeshedDataset(const std::string& input_root,
                                          const std::string& output_dir,
                                          const RemeshDatasetOptions& options);

}  // namespace symembed
