#include "harness/shape_pipeline.h"

#include <algorithm>
#include <any>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <type_traits>

#include "core/canonical_frame.h"
#include "core/clock.h"
#include "core/errors.h"
#include "core/mesh_graph.h"
#include "core/procrustes.h"
#include "core/spectral.h"
#include "harness/pair_pipeline.h"
#include "registry/hash.h"

namespace symembed {
namespace {

// The overloads of registry/serialize.h, visible beside the local ones below.
using ::symembed::Read;
using ::symembed::Write;

// Part of every key: bump when a stage's cached layout or the key scheme changes.
constexpr char kCacheScheme[] = "symembed-shape-cache-2";

// A cached stage output together with the seconds it took to compute.
template <typename T>
struct Timed {
  T value;
  double seconds = 0.0;
};

struct Distances {
  Eigen::MatrixXd D;  // #S x #V, float precision
};

// Runs step; returns why it failed when it threw what bad data can cause (InvalidInputError,
// SolverError), else "". For optional work whose failure must not fail the shape.
template <typename Step>
std::string FailureOf(Step&& step) {
  try {
    step();
  } catch (const InvalidInputError& e) {
    return e.what();
  } catch (const SolverError& e) {
    return e.what();
  }
  return "";
}

void Write(ArchiveWriter& out, const Distances& d) { out.FloatMatrix(d.D); }
void Read(ArchiveReader& in, Distances* d) { d->D = in.FloatMatrix(); }

// A product in the cache, read and written with its need's functions.
struct StoredProduct {
  const ProductNeed* need = nullptr;
  std::any value;
};

void Write(ArchiveWriter& out, const StoredProduct& p) { p.need->write(out, p.value); }
void Read(ArchiveReader& in, StoredProduct* p) { p->value = p->need->read(in); }

template <typename T>
void Write(ArchiveWriter& out, const Timed<T>& t) {
  Write(out, t.value);
  out.F64(t.seconds);
}

template <typename T>
void Read(ArchiveReader& in, Timed<T>* t) {
  Read(in, &t->value);
  t->seconds = in.F64();
}

// Loads entry `key` of `kind` into `initial`, or computes it with `compute` and stores it.
template <typename T, typename Compute>
T Cached(const ShapeContext& context, const std::string& kind, uint64_t key, Compute compute,
         std::vector<StageTime>* times, T initial = T()) {
  Timed<T> entry{std::move(initial)};
  if (context.cache->Load(kind, key, &entry)) {
    context.counters->Hit(kind);
    times->push_back({kind, entry.seconds, true});
    return std::move(entry.value);
  }
  const auto start = std::chrono::steady_clock::now();
  entry.value = compute();
  entry.seconds = SecondsSince(start);
  context.counters->Executed(kind);
  context.cache->Store(kind, key, entry);
  times->push_back({kind, entry.seconds, false});
  return std::move(entry.value);
}

}  // namespace

void StageCounters::Executed(const std::string& stage) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++executed_[stage];
}

void StageCounters::Hit(const std::string& stage) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++hits_[stage];
}

void StageCounters::Add(const StageCounters& other) {
  const std::map<std::string, int> executed = other.executed(), hits = other.hits();
  std::lock_guard<std::mutex> lock(mutex_);
  for (const auto& [stage, n] : executed) executed_[stage] += n;
  for (const auto& [stage, n] : hits) hits_[stage] += n;
}

std::map<std::string, int> StageCounters::executed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return executed_;
}

std::map<std::string, int> StageCounters::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

namespace {

// A copy of node without the map keys in kOutcomeNeutralKeys, at any depth.
YAML::Node WithoutNeutralKeys(const YAML::Node& node) {
  static const char* const kOutcomeNeutralKeys[] = {"threads"};
  if (!node.IsMap()) return YAML::Clone(node);
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    bool neutral = false;
    for (const char* k : kOutcomeNeutralKeys) neutral = neutral || key == k;
    if (!neutral) out[key] = WithoutNeutralKeys(kv.second);
  }
  return out;
}

}  // namespace

std::string OptionsText(const Stage& stage) {
  YAML::Emitter emitter;
  emitter.SetDoublePrecision(17);
  emitter << WithoutNeutralKeys(stage.resolved_options());
  return emitter.c_str();
}

