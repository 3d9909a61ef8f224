#include "eval/evaluator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <unordered_set>

#include "core/clock.h"
#include "core/errors.h"

namespace symembed {

namespace {

EvalShape BaseShape(const PreprocessResult& pre, int num_input_vertices) {
  if (static_cast<int>(pre.input_ids.size()) != pre.surface.NumVertices()) {
    throw InvalidInputError("preprocess result has " + std::to_string(pre.input_ids.size()) +
                            " input ids for " + std::to_string(pre.surface.NumVertices()) +
                            " vertices");
  }
  EvalShape shape;
  shape.surface = pre.surface;
  shape.area = TotalArea(pre.surface);
  if (!(shape.area > 0)) throw InvalidInputError("evaluation surface has zero area");
  shape.vertex_of_input.assign(num_input_vertices, -1);
  for (int v = 0; v < pre.surface.NumVertices(); ++v) {
    const int id = pre.input_ids[v];
    if (id < 0 || id >= num_input_vertices) {
      throw InvalidInputError("preprocess input id " + std::to_string(id) + " out of range [0, " +
                              std::to_string(num_input_vertices) + ")");
    }
    shape.vertex_of_input[id] = v;
  }
  return shape;
}

}  // namespace

EvalShape MakeEvalShape(const PreprocessResult& pre, const Surface& input) {
  EvalShape shape = BaseShape(pre, input.NumVertices());
  for (int id = 0; id < input.NumVertices(); ++id) {
    if (shape.vertex_of_input[id] >= 0) continue;
    // Removed by preprocessing: nearest kept vertex, compared in input coordinates.
    double best = std::numeric_limits<double>::infinity();
    for (int v = 0; v < pre.surface.NumVertices(); ++v) {
      const double d = (input.V.row(pre.input_ids[v]) - input.V.row(id)).squaredNorm();
      if (d < best) {
        best = d;
        shape.vertex_of_input[id] = v;
      }
    }
  }
  return shape;
}

EvalShape MakeEvalShape(const PreprocessResult& pre, int num_input_vertices) {
  EvalShape shape = BaseShape(pre, num_input_vertices);
  for (int id = 0; id < num_input_vertices; ++id) {
    if (shape.vertex_of_input[id] < 0) {
      throw InvalidInputError("input vertex " + std::to_string(id) +
                              " was removed by preprocessing; build the EvalShape from the input "
                              "surface to look it up");
    }
  }
  return shape;
}

InputGroundTruth SelectPoints(const InputGroundTruth& gt, const EvalShape& target, int n) {
  const int lines = static_cast<int>(gt.target_ids.size());
  if (n <= 0 || n >= lines) return gt;
  std::vector<Eigen::Vector3d> p(lines);
  for (int i = 0; i < lines; ++i) {
    const int id = gt.target_ids[i];
    if (id < 0 || id >= target.NumInputVertices()) {
      throw InvalidInputError("ground-truth target id " + std::to_string(id) + " out of range");
    }
    p[i] = target.surface.V.row(target.vertex_of_input[id]).transpose();
  }
  std::vector<double> dist(lines, std::numeric_limits<double>::infinity());
  std::vector<char> taken(lines, 0);
  int next = 0;
  for (int k = 0; k < n; ++k) {
    taken[next] = 1;
    int best = -1;
    double best_d = -1.0;
    for (int i = 0; i < lines; ++i) {
      dist[i] = std::min(dist[i], (p[i] - p[next]).squaredNorm());
      if (!taken[i] && dist[i] > best_d) {
        best_d = dist[i];
        best = i;
      }
    }
    next = best;
  }
  InputGroundTruth out;
  const bool sym = !gt.target_sym_ids.empty();
  for (int i = 0; i < lines; ++i) {
    if (!taken[i]) continue;
    out.source_ids.push_back(gt.source_ids[i]);
    out.target_ids.push_back(gt.target_ids[i]);
    if (sym) out.target_sym_ids.push_back(gt.target_sym_ids[i]);
  }
  return out;
}

// Distance rows of one target: source vertex -> distances to every vertex (float halves the
// memory; 7 significant digits are far below the errors' meaningful resolution).
struct Evaluator::TargetCache {
  std::mutex mutex;  // guards everything below
  std::unique_ptr<GeodesicSolver> solver;
  std::unordered_map<int, std::vector<float>> rows;
  uint64_t last_use = 0;
  bool evicted = false;  // removed from the cache; its bytes are no longer counted
  int64_t bytes = 0;
};

Evaluator::Evaluator(const EvaluationOptions& options, const GeodesicsStage& geodesics,
                     double cache_budget_mb)
    : options_(options),
      geodesics_(geodesics),
      budget_bytes_(static_cast<int64_t>(cache_budget_mb * 1024.0 * 1024.0)) {}

Evaluator::~Evaluator() = default;

int64_t Evaluator::RowsComputed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return rows_computed_;
}

