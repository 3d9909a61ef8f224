// The refine stages: thin adapters around ZoomOut, DiscreteOpt and FunctionalMapIcp. Each declares
// the Laplace-Beltrami basis it reads (Needs), which the runner computes once per shape
// (ShapeData::basis, shared with the flip stage).
#include "stages/register.h"

#include <memory>
#include <string>

#include "core/fmap/functional_map.h"
#include "core/fmap/partial_zoomout.h"
#include "core/fmap/zoomout.h"
#include "core/spectral.h"
#include "stages/products.h"
#include "stages/refine/discrete_opt.h"
#include "stages/refine/fmap_icp.h"

namespace symembed {

namespace {

// The first k eigenpairs of the shape's basis when it holds enough, else computed here
// (*computed set) so that a stage run without its needs (ComputeNeeds) still gets a result.
LaplaceBasis RefineBasis(const ShapeData& shape, int k, bool* computed) {
  if (shape.basis.NumEigenpairs() >= k &&
      shape.basis.NumVertices() == shape.surface.NumVertices()) {
    return LeadingEigenpairs(shape.basis, k);
  }
  *computed = true;
  LaplaceBasisOptions options;
  options.k = k;
  return ComputeLaplaceBasis(shape.surface, options);
}

// Both shapes' first k eigenpairs, and whether either had to be computed per pair.
struct PairBases {
  PairBases(const PairInput& pair, int k)
      : source(RefineBasis(pair.source, k, &computed)),
        target(RefineBasis(pair.target, k, &computed)) {}

  // Appended to the stage's status message.
  std::string Note() const {
    return computed ? " (basis computed per pair: the shape lacks the stage's needs)" : "";
  }

  bool computed = false;
  LaplaceBasis source;
  LaplaceBasis target;
};

ShapeNeeds BasisNeeds(int k) {
  ShapeNeeds needs;
  needs.basis = k;
  return needs;
}

// `count` vertices with area: the prefix of the shape's farthest-point samples when there are
// enough of them, else Euclidean farthest points; none (every vertex) when count is 0 or not
// less than the vertex count.
std::vector<int> Samples(const ShapeData& shape, const LaplaceBasis& basis, int count) {
  const int n = shape.surface.NumVertices();
  if (count == 0 || count >= n) return {};
  std::vector<bool> keep(n);
  for (int i = 0; i < n; ++i) keep[i] = basis.mass(i) > 0.0;
  std::vector<int> prefix;
  for (int id : shape.samples) {
    if (static_cast<int>(prefix.size()) == count) break;
    if (id >= 0 && id < n && keep[id]) prefix.push_back(id);
  }
  if (static_cast<int>(prefix.size()) == count) return prefix;
  return EuclideanFarthestPoints(shape.surface.V, count, keep);
}

// A part and a whole matched on the surfaces: ZoomOut with rectangular maps whose part's
// size follows the whole's by eigenvalue (core/fmap/partial_zoomout.h), on the stage's schedule
// of basis sizes (`schedule`'s k_start, k_end, step), iterating on `samples` onto
// `target_samples` (empty: every vertex), each point anchored to its start's image on the
// whole's surface with `anchor_weight` (0: free).
template <typename Schedule>
MatchResult RefinePart(const RefineInput& input, const PairBases& bases, const Schedule& schedule,
                       const std::vector<int>& samples, const std::vector<int>& target_samples,
                       double anchor_weight = 0.0) {
  ZoomOutOptions options;
  options.k_start = schedule.k_start;
  options.k_end = schedule.k_end;
  options.step = schedule.step;
  const PairInput& pair = input.pair;
  const PartialAnchor anchor{&pair.target.surface.V, anchor_weight};
  ZoomOutResult z =
      PartialZoomOut(bases.source, 1.0 / pair.source.scale, bases.target, 1.0 / pair.target.scale,
                     input.initial_map, samples, options, target_samples, anchor);
  z.status.message += bases.Note();
  return MatchResult{std::move(z.map), std::move(z.status)};
}

class NoRefine : public RefineStage {
 public:
  MatchResult Run(const RefineInput& input) const override {
    const PairInput& pair = input.pair;
    const std::vector<int>& initial_map = input.initial_map;
    CheckPointMap(initial_map, pair.source.surface.NumVertices(),
                  pair.target.surface.NumVertices());
    MatchResult result;
    result.map = initial_map;
    result.status.message = "no refinement";
    return result;
  }
};

class ZoomOutRefine : public RefineStage {
 public:
  ZoomOutRefine(const ZoomOutOptions& options, int sample_count, int target_sample_count)
      : options_(options), sample_count_(sample_count), target_sample_count_(target_sample_count) {}