void InputToKept(const Eigen::MatrixX3d& input_V, const std::vector<int>& input_ids,
                 std::vector<int>* kept_of_input, std::vector<int>* nearest_kept) {
  const int n = static_cast<int>(input_V.rows());
  kept_of_input->assign(n, -1);
  for (int k = 0; k < static_cast<int>(input_ids.size()); ++k) {
    const int v = input_ids[k];
    if (v < 0 || v >= n) {
      throw InvalidInputError("preprocessing returned input id " + std::to_string(v) +
                              " outside [0, " + std::to_string(n) + ")");
    }
    (*kept_of_input)[v] = k;
  }
  *nearest_kept = *kept_of_input;
  if (input_ids.empty()) return;
  // Removed vertices are few (small components, degenerate faces): brute force is enough.
  for (int v = 0; v < n; ++v) {
    if ((*kept_of_input)[v] >= 0) continue;
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < static_cast<int>(input_ids.size()); ++k) {
      const double d = (input_V.row(input_ids[k]) - input_V.row(v)).squaredNorm();
      if (d < best) {
        best = d;
        (*nearest_kept)[v] = k;
      }
    }
  }
}

double SymmetryGroundTruthError(const Eigen::MatrixX3d& Y, const std::vector<int>& ids,
                                const std::vector<int>& sym_ids) {
  SYMEMBED_CHECK(ids.size() == sym_ids.size(), "ground truth lines differ in length");
  const double size = RmsRadius(Y);
  double sum = 0.0;
  int lines = 0;
  for (size_t i = 0; i < ids.size(); ++i) {
    const int a = ids[i], b = sym_ids[i];
    if (a < 0 || b < 0) continue;
    SYMEMBED_CHECK(a < Y.rows() && b < Y.rows(), "ground truth id out of range");
    Eigen::RowVector3d mirrored = Y.row(a);
    mirrored(0) = -mirrored(0);
    sum += (mirrored - Y.row(b)).norm();
    ++lines;
  }
  if (lines == 0 || !(size > 0.0)) return -1.0;
  return sum / lines / size;
}

double GroundTruthGeodesicAsymmetry(const Surface& surface, const std::vector<int>& ids,
                                    const std::vector<int>& sym_ids, int max_lines) {
  SYMEMBED_CHECK(ids.size() == sym_ids.size(), "ground truth lines differ in length");
  const int n = surface.NumVertices();
  std::vector<int> valid;
  for (size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] < 0 || sym_ids[i] < 0) continue;
    SYMEMBED_CHECK(ids[i] < n && sym_ids[i] < n, "ground truth id out of range");
    valid.push_back(static_cast<int>(i));
  }
  if (max_lines < 2 || valid.size() < 2) return -1.0;
  // Evenly spaced lines: the ground truth's own order, whatever it is, decides nothing else.
  const size_t count = std::min(valid.size(), static_cast<size_t>(max_lines));
  std::vector<int> a(count), b(count);
  for (size_t k = 0; k < count; ++k) {
    const int line = valid[k * valid.size() / count];
    a[k] = ids[line];
    b[k] = sym_ids[line];
  }
  const MeshGraph graph = BuildMeshGraph(surface);
  DijkstraWorkspace<double> workspace;
  std::vector<double> from_a(n), from_b(n);
  double sum = 0.0, largest = 0.0;
  long pairs = 0;
  for (size_t i = 0; i < count; ++i) {
    Dijkstra(graph, a[i], from_a.data(), &workspace);
    Dijkstra(graph, b[i], from_b.data(), &workspace);
    for (size_t j = i + 1; j < count; ++j) {
      const double da = from_a[a[j]], db = from_b[b[j]];
      if (!std::isfinite(da) || !std::isfinite(db)) continue;
      sum += std::abs(da - db);
      largest = std::max(largest, da);
      ++pairs;
    }
  }
  if (pairs == 0 || !(largest > 0.0)) return -1.0;
  return sum / pairs / largest;
}

double SelfMapDisplacement(const ShapeData& data) {
  const Eigen::MatrixXd& Y = data.embedding.Y;
  if (data.symmetry.sigma.size() != data.samples.size()) return -1.0;
  Eigen::MatrixXd P(data.samples.size(), Y.cols());
  for (size_t i = 0; i < data.samples.size(); ++i) P.row(i) = Y.row(data.samples[i]);
  return SelfMapDisplacement(P, data.symmetry.sigma);
}