std::shared_ptr<Evaluator::TargetCache> Evaluator::Acquire(const std::string& target_name) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto& entry = cache_[target_name];
  if (!entry) entry = std::make_shared<TargetCache>();
  entry->last_use = ++clock_;
  return entry;
}

void Evaluator::Account(const std::string& target_name, TargetCache& entry, int64_t rows,
                        int64_t bytes) const {
  std::lock_guard<std::mutex> lock(mutex_);
  rows_computed_ += rows;
  if (entry.evicted) return;
  entry.bytes += bytes;
  total_bytes_ += bytes;
  // Evict whole targets, least recently used first, never the one in use by this call.
  while (total_bytes_ > budget_bytes_) {
    auto victim = cache_.end();
    for (auto it = cache_.begin(); it != cache_.end(); ++it) {
      if (it->first == target_name) continue;
      if (victim == cache_.end() || it->second->last_use < victim->second->last_use) victim = it;
    }
    if (victim == cache_.end()) break;
    victim->second->evicted = true;
    total_bytes_ -= victim->second->bytes;
    cache_.erase(victim);
  }
}

std::vector<double> Evaluator::Errors(const std::string& target_name, const EvalShape& target,
                                      const std::vector<int>& map_input_ids,
                                      const InputGroundTruth& all_gt, std::vector<double>* sym,
                                      double* distance_seconds) const {
  const InputGroundTruth gt = SelectPoints(all_gt, target, options_.points);
  const int lines = static_cast<int>(gt.target_ids.size());
  const bool has_sym = sym != nullptr && !gt.target_sym_ids.empty();
  if (lines == 0) throw InvalidInputError("no ground-truth points for this pair");
  if (gt.source_ids.size() != gt.target_ids.size() ||
      (!gt.target_sym_ids.empty() && gt.target_sym_ids.size() != gt.target_ids.size())) {
    throw InvalidInputError("ground truth has lines of different lengths");
  }
  const int num_source = static_cast<int>(map_input_ids.size());
  const int num_target = target.NumInputVertices();
  auto target_vertex = [&](int id, const char* what) {
    if (id < 0 || id >= num_target) {
      throw InvalidInputError(std::string(what) + " " + std::to_string(id) + " out of range [0, " +
                              std::to_string(num_target) + ")");
    }
    return target.vertex_of_input[id];
  };
  // Every line in vertex ids of the evaluation surface.
  std::vector<int> mapped(lines), truth(lines), truth_sym(has_sym ? lines : 0);
  for (int i = 0; i < lines; ++i) {
    const int a = gt.source_ids[i];
    if (a < 0 || a >= num_source) {
      throw InvalidInputError("ground-truth source id " + std::to_string(a) +
                              " is outside the map (" + std::to_string(num_source) + " entries)");
    }
    mapped[i] = target_vertex(map_input_ids[a], "map entry");
    truth[i] = target_vertex(gt.target_ids[i], "ground-truth target id");
    if (has_sym) truth_sym[i] = target_vertex(gt.target_sym_ids[i], "symmetric ground-truth id");
  }
  std::vector<int> gt_sources(truth);
  gt_sources.insert(gt_sources.end(), truth_sym.begin(), truth_sym.end());
  std::sort(gt_sources.begin(), gt_sources.end());
  gt_sources.erase(std::unique(gt_sources.begin(), gt_sources.end()), gt_sources.end());
  std::vector<int> map_sources(mapped);
  std::sort(map_sources.begin(), map_sources.end());
  map_sources.erase(std::unique(map_sources.begin(), map_sources.end()), map_sources.end());
  const bool from_truth = 2 * map_sources.size() >= gt_sources.size();
  const std::vector<int>& sources = from_truth ? gt_sources : map_sources;

  // When rows are missing, their time includes waiting for another pair computing this
  // target's rows.
  const auto rows_start = std::chrono::steady_clock::now();
  std::shared_ptr<TargetCache> entry = Acquire(target_name);
  std::lock_guard<std::mutex> lock(entry->mutex);
  if (!entry->solver) entry->solver = geodesics_.Prepare(target.surface);
  std::vector<int> missing;
  for (int s : sources) {
    if (!entry->rows.count(s)) missing.push_back(s);
  }
  if (!missing.empty()) {
    // A chunk of sources at a time (each row is computed on its own, so the rows do not depend
    // on the chunks): no #missing x #V matrix of doubles is held, and a chunk's column-major
    // values are read in order.
    constexpr size_t kChunk = 128;
    const int num_vertices = target.surface.NumVertices();
    for (size_t begin = 0; begin < missing.size(); begin += kChunk) {
      const std::vector<int> chunk(missing.begin() + begin,
                                   missing.begin() + std::min(missing.size(), begin + kChunk));
      const Eigen::MatrixXd D = entry->solver->Distances(chunk);
      SYMEMBED_CHECK(
          D.rows() == static_cast<Eigen::Index>(chunk.size()) && D.cols() == num_vertices,
          "geodesic solver returned " << D.rows() << " x " << D.cols());
      std::vector<std::vector<float>> chunk_rows(chunk.size(), std::vector<float>(num_vertices));
      for (int v = 0; v < num_vertices; ++v) {
        for (size_t k = 0; k < chunk.size(); ++k) chunk_rows[k][v] = static_cast<float>(D(k, v));
      }
      for (size_t k = 0; k < chunk.size(); ++k) {
        entry->rows.emplace(chunk[k], std::move(chunk_rows[k]));
      }
    }
    const auto rows = static_cast<int64_t>(missing.size());
    Account(target_name, *entry, rows, rows * num_vertices * static_cast<int64_t>(sizeof(float)));
  }
  if (distance_seconds) *distance_seconds = missing.empty() ? 0.0 : SecondsSince(rows_start);
  const double norm = 1.0 / std::sqrt(target.area);
  auto distance = [&](int x, int b) {
    return from_truth ? entry->rows.at(b)[x] : entry->rows.at(x)[b];
  };
  std::vector<double> errors(lines);
  for (int i = 0; i < lines; ++i) errors[i] = distance(mapped[i], truth[i]) * norm;
  if (has_sym) {
    sym->resize(lines);
    for (int i = 0; i < lines; ++i) (*sym)[i] = distance(mapped[i], truth_sym[i]) * norm;
  }
  return errors;
}

