// Test stages, a test dataset and a test evaluation for the runner tests: cheap stages on tiny
// grid meshes written to a temporary folder, each counting its calls, so that tests can check
// what the runner recomputes. Header-only (tests/ compiles only *_test.cpp and test_util.cpp).
#pragma once

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "core/errors.h"
#include "core/primitives.h"
#include "eval/report.h"
#include "harness/runner.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed::testing::runner {

// Calls of each test stage (by kind), process-wide.
class CallCounter {
 public:
  static CallCounter& Get() {
    static CallCounter counter;
    return counter;
  }
  void Add(const std::string& kind) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++calls_[kind];
  }
  std::map<std::string, int> Take() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::map<std::string, int> out;
    out.swap(calls_);
    return out;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, int> calls_;
};

inline void Count(const std::string& kind) { CallCounter::Get().Add(kind); }

// A minimal OFF writer/reader for the test meshes.
inline std::string OffText(const Surface& s) {
  std::ostringstream out;
  out.precision(17);
  out << "OFF\n" << s.NumVertices() << " " << s.NumFaces() << " 0\n";
  for (int i = 0; i < s.NumVertices(); ++i) out << s.V(i, 0) << " " << s.V(i, 1) << " " << s.V(i, 2) << "\n";
  for (int f = 0; f < s.NumFaces(); ++f) out << "3 " << s.F(f, 0) << " " << s.F(f, 1) << " " << s.F(f, 2) << "\n";
  return out.str();
}

inline Surface ReadOff(const std::string& path) {
  std::ifstream in(path);
  std::string magic;
  int nv = 0, nf = 0, ne = 0;
  if (!(in >> magic >> nv >> nf >> ne) || magic != "OFF" || nv <= 0 || nf <= 0) {
    throw InvalidInputError(path + ": not an OFF mesh");
  }
  Surface s;
  s.V.resize(nv, 3);
  s.F.resize(nf, 3);
  for (int i = 0; i < nv; ++i) in >> s.V(i, 0) >> s.V(i, 1) >> s.V(i, 2);
  for (int f = 0; f < nf; ++f) {
    int k;
    in >> k >> s.F(f, 0) >> s.F(f, 1) >> s.F(f, 2);
  }
  if (!in) throw InvalidInputError(path + ": truncated OFF mesh");
  return s;
}

// Dataset `testset`: root/shapes/*.off (sorted), root/pairs.txt ("A B" lines), identity ground
// truth (all shapes share connectivity) with the mirror x -> 1 - x of the 5 x 4 grids
// (GridMirror) as symmetric ground truth.
// The vertex of a 5 x 4 grid (GridMesh(5, 4)) mirrored by x -> 1 - x.
inline int GridMirror(int v) { return (v / 5) * 5 + (4 - v % 5); }

class TestDataset : public Dataset {
 public:
  explicit TestDataset(std::string root) : root_(std::move(root)) {}
  DatasetIndex Load() const override {
    DatasetIndex index;
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(root_ + "/shapes")) {
      files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      index.shapes.push_back({std::filesystem::path(f).stem().string(), "grid", f});
    }
    std::ifstream in(root_ + "/pairs.txt");
    for (std::string a, b; in >> a >> b;) index.pairs.push_back({a, b});
    return index;
  }
  // A shape whose name starts with 'p' has its ground truth onto s0 instead (as a SHREC'16
  // partial shape onto its null shape): vertex i onto s0's GridMirror(i).
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int num_vertices) const override {
    ShapeGroundTruth gt;
    if (shape.name[0] == 'p') {
      gt.onto = "s0";
      for (int i = 0; i < num_vertices; ++i) {
        gt.onto_lines.source_ids.push_back(i);
        gt.onto_lines.target_ids.push_back(GridMirror(i));
      }
      return gt;
    }
    for (int i = 0; i < num_vertices; ++i) gt.ids.push_back(i);
    if (num_vertices == 20) {
      for (int i = 0; i < num_vertices; ++i) gt.sym_ids.push_back(GridMirror(i));
    }
    return gt;
  }

 private:
  std::string root_;
};

class TestPreprocess : public PreprocessStage {
 public:
  PreprocessResult Run(const Surface& input) const override {
    Count("preprocess");
    PreprocessResult r;
    r.surface = input;
    for (int i = 0; i < input.NumVertices(); ++i) r.input_ids.push_back(i);
    r.report = {{"changed", 0.0}};
    return r;
  }
};

