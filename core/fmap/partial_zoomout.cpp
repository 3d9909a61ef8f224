#include "core/fmap/partial_zoomout.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/functional_map.h"
#include "core/fmap/spectral_knn.h"

namespace symembed {

int PartBasisSize(const Eigen::VectorXd& whole_evals, const Eigen::VectorXd& part_evals, int k_w) {
  if (k_w < 1 || k_w > whole_evals.size() || k_w > part_evals.size()) {
    throw InvalidInputError("partial zoomout: basis size " + std::to_string(k_w) +
                            " exceeds the eigenpairs given");
  }
  // A relative margin so that an eigenvalue equal to the whole's up to rounding counts.
  const double limit = whole_evals(k_w - 1) * (1.0 + 1e-9);
  int count = 0;
  while (count < k_w && part_evals(count) <= limit) ++count;
  return std::max(count, std::min(kMinPartSize, k_w));
}

namespace {

// NearestUnderMap with the anchor's points side by side when it has weight: each query's side
// row is its initial image's point, each target's its own.
std::vector<int> Query(const BasisRef& Q, const BasisRef& P, const std::vector<int>& targets,
                       const Eigen::MatrixXd& C, const PartialAnchor& anchor,
                       const std::vector<int>& images, std::vector<double>* sq) {
  if (anchor.weight <= 0.0) return NearestUnderMap(Q, P, targets, C, sq);
  const double w = std::sqrt(anchor.weight);
  const Eigen::MatrixX3d& X = *anchor.target_points;
  Eigen::MatrixXd target_side(targets.size(), 3), query_side(images.size(), 3);
  for (size_t r = 0; r < targets.size(); ++r) target_side.row(r) = w * X.row(targets[r]);
  for (size_t r = 0; r < images.size(); ++r) query_side.row(r) = w * X.row(images[r]);
  return NearestUnderMap(Q, P, targets, C, sq, target_side, query_side);
}

}  // namespace

ZoomOutResult PartialZoomOut(const LaplaceBasis& source, double source_unit,
                             const LaplaceBasis& target, double target_unit,
                             const std::vector<int>& initial_map, const std::vector<int>& samples,
                             const ZoomOutOptions& options, const std::vector<int>& target_samples,
                             const PartialAnchor& anchor) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("partial zoomout: " + error);
  const int k_end = options.k_end;
  CheckBasesReach("partial zoomout", source, target, k_end);
  if (!(source_unit > 0.0) || !(target_unit > 0.0)) {
    throw InvalidInputError("partial zoomout: the units must be positive");
  }
  if (anchor.weight > 0.0 &&
      (anchor.target_points == nullptr || anchor.target_points->rows() != target.NumVertices())) {
    throw InvalidInputError("partial zoomout: the anchor needs one point per target vertex");
  }
  const int ns = source.NumVertices(), nt = target.NumVertices();
  CheckPointMap(initial_map, ns, nt);
  const ZoomOutActive active = ZoomOutActivePoints("partial zoomout", source, samples);
  for (int j : target_samples) {
    if (j < 0 || j >= nt) throw InvalidInputError("partial zoomout: target sample id out of range");
  }

  // Eigenvalues scale as 1 / length^2, areas as length^2.
  const Eigen::VectorXd source_evals = source.evals.head(k_end) / (source_unit * source_unit);
  const Eigen::VectorXd target_evals = target.evals.head(k_end) / (target_unit * target_unit);
  const double source_area = source.mass.sum() * source_unit * source_unit;
  const double target_area = target.mass.sum() * target_unit * target_unit;
  ZoomOutResult result;
  result.start = options.k_start;
  if (source_area > target_area) {
    // Every source vertex takes part in the fit, and those of the whole that the part lacks
    // have no true image to pull towards.
    result.map = initial_map;
    result.status.message =
        "not run: the source is the whole (a part's map is refined from "
        "the part)";
    return result;
  }

  // The schedule: the whole's sizes as ZoomOut's, the part's matched by eigenvalue.
  const std::vector<int> sizes = ZoomOutBasisSizes(options.k_start, options);
  const Eigen::MatrixXd source_rows = BasisRows(source.evecs, active.ids, k_end);
  const Eigen::MatrixXd gram = WeightedGram(source_rows, active.weights);
  const std::vector<int> targets =
      MatchableTargets(target.mass, samples.empty() ? std::vector<int>{} : target_samples);
  const Eigen::MatrixXd target_rows = BasisRows(target.evecs, targets, k_end);

  // The bases are M-orthonormal on each surface in its own units, so a function's values scale
  // as 1 / length: in the common unit the source's rows are these over source_unit, the
  // target's over target_unit. The least-squares map absorbs that factor; the query, which
  // compares the source's rows with the target's under C^T, must not, or a part's rows would be
  // compared with the whole's at another scale. So C is queried as (source_unit /
  // target_unit)^2 C, the query of the maps in the common unit.
  const double query_scale = (source_unit / target_unit) * (source_unit / target_unit);
  std::vector<int> active_map(active.ids.size());
  for (size_t r = 0; r < active_map.size(); ++r) active_map[r] = initial_map[active.ids[r]];
  const std::vector<int> active_initial = active_map;
  Eigen::MatrixXd C;
  std::ostringstream trace;
  trace.precision(3);
  for (size_t it = 0; it < sizes.size(); ++it) {
    const int kt = sizes[it];
    const int ks = PartBasisSize(target_evals, source_evals, kt);
    C = FitFunctionalMapFromRows(source_rows.leftCols(ks), BasisRows(target.evecs, active_map, kt),
                                 active.weights, &gram);
    std::vector<double> sq;
    if (it + 1 < sizes.size()) {
      active_map = Query(source_rows.leftCols(ks), target_rows.leftCols(kt), targets,
                         query_scale * C, anchor, active_initial, &sq);
    } else {
      // The last query maps every source vertex onto every target vertex.
      const std::vector<int> all_targets = MatchableTargets(target.mass);
      result.map = Query(source.evecs.leftCols(ks), BasisRows(target.evecs, all_targets, kt),
                         all_targets, query_scale * C, anchor, initial_map, &sq);
    }
    result.k.push_back(kt);
    result.spectral_residual.push_back(std::accumulate(sq.begin(), sq.end(), 0.0) / sq.size());
    trace << " " << ks << "x" << kt << ":" << result.spectral_residual.back();
  }
  for (int i = 0; i < ns; ++i) result.changed += result.map[i] != initial_map[i];
  result.status.converged = true;
  result.status.iterations = static_cast<int>(sizes.size());
  result.status.residual = result.spectral_residual.back();
  std::ostringstream message;
  message.precision(3);
  message << "partial zoomout (area ratio " << source_area / target_area << "), whole's k "
          << options.k_start << ".." << k_end << " step " << options.step
          << (samples.empty() ? "" : " on " + std::to_string(active.ids.size()) + " samples")
          << (anchor.weight > 0.0
                  ? ", anchored to the initial map with weight " + std::to_string(anchor.weight)
                  : std::string())
          << "; changed " << result.changed << "/" << ns
          << "; per size (source x target: mean NN spectral residual):" << trace.str();
  result.status.message = message.str();
  return result;
}

}  // namespace symembed