PairEvaluation Evaluator::Evaluate(const std::string& source_name, const std::string& target_name,
                                   const EvalShape& target, const std::vector<int>& map_input_ids,
                                   const InputGroundTruth& gt, int chosen, int oracle) const {
  const auto start = std::chrono::steady_clock::now();
  PairEvaluation pair;
  pair.source = source_name;
  pair.target = target_name;
  pair.chosen = chosen;
  pair.oracle = oracle;
  try {
    pair.errors_direct = Errors(target_name, target, map_input_ids, gt, &pair.errors_sym);
    ComputePairStatistics(pair);
    pair.flip = ClassifyFlip(chosen, oracle, pair.has_sym, pair.mean_direct, pair.mean_sym);
    pair.ok = true;
  } catch (const std::exception& e) {
    pair = PairEvaluation{};
    pair.source = source_name;
    pair.target = target_name;
    pair.chosen = chosen;
    pair.oracle = oracle;
    pair.ok = false;
    pair.message = e.what();
  }
  pair.stage_seconds["evaluation"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return pair;
}

double Evaluator::MeanError(const std::string& target_name, const EvalShape& target,
                            const std::vector<int>& map_input_ids,
                            const InputGroundTruth& gt, double* distance_seconds) const {
  return Mean(Errors(target_name, target, map_input_ids, gt, nullptr, distance_seconds));
}

}  // namespace symembed
