// Orientation term of the flip scorers: which candidate rotation leads to an orientation-
// preserving correspondence once the map is refined intrinsically.
//
// On a shape whose symmetrized embedding is thin and nearly symmetric front-to-back (a human),
// the rotation by pi about the vertical axis maps the embedding almost onto itself mirrored
// left-right, so that candidate's map lies close to the left-right mirrored correspondence and
// every descriptor invariant under the symmetry (curvature, HKS) scores it like the right one.
// The two differ in orientation: the correct correspondence preserves the orientation of the
// (consistently oriented) surfaces, the mirrored one reverses it. The nearest-neighbour map of a
// proper rotation preserves orientation in either case, so each candidate's map is first
// refined with a few ZoomOut iterations [Melzi et al. 2019], which pull it onto the nearest
// near-isometry (the correct map or the mirrored one), and the orientation of the refined map is
// measured on the source samples: for each sample i and pairs (j, k) of its nearest samples, the
// sign of ((p_j - p_i) x (p_k - p_i)) . n_i on the source against the same triple product of the
// image points and the image normal on the target, in the surfaces' own coordinates.
// [Ren et al. 2018] Continuous and orientation-preserving correspondences via functional maps
// (the orientation-preserving idea, here as a measurement rather than a term of the map).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/fmap/zoomout.h"
#include "core/mesh.h"
#include "core/spectral.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/zoomout_schedule.h"

namespace symembed {

struct OrientationOptions {
  // ZoomOut basis sizes (both bases need k_end eigenpairs), the source samples the refinement
  // and the measurement use, and the target samples the refined maps land on (0: every target
  // vertex). Matching only onto a prefix of the target's farthest-point samples makes each
  // ZoomOut step a few times cheaper; the sizes and counts are those that chose the oracle's
  // candidate most often on the studies' base pipelines (docs/analysis.md, "Measurements
  // behind the defaults").
  FlipZoomOutSchedule zoomout{/*k_start=*/6, /*k_end=*/60, /*step=*/5, /*samples=*/200,
                              /*target_samples=*/1000};
  int neighbors = 6;  // nearest samples whose pairs form the triangles of a sample

  bool IsValid(std::string* error) const;
};

// The source side of the measurement, independent of the map: triangles (apex sample i and two
// of its nearest samples j, k) that are spread and near tangent to the surface at i.
struct SourceTriangles {
  std::vector<std::array<int, 3>> vertices;  // source vertex ids (i, j, k)
  std::vector<double> sign;                  // sign of their orientation against the normal at i
};

// The triangles of `samples` (source vertex ids), each with two of its `neighbors` nearest
// samples in the source's own coordinates.
SourceTriangles MakeSourceTriangles(const Surface& source, const std::vector<int>& samples,
                                    int neighbors);

// Mean of source sign * sign of the image triangle's triple product with the target normal at
// the apex's image, over the triangles whose image is spread and near tangent (0 when none is).
// map: target vertex per source vertex (at least at the triangles' vertices); target_normals:
// VertexNormals(target).
double TriangleOrientation(const SourceTriangles& triangles, const Surface& target,
                           const Eigen::MatrixX3d& target_normals, const std::vector<int>& map);

// Mean over source samples and their neighbour pairs of sign(source triple product) *
// sign(image triple product), in [-1, 1]: near 1 for an orientation-preserving map, near -1 for
// a reversing one. map: #Vs target vertex per source vertex; samples: source vertex ids.
double MapOrientation(const Surface& source, const Surface& target, const std::vector<int>& map,
                      const std::vector<int>& samples, int neighbors);

// The orientation of a candidate's nearest-neighbour map (from ComputeCandidateMaps of the
// canonical embeddings) after ZoomOut in the given bases. Built once per pair: it holds what does
// not depend on the candidate (sample prefixes, ZoomOut's setup, source triangles, target
// normals). samples: source vertex ids (the first options.zoomout.samples are used);
// target_samples: target vertex ids (the first options.zoomout.target_samples are used; all
// target vertices when that is 0). The surfaces and bases are referenced, not copied: they must outlive it. Throws
// ConfigError for invalid options, InvalidInputError for too few samples.
class CandidateOrientation {
 public:
  CandidateOrientation(const Surface& source, const Surface& target,
                       const LaplaceBasis& source_basis, const LaplaceBasis& target_basis,
                       const std::vector<int>& samples, const std::vector<int>& target_samples,
                       const OrientationOptions& options);

  // The orientation of one candidate's map (#Vs target vertex per source vertex).
  double operator()(const std::vector<int>& map) const;

 private:
  const Surface& source_;
  const Surface& target_;
  std::vector<int> samples_;
  std::optional<ZoomOutSetup> zoomout_;  // set in the constructor, after the sample prefixes
  SourceTriangles triangles_;
  Eigen::MatrixX3d target_normals_;
};

// The orientation of each of the four candidates' maps.
std::array<double, 4> CandidateOrientations(const CandidateOrientation& measure,
                                            const CandidateMaps& maps);

// The orientation term added to per-candidate scores (lower is better):
// total_k = scores[k] + weight * (1 - o_k) / 2, o_k = measure(maps.map[k]). Since
// total_k >= scores[k], o_k is only measured for candidates that can still have the lowest
// total: they are visited by increasing scores[k], and one whose score exceeds the lowest total
// so far is skipped (orientation NaN, total left at its lower bound scores[k]). The candidate
// with the lowest total is the one that measuring all four would give.
struct OrientationScores {
  std::array<double, 4> total{};
  std::array<double, 4> orientation{};  // NaN for skipped candidates
  int measured = 0;                     // candidates whose ZoomOut ran
};
OrientationScores AddOrientationTerm(const std::array<double, 4>& scores, double weight,
                                     const CandidateMaps& maps,
                                     const CandidateOrientation& measure);

}  // namespace symembed