double CanonicalXSpread(const Eigen::MatrixX3d& Y) {
  if (Y.rows() < 2) return -1.0;
  const Eigen::RowVector3d sd =
      ((Y.rowwise() - Y.colwise().mean()).colwise().squaredNorm() / (Y.rows() - 1)).cwiseSqrt();
  const double other = std::min(sd(1), sd(2));
  return other > 0.0 ? sd(0) / other : -1.0;
}

namespace {

// The per-shape measures of shapes.csv that depend only on the mesh content: what the sampling,
// embedding, symmetry, symmetrize and canonical-frame stages report.
void AddShapeMeasures(const SamplingResult& sampling, const SymmetrizeResult& symmetrized,
                      double axis_ratio, const ShapeData& data, ShapeOutcome* out) {
  out->report.push_back({"samples", static_cast<double>(data.samples.size())});
  out->report.push_back({"coverage_radius", sampling.coverage_radius});
  out->report.push_back({"normalized_stress", data.embedding.normalized_stress});
  out->report.push_back({"reflection", static_cast<double>(data.embedding.reflection)});
  out->report.push_back({"symmetry_score", data.symmetry.score});
  out->report.push_back({"asymmetry_before", symmetrized.asymmetry_before});
  out->report.push_back({"asymmetry_after", symmetrized.asymmetry_after});
  out->report.push_back(
      {"symmetrize_iterations", static_cast<double>(symmetrized.status.iterations)});
  out->report.push_back({"frame_axis_ratio", axis_ratio});
  out->report.push_back({"self_map_displacement", SelfMapDisplacement(data)});
  out->report.push_back({"canonical_x_spread", CanonicalXSpread(data.Y)});
}

// The per-shape measures of shapes.csv against a shape's symmetric ground truth (none without
// one): the error of the symmetric embedding, and the asymmetry of the surface's own geodesics.
Report GroundTruthMeasures(const ShapeOutcome& out) {
  Report report;
  if (out.ground_truth.sym_ids.empty()) return report;
  // The shape's lines against themselves: target_sym_ids are the symmetric partners, in
  // preprocessed ids like the pairs' ground truth (lines of removed vertices dropped).
  const PreprocessedGroundTruth self =
      ToPreprocessedIds(PairLines(out.ground_truth, out.ground_truth), out, out);
  const ShapeData& data = *out.data;
  const double error = SymmetryGroundTruthError(data.Y, self.source_ids, self.target_sym_ids);
  if (error >= 0.0) report.push_back({"symmetry_gt_error", error});
  const double asymmetry =
      GroundTruthGeodesicAsymmetry(data.surface, self.source_ids, self.target_sym_ids);
  if (asymmetry >= 0.0) report.push_back({"gt_geodesic_asymmetry", asymmetry});
  return report;
}

// The cache keys of what a product can be computed from (ProductInput).
struct InputKeys {
  uint64_t surface = 0;    // preprocess
  uint64_t samples = 0;    // sampling
  uint64_t embedding = 0;  // the last per-shape stage: the canonical embedding follows from all
};

uint64_t BasisKey(uint64_t surface_key, const LaplaceBasisOptions& options) {
  return Hasher(surface_key)
      .AddString("laplace_basis")
      .AddU64(static_cast<uint64_t>(options.k))
      .AddU64(static_cast<uint64_t>(options.mass))
      .AddBytes(&options.tolerance, sizeof(options.tolerance))
      .AddU64(static_cast<uint64_t>(options.max_iterations))
      .Digest();
}

// Computes (or loads) what the per-pair stages declare they need (PairStage::Needs) into
// data->basis and data->products: the basis of the most eigenpairs any stage reads, each
// product keyed by its input's key and its id, and a smaller basis only when a product missing
// from the cache is computed from it. Returns the shape's key for the pair cache: the embedding's
// key and the key of everything the stages read.
uint64_t PrepareNeeds(const Pipeline& pipeline, const ShapeContext& context, const InputKeys& keys,
                      ShapeData* data, ShapeOutcome* out) {
  ShapeNeeds needs;
  Pipeline::ForEachStage(pipeline, [&](const char*, const auto& member) {
    using T = typename std::decay_t<decltype(member)>::element_type;
    if constexpr (std::is_base_of_v<PairStage, T>) needs.Add(member->Needs());
  });
  auto options_of = [](int k) {
    LaplaceBasisOptions options;
    options.k = k;
    return options;
  };
  std::map<int, LaplaceBasis> bases;  // by eigenpairs
  auto basis = [&](int k) -> const LaplaceBasis& {
    auto it = bases.find(k);
    if (it == bases.end()) {
      LaplaceBasis b = Cached<LaplaceBasis>(
          context, "laplace_basis", BasisKey(keys.surface, options_of(k)),
          [&] { return ComputeLaplaceBasis(data->surface, options_of(k)); }, &out->times);
      it = bases.emplace(k, std::move(b)).first;
    }
    return it->second;
  };
  Hasher pair_key(keys.embedding);
  if (needs.basis > 0) {
    data->basis = basis(needs.basis);
    pair_key.AddU64(BasisKey(keys.surface, options_of(needs.basis)));
  }
  static const LaplaceBasis kNoBasis;
  for (const ProductNeed& need : needs.products) {
    uint64_t input_key = keys.surface;
    if (need.input == ProductInput::kSamples) input_key = keys.samples;
    if (need.input == ProductInput::kEmbedding) input_key = keys.embedding;
    if (need.input == ProductInput::kBasis) {
      input_key = BasisKey(keys.surface, options_of(need.basis_size));
    }
    const uint64_t key = Hasher(input_key).AddString(need.id).Digest();
    pair_key.AddU64(key);
    StoredProduct stored = Cached<StoredProduct>(
        context, need.name, key,
        [&] {
          const LaplaceBasis& b =
              need.input == ProductInput::kBasis ? basis(need.basis_size) : kNoBasis;
          return StoredProduct{&need, need.compute(*data, b)};
        },
        &out->times, StoredProduct{&need, {}});
    data->products.PutAny(need.id, std::make_shared<const std::any>(std::move(stored.value)));
  }
  return pair_key.Digest();
}

}  // namespace

