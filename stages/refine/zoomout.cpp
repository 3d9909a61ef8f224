#include "stages/refine/zoomout.h"

#include <numeric>
#include <sstream>

#include "core/errors.h"
#include "stages/refine/functional_map.h"

namespace symembed {

bool ZoomOutOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  if (k_start < 1) {
    out << "k_start must be >= 1, got " << k_start;
  } else if (k_end < k_start) {
    out << "k_end (" << k_end << ") must be >= k_start (" << k_start << ")";
  } else if (step < 1) {
    out << "step must be >= 1, got " << step;
  }
  if (out.str().empty()) return true;
  if (error != nullptr) *error = out.str();
  return false;
}

ZoomOutResult ZoomOut(const LaplaceBasis& source, const LaplaceBasis& target,
                      const std::vector<int>& initial_map, const std::vector<int>& samples,
                      const ZoomOutOptions& options, const std::vector<int>& target_samples) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("zoomout: " + error);
  const int ns = source.NumVertices(), nt = target.NumVertices();
  if (source.NumEigenpairs() < options.k_end || target.NumEigenpairs() < options.k_end) {
    std::ostringstream out;
    out << "zoomout: k_end = " << options.k_end << " but the bases have " << source.NumEigenpairs()
        << " and " << target.NumEigenpairs() << " eigenpairs";
    throw InvalidInputError(out.str());
  }
  CheckPointMap(initial_map, ns, nt);

  // The vertices the iterations run on, and their least-squares weights.
  std::vector<int> active = samples;
  Eigen::VectorXd weights = source.mass;
  if (active.empty()) {
    active.resize(ns);
    std::iota(active.begin(), active.end(), 0);
  } else {
    for (int i : active) {
      if (i < 0 || i >= ns) throw InvalidInputError("zoomout: sample id out of range");
    }
    for (int j : target_samples) {
      if (j < 0 || j >= nt) throw InvalidInputError("zoomout: target sample id out of range");
    }
    weights.setOnes();
  }
  std::vector<int> all(ns);
  std::iota(all.begin(), all.end(), 0);
  const bool sampled = !samples.empty();

  std::vector<int> active_map(active.size());
  for (size_t r = 0; r < active.size(); ++r) active_map[r] = initial_map[active[r]];

  ZoomOutResult result;
  std::vector<int> k_sizes;
  for (int k = options.k_start; k < options.k_end; k += options.step) k_sizes.push_back(k);
  k_sizes.push_back(options.k_end);
  // The same points and weights at every basis size: A^T W A once, at the largest.
  const Eigen::MatrixXd gram = WeightedGram(source.evecs.leftCols(options.k_end), active, weights);
  for (size_t it = 0; it < k_sizes.size(); ++it) {
    const int k = k_sizes[it];
    const bool last = it + 1 == k_sizes.size();
    const Eigen::MatrixXd C = FitFunctionalMap(source.evecs.leftCols(k), target.evecs.leftCols(k),
                                               active, active_map, weights, &gram);
    std::vector<double> sq_dist;
    // The query covers every source vertex without samples, and in the last iteration of the
    // sampled variant (its dense map) unless only the samples are asked for; a query on the
    // samples lands on the target samples.
    const bool every_vertex = !sampled || (last && options.dense_result);
    const std::vector<int>& query = every_vertex ? all : active;
    std::vector<int> mapped =
        PointMapFromFunctionalMap(source.evecs, target.evecs, target.mass, C, query, &sq_dist,
                                  every_vertex ? std::vector<int>{} : target_samples);
    result.k.push_back(k);
    result.orthogonality.push_back(OrthogonalityDefect(C));
    result.spectral_residual.push_back(
        sq_dist.empty() ? 0.0
                        : std::accumulate(sq_dist.begin(), sq_dist.end(), 0.0) / sq_dist.size());
    if (last && every_vertex) {
      result.map = std::move(mapped);
    } else if (last) {
      result.map = initial_map;
      for (size_t r = 0; r < active.size(); ++r) result.map[active[r]] = mapped[r];
    } else {
      active_map = std::move(mapped);
    }
  }
  for (int i = 0; i < ns; ++i) result.changed += result.map[i] != initial_map[i];

  std::ostringstream message;
  message << "zoomout k " << options.k_start << ".." << options.k_end << " step " << options.step
          << (sampled ? " on " + std::to_string(samples.size()) + " samples" : "") << "; changed "
          << result.changed << "/" << ns
          << "; per k: orthogonality defect ||C^T C - I||^2/k, mean NN spectral residual:";
  message.precision(3);
  for (size_t it = 0; it < result.k.size(); ++it) {
    message << " " << result.k[it] << ":" << result.orthogonality[it] << ","
            << result.spectral_residual[it];
  }
  result.status.converged = true;
  result.status.iterations = static_cast<int>(result.k.size());
  result.status.residual = result.orthogonality.back();
  result.status.message = message.str();
  return result;
}

}  // namespace symembed