class TestSampling : public SamplingStage {
 public:
  explicit TestSampling(int count) : count_(count) {}
  SamplingResult Run(const Surface& s) const override {
    Count("sampling");
    SamplingResult r;
    for (int i = 0; i < std::min(count_, s.NumVertices()); ++i) r.samples.push_back(i);
    return r;
  }

 private:
  int count_;
};

class EuclideanSolver : public GeodesicSolver {
 public:
  explicit EuclideanSolver(const Surface& s) : V_(s.V) {}
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const override {
    Count("geodesics");
    Eigen::MatrixXd D(sources.size(), V_.rows());
    for (size_t i = 0; i < sources.size(); ++i) {
      for (int v = 0; v < V_.rows(); ++v) D(i, v) = (V_.row(sources[i]) - V_.row(v)).norm();
    }
    return D;
  }

 private:
  Eigen::MatrixX3d V_;
};

class TestGeodesics : public GeodesicsStage {
 public:
  std::unique_ptr<GeodesicSolver> Prepare(const Surface& s) const override {
    return std::make_unique<EuclideanSolver>(s);
  }
};

// Y = scale * V (uses D only to check it is there).
class TestEmbedding : public EmbeddingStage {
 public:
  explicit TestEmbedding(double scale) : scale_(scale) {}
  EmbeddingResult Run(const EmbeddingInput& in) const override {
    Count("embedding");
    SYMEMBED_CHECK(in.D.rows() == static_cast<int>(in.samples.size()), "D rows");
    EmbeddingResult r;
    r.Y = scale_ * in.surface.V;
    return r;
  }

 private:
  double scale_;
};

// The identity self map; with `second`, also a second plane hypothesis (score 1 marks it; with
// `second_fails`, score 2, which TestSymmetrize cannot symmetrize).
class TestSymmetry : public SymmetryStage {
 public:
  explicit TestSymmetry(bool second = false, bool second_fails = false)
      : second_(second), second_fails_(second_fails) {}
  SymmetryResult Run(const SymmetryInput& in) const override {
    Count("symmetry");
    SymmetryResult r;
    for (size_t i = 0; i < in.samples.size(); ++i) r.sigma.push_back(static_cast<int>(i));
    r.confidence = Eigen::VectorXd::Ones(in.samples.size());
    return r;
  }
  SymmetryResult RunAlternative(const SymmetryInput& in, const SymmetryResult&) const override {
    if (!second_) return SymmetryResult{};
    Count("symmetry_second");
    SymmetryResult r = Run(in);
    r.score = second_fails_ ? 2.0 : 1.0;
    return r;
  }

 private:
  bool second_, second_fails_;
};

// The embedding as it is; about the second plane (TestSymmetry's), mirrored in x; about a plane
// of score 2, a SolverError.
class TestSymmetrize : public SymmetrizeStage {
 public:
  SymmetrizeResult Run(const SymmetryInput& in, const SymmetryResult& symmetry) const override {
    Count("symmetrize");
    if (symmetry.score == 2.0) throw SolverError("test symmetrize: no solution about this plane");
    SymmetrizeResult r;
    r.Y = in.embedding.Y;
    if (symmetry.score == 1.0) r.Y.col(0) = -r.Y.col(0);
    return r;
  }
};

// Chooses a fixed candidate; needs a per-vertex feature of the embedding, a product.
class TestFlip : public FlipStage {
 public:
  explicit TestFlip(int choose) : choose_(choose) {}
  static ProductKey<Eigen::MatrixXd> FeatureKey() {
    return {"test_feature", "column=" + std::to_string(feature_column)};
  }
  ShapeNeeds Needs() const override {
    ShapeNeeds needs;
    const int column = feature_column;
    needs.products.push_back(NeedProduct(FeatureKey(), ProductInput::kEmbedding, 0,
                                         [column](const ShapeData& shape, const LaplaceBasis&) {
                                           Count("test_feature");
                                           return Eigen::MatrixXd(shape.Y.col(column));
                                         }));
    return needs;
  }
  // The column of Y the feature is (a product's option), the same for every instance.
  static inline int feature_column = 0;
  FlipResult Run(const PairInput& pair) const override {
    Count("flip");
    ProductOf(pair.source, FeatureKey());
    FlipResult r;
    r.chosen = choose_;
    // Lower with the source's second plane, higher with the target's: of the combinations of
    // TestSymmetry's planes, source second / target first scores lowest.
    r.scores.fill(1.0);
    r.scores[choose_] = 1.0 - (pair.source.symmetry.score == 1.0 ? 0.5 : 0.0) +
                        (pair.target.symmetry.score == 1.0 ? 0.25 : 0.0);
    r.status.message = "test flip chose " + std::to_string(choose_);
    return r;
  }

