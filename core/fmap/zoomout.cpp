#include "core/fmap/zoomout.h"

#include <algorithm>
#include <numeric>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/functional_map.h"

namespace symembed {

bool ZoomOutOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  out << FieldViolation(*this);
  if (out.str().empty() && k_end < k_start) {
    out << "k_end (" << k_end << ") must be >= k_start (" << k_start << ")";
  }
  for (size_t i = 0; i < extra_k_starts.size() && out.str().empty(); ++i) {
    const int k = extra_k_starts[i];
    const auto earlier = extra_k_starts.begin() + i;
    if (k < 1 || k > k_end) {
      out << "extra_k_starts must lie in [1, k_end = " << k_end << "], got " << k;
    } else if (k == k_start) {
      out << "extra_k_starts must differ from k_start (" << k_start << ")";
    } else if (std::find(extra_k_starts.begin(), earlier, k) != earlier) {
      out << "extra_k_starts lists " << k << " twice";
    }
  }
  if (out.str().empty()) return true;
  if (error != nullptr) *error = out.str();
  return false;
}

std::vector<int> ZoomOutBasisSizes(int start, const ZoomOutOptions& options) {
  std::vector<int> sizes;
  for (int k = start; k < options.k_end; k += options.step) sizes.push_back(k);
  sizes.push_back(options.k_end);
  return sizes;
}

ZoomOutActive ZoomOutActivePoints(const char* who, const LaplaceBasis& source,
                                  const std::vector<int>& samples) {
  const int ns = source.NumVertices();
  ZoomOutActive active{samples, {}};
  if (active.ids.empty()) {
    active.ids.resize(ns);
    std::iota(active.ids.begin(), active.ids.end(), 0);
    active.weights = source.mass;
    return active;
  }
  for (int i : active.ids) {
    if (i < 0 || i >= ns) throw InvalidInputError(std::string(who) + ": sample id out of range");
  }
  active.weights = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(active.ids.size()));
  return active;
}

void CheckBasesReach(const char* who, const LaplaceBasis& source, const LaplaceBasis& target,
                     int k_end) {
  if (source.NumEigenpairs() >= k_end && target.NumEigenpairs() >= k_end) return;
  std::ostringstream out;
  out << who << ": k_end = " << k_end << " but the bases have " << source.NumEigenpairs() << " and "
      << target.NumEigenpairs() << " eigenpairs";
  throw InvalidInputError(out.str());
}

namespace {

double Mean(const std::vector<double>& values) {
  return values.empty() ? 0.0
                        : std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

// One ZoomOut run from one start on the active points: its trace and the functional map at k_end.
struct StartRun {
  int start = 0;
  std::vector<int> k;
  std::vector<double> orthogonality, spectral_residual;
  Eigen::MatrixXd C;            // the functional map at k_end
  std::vector<int> active_map;  // the map of the active points (after C when it was queried)
};

}  // namespace

ZoomOutSetup::ZoomOutSetup(const LaplaceBasis& source, const LaplaceBasis& target,
                           const std::vector<int>& samples, const ZoomOutOptions& options,
                           const std::vector<int>& target_samples)
    : source_(source), target_(target), options_(options), sampled_(!samples.empty()),
      target_sample_count_(samples.empty() ? 0 : static_cast<int>(target_samples.size())) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("zoomout: " + error);
  const int nt = target.NumVertices();
  CheckBasesReach("zoomout", source, target, options.k_end);
  // The vertices the iterations run on, and their least-squares weights.
  ZoomOutActive active = ZoomOutActivePoints("zoomout", source, samples);
  active_ = std::move(active.ids);
  active_weights_ = std::move(active.weights);
  if (!samples.empty()) {
    for (int j : target_samples) {
      if (j < 0 || j >= nt) throw InvalidInputError("zoomout: target sample id out of range");
    }
  }
  // A query on the samples lands on the target samples; a query on every source vertex (the
  // dense variant, and the last query of the sampled one) on every target vertex.
  const std::vector<int> no_ids;
  const std::vector<int>& active_targets = samples.empty() ? no_ids : target_samples;
  // The same points and weights at every basis size: A^T W A once, at the largest, and the basis
  // rows of the active points and of the targets they may land on gathered once; each basis size
  // uses their first columns.
  source_rows_ = BasisRows(source.evecs, active_, options.k_end);
  gram_ = WeightedGram(source_rows_, active_weights_);
  targets_ = MatchableTargets(target.mass, active_targets);
  target_rows_ = BasisRows(target.evecs, targets_, options.k_end);
  target_row_.assign(nt, -1);
  for (size_t r = 0; r < targets_.size(); ++r) target_row_[targets_[r]] = static_cast<int>(r);
}

Eigen::MatrixXd ZoomOutSetup::TargetRows(const std::vector<int>& ids, int k) const {
  std::vector<int> rows(ids.size());
  for (size_t r = 0; r < ids.size(); ++r) {
    rows[r] = target_row_[ids[r]];
    // An initial map may land off the matchable targets: then the basis itself.
    if (rows[r] < 0) return BasisRows(target_.evecs, ids, k);
  }
  return BasisRows(target_rows_, rows, k);
}