ShapeStageKeys::ShapeStageKeys(uint64_t mesh_key, const Pipeline& pipeline) {
  uint64_t previous = mesh_key;
  for (const StageKind& kind : kPipelineStageKinds) {
    if (kind.scope != StageScope::kShape) continue;
    previous = Hasher(previous)
                   .AddString(kind.name)
                   .AddString(OptionsText(pipeline.StageOf(kind.name)))
                   .Digest();
    keys_.emplace_back(kind.name, previous);
  }
  SYMEMBED_CHECK(!keys_.empty(), "the stage-kind table has no per-shape kind");
}

uint64_t ShapeStageKeys::Of(const std::string& kind) const {
  for (const auto& [name, key] : keys_) {
    if (name == kind) return key;
  }
  SYMEMBED_CHECK(false, "'" << kind << "' is not a per-shape kind");
  return 0;
}

uint64_t MeshKey(const std::string& mesh_path) {
  const std::string extension = std::filesystem::path(mesh_path).extension().string();
  return Hasher().AddString(kCacheScheme).AddString(extension).AddU64(HashFile(mesh_path)).Digest();
}

uint64_t SurfaceMeshKey(const Surface& surface) {
  Hasher hasher;
  hasher.AddString(kCacheScheme).AddString("arrays");
  hasher.AddU64(static_cast<uint64_t>(surface.V.rows()))
      .AddU64(static_cast<uint64_t>(surface.F.rows()));
  for (Eigen::Index i = 0; i < surface.V.rows(); ++i) {
    for (int j = 0; j < 3; ++j) {
      const double x = surface.V(i, j);
      uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      hasher.AddU64(bits);
    }
  }
  for (Eigen::Index i = 0; i < surface.F.rows(); ++i) {
    for (int j = 0; j < 3; ++j) {
      hasher.AddU64(static_cast<uint64_t>(static_cast<int64_t>(surface.F(i, j))));
    }
  }
  return hasher.Digest();
}

namespace {

// The per-shape kind from which the chain runs again for the second plane hypothesis.
constexpr const char* kSecondPlaneFrom = "symmetry";

// The key of the second plane's output of a kind: the first plane's key, marked.
uint64_t SecondPlaneKey(uint64_t key) { return Hasher(key).AddString("second plane").Digest(); }

// What the per-shape chain has computed of one mesh: each kind's step (RunShapeStep) reads what
// the steps before it wrote and adds its kind's output, cached under the kind's key.
struct ShapeChain {
  ShapeChain(const ShapeContext& context, const ShapeStageKeys& keys, ShapeOutcome& out,
             ShapeData& data)
      : context(context), keys(keys), out(out), data(data) {}