 private:
  int choose_;
};

class TestMatching : public MatchingStage {
 public:
  MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const override {
    Count("matching");
    const Eigen::MatrixX3d& Ys = source.Y;
    const Eigen::MatrixX3d& Yt = target.Y;
    MatchResult r;
    for (int i = 0; i < Ys.rows(); ++i) {
      Eigen::Index best;
      (Yt.rowwise() - Ys.row(i)).rowwise().squaredNorm().minCoeff(&best);
      r.map.push_back(static_cast<int>(best));
    }
    return r;
  }
};

// Keeps the map, or with `mirror` composes it with GridMirror (a refinement that flips).
class TestRefine : public RefineStage {
 public:
  explicit TestRefine(bool mirror) : mirror_(mirror) {}
  MatchResult Run(const RefineInput& input) const override {
    Count("refine");
    MatchResult r;
    r.map = input.initial_map;
    if (mirror_) {
      for (int& t : r.map) t = GridMirror(t);
    }
    return r;
  }

 private:
  bool mirror_;
};

template <typename T, typename... Args>
Registry::Factory Simple(Args... args) {
  return [=](OptionReader&) { return std::unique_ptr<Stage>(new T(args...)); };
}

inline Registry TestRegistry() {
  Registry r;
  r.Add("dataset", "testset", "test grids", [](OptionReader& o) {
    return std::make_unique<TestDataset>(o.GetRequiredString("root"));
  });
  r.Add("preprocess", "test", "identity", Simple<TestPreprocess>());
  r.Add("sampling", "test", "first N", [](OptionReader& o) {
    return std::make_unique<TestSampling>(o.GetInt("count", 10, Range::AtLeast(1)));
  });
  r.Add("geodesics", "test", "euclidean", Simple<TestGeodesics>());
  r.Add("embedding", "test", "scaled input", [](OptionReader& o) {
    return std::make_unique<TestEmbedding>(o.GetDouble("scale", 1.0));
  });
  r.Add("symmetry", "test", "identity", [](OptionReader& o) {
    const bool second = o.GetBool("second", false);
    return std::make_unique<TestSymmetry>(second, o.GetBool("second_fails", false));
  });
  r.Add("symmetrize", "test", "identity", Simple<TestSymmetrize>());
  r.Add("flip", "test", "fixed", [](OptionReader& o) {
    return std::make_unique<TestFlip>(o.GetInt("choose", 0, Range::Closed(0, 3)));
  });
  r.Add("matching", "test", "brute-force NN", Simple<TestMatching>());
  r.Add("refine", "test", "identity or mirror", [](OptionReader& o) {
    return std::make_unique<TestRefine>(o.GetBool("mirror", false));
  });
  return r;
}

// Writes `count` bent 5 x 4 grids and all ordered pairs to root; returns the config text.
inline std::string WriteTestDataset(const std::string& root, int count,
                                    const std::string& variants = "") {
  for (int k = 0; k < count; ++k) {
    Surface s = GridMesh(5, 4);
    for (int i = 0; i < s.NumVertices(); ++i) s.V(i, 2) = 0.1 * k * s.V(i, 0) * s.V(i, 0);
    WriteText(root + "/shapes/s" + std::to_string(k) + ".off", OffText(s));
  }
  std::string pairs;
  for (int a = 0; a < count; ++a) {
    for (int b = 0; b < count; ++b) {
      if (a != b) pairs += "s" + std::to_string(a) + " s" + std::to_string(b) + "\n";
    }
  }
  WriteText(root + "/pairs.txt", pairs);
  return "name: test\n"
         "dataset: {format: testset, root: " + root + "}\n"
         "pipeline:\n"
         "  preprocess: {type: test}\n  sampling: {type: test, count: 6}\n"
         "  geodesics: {type: test}\n  embedding: {type: test}\n  symmetry: {type: test}\n"
         "  symmetrize: {type: test}\n  flip: {type: test}\n  matching: {type: test}\n"
         "  refine: {type: test}\n"
         "evaluation: {geodesics: test}\n" + variants;
}

