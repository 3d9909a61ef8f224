#include "stages/refine/fmap_icp.h"

#include <numeric>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/functional_map.h"

namespace symembed {

FunctionalMapIcpResult FunctionalMapIcp(const LaplaceBasis& source, const LaplaceBasis& target,
                                        const std::vector<int>& initial_map,
                                        const FunctionalMapIcpOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("icp: " + error);
  const int ns = source.NumVertices(), nt = target.NumVertices(), k = options.k;
  if (source.NumEigenpairs() < k || target.NumEigenpairs() < k) {
    std::ostringstream out;
    out << "icp: k = " << k << " but the bases have " << source.NumEigenpairs() << " and "
        << target.NumEigenpairs() << " eigenpairs";
    throw InvalidInputError(out.str());
  }
  CheckPointMap(initial_map, ns, nt);
  std::vector<int> all(ns);
  std::iota(all.begin(), all.end(), 0);
  const Eigen::MatrixXd Phi_s = source.evecs.leftCols(k), Phi_t = target.evecs.leftCols(k);

  FunctionalMapIcpResult result;
  result.map = initial_map;
  result.status.converged = false;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::MatrixXd C =
        FitOrthogonalFunctionalMap(Phi_s, Phi_t, all, result.map, source.mass);
    std::vector<double> sq_dist;
    std::vector<int> mapped =
        PointMapFromFunctionalMap(Phi_s, Phi_t, target.mass, C, all, &sq_dist);
    int changes = 0;
    for (int i = 0; i < ns; ++i) changes += mapped[i] != result.map[i];
    result.map = std::move(mapped);
    result.changes.push_back(changes);
    result.spectral_residual.push_back(std::accumulate(sq_dist.begin(), sq_dist.end(), 0.0) / ns);
    if (changes == 0) {
      result.status.converged = true;
      break;
    }
  }
  for (int i = 0; i < ns; ++i) result.changed += result.map[i] != initial_map[i];

  std::ostringstream message;
  message << "icp k " << k << "; " << (result.status.converged ? "converged" : "stopped")
          << " after " << result.changes.size() << " iterations; changed " << result.changed << "/"
          << ns << "; per iteration: changes, mean NN spectral residual:";
  message.precision(3);
  for (size_t it = 0; it < result.changes.size(); ++it) {
    message << " " << result.changes[it] << "," << result.spectral_residual[it];
  }
  result.status.iterations = static_cast<int>(result.changes.size());
  result.status.residual = result.spectral_residual.back();
  result.status.message = message.str();
  return result;
}

}  // namespace symembed
