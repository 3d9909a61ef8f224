// ZoomOut between a part of a surface and the whole: rectangular functional maps whose two
// basis sizes grow together, matched by eigenvalue.
//
// A part (a cut, a scan of one side) has fewer Laplace-Beltrami eigenfunctions below a given
// frequency than the whole it is cut from: by Weyl's law their counts below an eigenvalue scale
// with area, so the functional map between the part's first k_p and the whole's first k_w
// eigenfunctions is a slanted band, and ZoomOut with equal sizes pulls the part's map over the
// whole [Rodolà et al. 2017, Partial functional correspondence]. Here each iteration takes the
// whole's basis size k_w from the ZoomOut schedule (k_start, k_start + step, ..., k_end) and
// the part's as the number of its eigenvalues not above the whole's k_w-th, both in one unit of
// length, so a part of half the whole's area gets about half the functions. Then, as in ZoomOut
// [Melzi et al. 2019, Sec. 5, which notes rectangular maps for partial shapes], the least-
// squares map C (k_s x k_t) of the point map and the point map of C alternate.
//
// The source is the part: every source vertex takes part in the fit, and a whole's vertices
// that the part lacks have no true image. When the source's area (mass sum, common unit)
// exceeds the target's, the initial map is returned unchanged and the message says so. Units: each
// basis's eigenvalues are in its own units of 1/length^2; `source_unit`, `target_unit` convert each
// shape's lengths to the common unit (the input units, 1 / ShapeData::scale). The iterations run on
// the samples (source vertex ids; empty: every vertex), mapping onto target_samples (empty: every
// target vertex), and the last query maps every source vertex onto every target vertex. Single
// start (options.extra_k_starts and dense_result are not read). With an anchor (PartialAnchor),
// each query also pays for straying from its initial image. Deterministic.
//
// Throws ConfigError for invalid options, InvalidInputError when a basis has fewer than k_end
// eigenpairs, a unit is not positive, an id is out of range, or an anchor with weight lacks one
// point per target vertex.
#pragma once

#include <vector>

#include "core/fmap/zoomout.h"
#include "core/spectral.h"

namespace symembed {

// The part's basis size for the whole's k_w, given both shapes' eigenvalues in the common unit:
// the number of the part's eigenvalues not above the whole's k_w-th, at least
// min(kMinPartSize, k_w) and at most k_w. Throws InvalidInputError when either has fewer than
// k_w eigenvalues.
constexpr int kMinPartSize = 4;
int PartBasisSize(const Eigen::VectorXd& whole_evals, const Eigen::VectorXd& part_evals, int k_w);

// An anchor to the initial map: each query also pays `weight` times the squared distance
// between its candidate's point and its initial image's (`target_points`, #Vt x 3, in any one
// unit), so a region moves where the spectral terms agree but is not carried off wholesale (as
// onto a mirror image, which a part's low frequencies cannot tell apart). Weight 0: none.
struct PartialAnchor {
  const Eigen::MatrixX3d* target_points = nullptr;
  double weight = 0.0;
};

ZoomOutResult PartialZoomOut(const LaplaceBasis& source, double source_unit,
                             const LaplaceBasis& target, double target_unit,
                             const std::vector<int>& initial_map, const std::vector<int>& samples,
                             const ZoomOutOptions& options,
                             const std::vector<int>& target_samples = {},
                             const PartialAnchor& anchor = {});

}  // namespace symembed