// Record: source, target, chosen, oracle, the Euclidean mean error on the target input mesh (the
// one value of errors_direct) and the flip stage's message (stage_messages "flip");
// WriteVariant writes summary.txt (each pair's record as SerializePairRecord writes it),
// WriteExperiment comparison.txt.
class TestEvaluation : public RunEvaluation {
 public:
  class Variant : public VariantEvaluation {
   public:
    double MeanError(const PairContext& pair, const std::vector<int>& predicted,
                     double* distance_seconds) const override {
      if (distance_seconds) *distance_seconds = 0.0;
      double sum = 0;
      for (size_t i = 0; i < predicted.size(); ++i) {
        sum += (pair.target.input.V.row(predicted[i]) -
                pair.target.input.V.row(pair.ground_truth.target_ids[i])).norm();
      }
      return predicted.empty() ? 0.0 : sum / predicted.size();
    }
    PairEvaluation Evaluate(const PairContext& pair, const PairOutcome& outcome,
                            std::string* failure) const override {
      std::vector<int> predicted;
      for (int s : pair.ground_truth.source_ids) predicted.push_back(outcome.map[s]);
      PairEvaluation record;
      record.source = pair.source_info.name;
      record.target = pair.target_info.name;
      record.ok = true;
      record.chosen = outcome.flip.chosen;
      record.oracle = outcome.oracle;
      record.errors_direct = {MeanError(pair, predicted, nullptr)};
      record.stage_messages["flip"] = outcome.flip.status.message;
      if (pair.source_info.name == fail_source) *failure = "evaluation refused " + fail_source;
      return record;
    }
    std::string fail_source;
  };

  std::unique_ptr<VariantEvaluation> ForVariant(const Pipeline&) override {
    auto v = std::make_unique<Variant>();
    v->fail_source = fail_source;
    return v;
  }
  // "source target chosen oracle mean | flip message" of a record file's text.
  static std::string RecordBody(const std::string& text) {
    const PairEvaluation record = ParsePairRecord(text);
    const auto flip = record.stage_messages.find("flip");
    std::ostringstream out;
    out.precision(17);
    out << record.source << " " << record.target << " " << record.chosen << " " << record.oracle
        << " " << record.errors_direct.at(0) << " | "
        << (flip == record.stage_messages.end() ? "" : flip->second);
    return out.str();
  }
  void WriteVariant(const VariantResults& results) override {
    if (throw_in_write) throw IoError(results.dir + "/summary.txt: disk full");
    std::string text;
    for (size_t i = 0; i < results.pairs.size(); ++i) {
      text += results.pairs[i].source + "->" + results.pairs[i].target + ": " +
              (results.records[i] ? SerializePairRecord(*results.records[i]) : "failed") + "\n";
    }
    text += "failures " + std::to_string(results.failures.size()) + "\n";
    text += "shapes " + std::to_string(results.shapes.size()) + "\n";
    WriteText(results.dir + "/summary.txt", text);
  }
  void WriteExperiment(const std::string& dir, const std::vector<std::string>& variants) override {
    std::string text;
    for (const auto& v : variants) {
      if (std::filesystem::exists(dir + "/" + v + "/summary.txt")) text += v + "\n";
    }
    WriteText(dir + "/comparison.txt", text);
  }
  std::string fail_source;
  bool throw_in_write = false;  // WriteVariant throws IoError
};

// Runs `count` shards of a run through run(out, shard options), each into tmp/shardI, and
// returns their folders in shard order.
template <typename Run>
std::vector<std::string> RunShards(const TempDir& tmp, int count, Run run,
                                   ShardSplit split = ShardSplit::kPair) {
  std::vector<std::string> outs;
  for (int i = 0; i < count; ++i) {
    RunOptions shard;
    shard.shard_index = i;
    shard.shard_count = count;
    shard.shard_split = split;
    outs.push_back(tmp.File("shard" + std::to_string(i)));
    run(outs.back(), shard);
  }
  return outs;
}

// A run of config_text with the test registry and stages (2 jobs, quiet), and the test stages
// called during it.
struct RunResult {
  RunStats stats;
  std::map<std::string, int> calls;  // test stage calls during the run
};

inline RunResult RunConfig(const std::string& config_text, const std::string& out,
                    const std::string& cache, RunOptions options = {},
                    TestEvaluation* evaluation = nullptr,
                    const std::string& file = "test.yaml") {
  const Registry registry = TestRegistry();
  const ExperimentConfig config = ParseExperimentConfig(config_text, file, registry);
  options.out_dir = out;
  options.cache_dir = cache;
  options.quiet = true;
  options.jobs = 2;
  options.load_mesh = ReadOff;
  TestEvaluation default_evaluation;
  CallCounter::Get().Take();
  RunResult run;
  run.stats =
      RunExperiment(config, registry, options, evaluation ? *evaluation : default_evaluation);
  run.calls = CallCounter::Get().Take();
  return run;
}

}  // namespace symembed::testing::runner