  const ShapeContext& context;
  const ShapeStageKeys& keys;
  ShapeOutcome& out;
  ShapeData& data;
  SamplingResult sampling;
  std::optional<SymmetrizeResult> symmetrized;
  // The geodesic distances: set by the geodesics step, loaded or computed by the first step that
  // reads them (D), released when the chain is done.
  std::function<Distances()> require_distances;
  std::unique_ptr<Distances> distances;
  // On the second plane's branch (the kinds from kSecondPlaneFrom on, run again): the chain of
  // the first plane, whose distances it reads and whose plane its symmetry step proposes an
  // alternative to. The branch's outputs are named "<kind>_second" and keyed apart.
  ShapeChain* first = nullptr;

  const Eigen::MatrixXd& D() {
    if (first != nullptr) return first->D();
    if (!distances) distances = std::make_unique<Distances>(require_distances());
    return distances->D;
  }
  std::string Name(const std::string& kind) const { return first ? kind + "_second" : kind; }
  uint64_t Key(const std::string& kind) const {
    return first ? SecondPlaneKey(keys.Of(kind)) : keys.Of(kind);
  }
  // Loads entry Key(kind) of Name(kind) or computes it with `compute`, timed in out.times.
  template <typename T, typename Compute>
  T Cached(const std::string& kind, Compute compute) {
    return ::symembed::Cached<T>(context, Name(kind), Key(kind), compute, &out.times);
  }
  SymmetryInput ForSymmetry() { return {data.surface, data.samples, D(), data.embedding}; }
};

// One overload per per-shape kind's interface: ComputeMeshOutcome calls them in the order of the
// stage-kind table, so a per-shape kind without its step does not compile.
void RunShapeStep(const std::string& kind, const PreprocessStage& stage, ShapeChain& chain) {
  const PreprocessResult pre =
      chain.Cached<PreprocessResult>(kind, [&] { return stage.Run(chain.out.input); });
  chain.data.surface = pre.surface;
  chain.data.input_ids = pre.input_ids;
  chain.data.scale = pre.scale;
  chain.out.report = pre.report;
  InputToKept(chain.out.input.V, chain.data.input_ids, &chain.out.kept_of_input,
              &chain.out.nearest_kept);
}

void RunShapeStep(const std::string& kind, const SamplingStage& stage, ShapeChain& chain) {
  chain.sampling =
      chain.Cached<SamplingResult>(kind, [&] { return stage.Run(chain.data.surface); });
  chain.data.samples = chain.sampling.samples;
}

// D is loaded or computed only when a stage that reads it has to run.
void RunShapeStep(const std::string& kind, const GeodesicsStage& stage, ShapeChain& chain) {
  chain.require_distances = [kind, &stage, &chain] {
    return chain.Cached<Distances>(kind, [&] {
      auto solver = stage.Prepare(chain.data.surface);
      Distances d{solver->Distances(chain.data.samples)};
      d.D = d.D.cast<float>().cast<double>();
      return d;
    });
  };
}

void RunShapeStep(const std::string& kind, const EmbeddingStage& stage, ShapeChain& chain) {
  chain.data.embedding = chain.Cached<EmbeddingResult>(kind, [&] {
    return stage.Run(EmbeddingInput{chain.data.surface, chain.data.samples, chain.D()});
  });
}

// On the second plane's branch: the stage's alternative to the first plane (no self map: none).
void RunShapeStep(const std::string& kind, const SymmetryStage& stage, ShapeChain& chain) {
  chain.data.symmetry = chain.Cached<SymmetryResult>(kind, [&] {
    return chain.first ? stage.RunAlternative(chain.ForSymmetry(), chain.first->data.symmetry)
                       : stage.Run(chain.ForSymmetry());
  });
}

// A second plane without a self map is no hypothesis: nothing to symmetrize.
void RunShapeStep(const std::string& kind, const SymmetrizeStage& stage, ShapeChain& chain) {
  if (chain.first && chain.data.symmetry.sigma.empty()) return;
  chain.symmetrized = chain.Cached<SymmetrizeResult>(
      kind, [&] { return stage.Run(chain.ForSymmetry(), chain.data.symmetry); });
}

}  // namespace