  ShapeNeeds Needs() const override { return BasisNeeds(options_.k_end); }

  MatchResult Run(const RefineInput& input) const override {
    const PairBases bases(input.pair, options_.k_end);
    const std::vector<int> samples = Samples(input.pair.source, bases.source, sample_count_);
    // Target samples only go with source samples (the dense variant maps onto every vertex).
    const std::vector<int> target_samples =
        samples.empty() ? std::vector<int>{}
                        : Samples(input.pair.target, bases.target, target_sample_count_);
    if (input.part_and_whole) {
      return RefinePart(input, bases, options_, samples, target_samples);
    }
    ZoomOutResult z =
        ZoomOut(bases.source, bases.target, input.initial_map, samples, options_, target_samples);
    z.status.message += bases.Note();
    return MatchResult{std::move(z.map), std::move(z.status)};
  }

 private:
  ZoomOutOptions options_;
  int sample_count_;
  int target_sample_count_;
};

class IcpRefine : public RefineStage {
 public:
  explicit IcpRefine(const FunctionalMapIcpOptions& options) : options_(options) {}

  ShapeNeeds Needs() const override { return BasisNeeds(options_.k); }

  MatchResult Run(const RefineInput& input) const override {
    if (input.part_and_whole) {
      MatchResult unchanged{input.initial_map, {}};
      unchanged.status.message = "not run: the map is between a part and a whole";
      return unchanged;
    }
    const PairBases bases(input.pair, options_.k);
    FunctionalMapIcpResult r =
        FunctionalMapIcp(bases.source, bases.target, input.initial_map, options_);
    r.status.message += bases.Note();
    return MatchResult{std::move(r.map), std::move(r.status)};
  }

 private:
  FunctionalMapIcpOptions options_;
};

class DiscreteRefine : public RefineStage {
 public:
  DiscreteRefine(const DiscreteOptOptions& options, int sample_count)
      : options_(options), sample_count_(sample_count) {}

  // The basis, and the descriptor term's products, which depend on the shape alone.
  ShapeNeeds Needs() const override {
    ShapeNeeds needs = BasisNeeds(options_.k_end);
    if (options_.weights.descriptor > 0.0) {
      const int k_end = options_.k_end;
      needs.products.push_back(NeedProduct(
          ProductsKey(), ProductInput::kBasis, k_end,
          [k_end](const ShapeData&, const LaplaceBasis& basis) {
            return DiscreteWksProducts(basis, k_end);
          }));
    }
    return needs;
  }

  MatchResult Run(const RefineInput& input) const override {
    const PairInput& pair = input.pair;
    const PairBases bases(pair, options_.k_end);
    std::vector<int> samples, target_samples;
    if (sample_count_ > 0) {
      samples = SamplesOrAll(pair.source, bases.source);
      target_samples = SamplesOrAll(pair.target, bases.target);
    }
    // The discrete terms ask for a bijection, which a part and a whole have not.
    if (input.part_and_whole) {
      return RefinePart(input, bases, options_, samples, target_samples,
                        options_.weights.embedding);
    }
    // The embedding term reads the points the matching stage compared; a map refined without
    // them (from elsewhere) goes without the term, and the message says so.
    DiscreteOptOptions options = options_;
    DiscreteOptPoints points;
    const bool embedded = input.source_points != nullptr && input.target_points != nullptr;
    if (embedded) points = {input.source_points->Y, input.target_points->Y};
    if (!embedded) options.weights.embedding = 0.0;
    DiscreteOptResult r =
        DiscreteOpt(bases.source, bases.target, input.initial_map, samples, target_samples, options,
                    pair.source.products.Find(ProductsKey()),
                    pair.target.products.Find(ProductsKey()), embedded ? &points : nullptr);
    r.status.message += bases.Note();
    if (!embedded && options_.weights.embedding > 0.0) {
      r.status.message += " (embedding term off: no embedded points)";
    }
    return MatchResult{std::move(r.map), std::move(r.status)};
  }

 private:
  ProductKey<WksProducts> ProductsKey() const {
    return {"discrete_descriptor_products", "k_end=" + std::to_string(options_.k_end)};
  }

  // Samples of a shape, or every vertex with area when it has no more than sample_count_.
  std::vector<int> SamplesOrAll(const ShapeData& shape, const LaplaceBasis& basis) const {
    std::vector<int> ids = Samples(shape, basis, sample_count_);
    return ids.empty() ? MatchableTargets(basis.mass) : ids;
  }