ZoomOutResult ZoomOut(const LaplaceBasis& source, const LaplaceBasis& target,
                      const std::vector<int>& initial_map, const std::vector<int>& samples,
                      const ZoomOutOptions& options, const std::vector<int>& target_samples) {
  return ZoomOutSetup(source, target, samples, options, target_samples).Run(initial_map);
}

namespace {

// Appends basis size k's trace to *run: the orthogonality defect of C and the mean squared
// spectral residual sq of its query.
void Record(StartRun* run, int k, const Eigen::MatrixXd& C, const std::vector<double>& sq) {
  run->k.push_back(k);
  run->orthogonality.push_back(OrthogonalityDefect(C));
  run->spectral_residual.push_back(Mean(sq));
}

// The status message: the schedule, the samples (when sampled: `active` of them), the starts
// compared, and the trace.
std::string ZoomOutMessage(const ZoomOutResult& result, const std::vector<int>& starts,
                           const ZoomOutOptions& options, bool sampled, size_t active,
                           int target_samples, int ns) {
  std::ostringstream message;
  message << "zoomout k " << result.start << ".." << options.k_end << " step " << options.step
          << (sampled ? " on " + std::to_string(active) + " samples" : "")
          << (target_samples > 0 ? " onto " + std::to_string(target_samples) + " target samples"
                                 : "");
  message.precision(3);
  if (!result.start_residuals.empty()) {
    message << "; starts (k: residual at k_end)";
    for (size_t s = 0; s < starts.size(); ++s) {
      message << " " << starts[s] << ":" << result.start_residuals[s];
    }
    message << ", kept " << result.start;
  }
  message << "; changed " << result.changed << "/" << ns
          << "; per k: orthogonality defect ||C^T C - I||^2/k, mean NN spectral residual:";
  for (size_t it = 0; it < result.k.size(); ++it) {
    message << " " << result.k[it] << ":" << result.orthogonality[it] << ","
            << result.spectral_residual[it];
  }
  return message.str();
}

}  // namespace

ZoomOutResult ZoomOutSetup::Run(const std::vector<int>& initial_map) const {
  const int ns = source_.NumVertices();
  CheckPointMap(initial_map, ns, target_.NumVertices());
  std::vector<int> starts = {options_.k_start};
  starts.insert(starts.end(), options_.extra_k_starts.begin(), options_.extra_k_starts.end());
  // The sampled variant's result maps every source vertex with the last functional map. A
  // single run goes straight to that query; several are first compared on the active points.
  const bool dense_last = sampled_ && options_.dense_result;
  const bool query_last_on_active = !dense_last || starts.size() > 1;

  std::vector<StartRun> runs(starts.size());
  for (size_t s = 0; s < starts.size(); ++s) {
    StartRun& run = runs[s];
    run.start = starts[s];
    run.active_map.resize(active_.size());
    for (size_t r = 0; r < active_.size(); ++r) run.active_map[r] = initial_map[active_[r]];
    const std::vector<int> sizes = ZoomOutBasisSizes(run.start, options_);
    for (size_t it = 0; it < sizes.size(); ++it) {
      const int k = sizes[it];
      run.C = FitFunctionalMapFromRows(source_rows_.leftCols(k), TargetRows(run.active_map, k),
                                       active_weights_, &gram_);
      if (it + 1 < sizes.size() || query_last_on_active) {
        std::vector<double> sq;
        run.active_map =
            NearestUnderMap(source_rows_.leftCols(k), target_rows_.leftCols(k), targets_, run.C,
                            &sq);
        Record(&run, k, run.C, sq);
      }
    }
  }
  // The kept run: the lowest mean spectral residual at k_end on the active points.
  size_t kept = 0;
  for (size_t s = 1; s < runs.size(); ++s) {
    if (runs[s].spectral_residual.back() < runs[kept].spectral_residual.back()) kept = s;
  }

  ZoomOutResult result;
  if (starts.size() > 1) {
    for (const StartRun& r : runs) result.start_residuals.push_back(r.spectral_residual.back());
  }
  StartRun& run = runs[kept];
  result.start = run.start;
  if (dense_last) {
    // The trace reports the dense query at k_end, not the comparison's on the samples.
    if (query_last_on_active) {
      run.k.pop_back();
      run.orthogonality.pop_back();
      run.spectral_residual.pop_back();
    }
    std::vector<int> all(ns);
    std::iota(all.begin(), all.end(), 0);
    std::vector<double> sq;
    result.map =
        PointMapFromFunctionalMap(source_.evecs, target_.evecs, target_.mass, run.C, all, &sq);
    Record(&run, options_.k_end, run.C, sq);
  } else if (sampled_) {
    result.map = initial_map;
    for (size_t r = 0; r < active_.size(); ++r) result.map[active_[r]] = run.active_map[r];
  } else {
    result.map = run.active_map;
  }
  result.k = std::move(run.k);
  result.orthogonality = std::move(run.orthogonality);
  result.spectral_residual = std::move(run.spectral_residual);
  for (int i = 0; i < ns; ++i) result.changed += result.map[i] != initial_map[i];

  result.status.converged = true;
  result.status.iterations = static_cast<int>(result.k.size());
  result.status.residual = result.orthogonality.back();
  result.status.message = ZoomOutMessage(result, starts, options_, sampled_, active_.size(),
                                         target_sample_count_, ns);
  return result;
}

}  // namespace symembed