ShapeOutcome ComputeMeshOutcome(Surface input, double load_seconds, uint64_t mesh_key,
                                const Pipeline& pipeline, const ShapeContext& context) {
  ShapeOutcome out;
  out.input = std::move(input);
  out.times.push_back({"load", load_seconds, false});

  const ShapeStageKeys keys(mesh_key, pipeline);
  out.surface_key = keys.Of("preprocess");
  auto data = std::make_shared<ShapeData>();
  ShapeChain chain(context, keys, out, *data);
  // Runs the per-shape kinds on `on`, those before kSecondPlaneFrom only when `all`.
  auto run_shape_kinds = [&](ShapeChain& on, bool all) {
    Pipeline::ForEachStage(pipeline, [&](const char* kind, const auto& stage) {
      using T = typename std::decay_t<decltype(stage)>::element_type;
      all = all || std::strcmp(kind, kSecondPlaneFrom) == 0;
      if constexpr (!std::is_base_of_v<PairStage, T>) {
        if (all) RunShapeStep(kind, *stage, on);
      }
    });
  };
  run_shape_kinds(chain, true);
  const SamplingResult& sampling = chain.sampling;
  const SymmetrizeResult& symmetrized = *chain.symmetrized;

  // The second plane is a hypothesis beside a plane that worked: when its search or its
  // symmetrization fails on this shape, the shape goes on with the first plane alone.
  ShapeData second_data = *data;
  ShapeChain second(context, keys, out, second_data);
  second.first = &chain;
  std::string second_failure = FailureOf([&] { run_shape_kinds(second, false); });
  chain.distances.reset();
  data->symmetry.detection.reset();
  second_data.symmetry.detection.reset();

  const auto start = std::chrono::steady_clock::now();
  double axis_ratio = 0.0;
  data->Y = CanonicalFrame(symmetrized.Y, nullptr, nullptr, &axis_ratio);
  out.times.push_back({"canonical_frame", SecondsSince(start), false});

  AddShapeMeasures(sampling, symmetrized, axis_ratio, *data, &out);

  const uint64_t pre_key = keys.Of("preprocess"), samp_key = keys.Of("sampling");
  // The canonical embedding follows from every per-shape stage: the last key of the chain.
  out.key = PrepareNeeds(pipeline, context, {pre_key, samp_key, keys.Last()}, data.get(), &out);
  if (second.symmetrized && second_failure.empty()) {
    second_failure = FailureOf([&] {
      auto alternative = std::make_shared<ShapeData>(*data);
      alternative->symmetry = second_data.symmetry;
      alternative->Y = CanonicalFrame(second.symmetrized->Y, nullptr, nullptr, nullptr);
      const uint64_t alt_key =
          PrepareNeeds(pipeline, context, {pre_key, samp_key, SecondPlaneKey(keys.Last())},
                       alternative.get(), &out);
      out.key = Hasher(out.key).AddU64(alt_key).Digest();
      out.alternative = std::move(alternative);
    });
  }
  if (!second_failure.empty()) {
    out.warnings.push_back(
        "second plane hypothesis dropped (the shape goes on with its first plane): " +
        second_failure);
  }
  // Last: OutcomeOfShape puts the ground-truth measures before it.
  out.report.push_back(
      {"second_plane", !second_failure.empty() ? -1.0 : (out.alternative ? 1.0 : 0.0)});
  out.data = std::move(data);
  return out;
}

ShapeOutcome OutcomeOfShape(ShapeOutcome content, const DatasetShape& shape, ShapeGroundTruth truth,
                            bool reused) {
  SYMEMBED_CHECK(
      content.data && !content.report.empty() && content.report.back().first == "second_plane",
      "not an outcome of ComputeMeshOutcome");
  ShapeOutcome out = std::move(content);
  out.name = shape.name;
  out.ground_truth = std::move(truth);
  // The per-pair stages name the shape through its data: an outcome of another name keeps its
  // own copy.
  for (std::shared_ptr<ShapeData>* data : {&out.data, &out.alternative}) {
    if (!*data) continue;
    if (data->use_count() > 1) *data = std::make_shared<ShapeData>(**data);
    (*data)->name = shape.name;
  }
  // Where a single computation of the shape put them, so that shapes.csv's columns keep their
  // order.
  const Report measures = GroundTruthMeasures(out);
  out.report.insert(out.report.end() - 1, measures.begin(), measures.end());
  if (reused) {
    for (StageTime& time : out.times) time.cached = true;
  }
  return out;
}

}  // namespace symembed