  DiscreteOptOptions options_;
  int sample_count_;
};

// A sample must determine k_end coefficients.
void CheckSampleCount(OptionReader& reader, const std::string& key, int count, int k_end) {
  if (count > 0 && count < k_end) {
    reader.Fail(key, "must be 0 (every vertex) or >= k_end (" + std::to_string(k_end) + "), got " +
                         std::to_string(count));
  }
}

// Samples of each shape the zoomout stage iterates on unless the config says otherwise (k_end is
// at most 1,000, so they determine the last functional map).
constexpr int kDefaultSamples = 1000;

// Weight of the discrete stage's embedding term (DiscreteOptWeights::embedding, whose default 0
// suits callers without embedded points).
constexpr double kDefaultEmbeddingWeight = 100.0;

}  // namespace

void RegisterRefineStages(Registry& registry) {
  registry.Add(
      "refine", "none", "no refinement: the matching stage's map unchanged",
      [](OptionReader&) -> std::unique_ptr<Stage> { return std::make_unique<NoRefine>(); });
  registry.Add(
      "refine", "zoomout",
      "ZoomOut spectral upsampling of the map [Melzi et al. 2019], Laplace-Beltrami basis by "
      "Spectra",
      [](OptionReader& reader) -> std::unique_ptr<Stage> {
        ZoomOutOptions options;
        ReadFields(reader, &options);
        // By default ZoomOut also runs from k = 5, 10 and 15 and keeps the run with the lowest
        // residual: a single start at k_start leaves regions that the initial map sends to the
        // wrong part of the target where they are, and which start recovers them depends on the
        // pair. The sizes that would repeat k_start or exceed k_end are left out.
        std::vector<int> default_starts;
        for (int k : {5, 10, 15}) {
          if (k != options.k_start && k <= options.k_end) default_starts.push_back(k);
        }
        options.extra_k_starts =
            reader.GetIntList("extra_k_starts", default_starts, ZoomOutOptions::kKStart);
        // The iterations on 1,000 farthest-point samples of each shape, then one dense query:
        // the runs from several starts cost less together than one dense run.
        const int sample_count = reader.GetInt("sample_count", kDefaultSamples, Range::AtLeast(0));
        const int target_sample_count = reader.GetInt(
            "target_sample_count", sample_count == 0 ? 0 : kDefaultSamples, Range::AtLeast(0));
        RequireValid(reader, options);
        CheckSampleCount(reader, "sample_count", sample_count, options.k_end);
        CheckSampleCount(reader, "target_sample_count", target_sample_count, options.k_end);
        if (target_sample_count > 0 && sample_count == 0) {
          reader.Fail("target_sample_count",
                      "needs sample_count (the dense variant maps onto every target vertex)");
        }
        return std::make_unique<ZoomOutRefine>(options, sample_count, target_sample_count);
      });
  registry.Add(
      "refine", "discrete",
      "discrete optimisation of point and functional maps in both directions (orthogonality, "
      "bijectivity, properness, Laplacian commutativity, descriptors) grown over basis sizes "
      "[Ren et al. 2021]",
      [](OptionReader& reader) -> std::unique_ptr<Stage> {
        DiscreteOptOptions options;
        ReadFields(reader, &options);
        options.sample_candidates =
            reader.GetChoice("candidates", "samples", {"samples", "vertices"}) == "samples";
        OptionReader w = reader.Child("weights");
        // The stage anchors the map to the matching stage's aligned embeddings by default:
        // on a pair that is far from isometric the spectral terms alone move whole regions
        // away from where the embedding put them. The embedding is in units of the unit-area
        // surface: at weight 100 a point 0.1 away from its image costs 1, a unit of each
        // spectral term (whose eigenfunctions have unit norm).
        options.weights.embedding = kDefaultEmbeddingWeight;
        ReadFields(w, &options.weights);
        w.Finish();
        reader.AdoptChild("weights", w);
        const int sample_count = reader.GetInt("sample_count", kDefaultSamples, Range::AtLeast(0));
        RequireValid(reader, options);
        CheckSampleCount(reader, "sample_count", sample_count, options.k_end);
        return std::make_unique<DiscreteRefine>(options, sample_count);
      });
  registry.Add("refine", "icp",
               "functional-map ICP at a fixed basis size [Ovsjanikov et al. 2012] (baseline)",
               FieldsFactory<IcpRefine, FunctionalMapIcpOptions>());
}

}  // namespace symembed
