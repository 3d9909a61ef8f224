// Per-shape work of one variant (docs/design.md, "Data flow"): load -> the per-shape kinds of
// the stage-kind table in its order (preprocess -> sampling -> geodesics -> embedding ->
// symmetry -> symmetrize) -> the second plane hypothesis -> canonical frame -> ShapeData, then
// what the per-pair stages (flip, matching, refine) declare they need of the shape
// (PairStage::Needs: a Laplace-Beltrami basis, products; registry/product_needs.h).
//
// The work is done once per mesh content, not per name: ComputeMeshOutcome runs the stages on a
// loaded mesh, and OutcomeOfShape gives each dataset shape whose file has those bytes its own
// outcome (its name, its ground truth and the measures against it). A mesh under several names
// (a symlink, a copy) is therefore computed once.
//
// Every stage output is cached on disk under a chained key: H(mesh bytes, file extension), then
// for each per-shape kind of the stage-kind table (registry/stage_kinds.h), in its order,
// H(previous key, kind, resolved options as YAML text) (ShapeStageKeys). A variant that changes
// only a later stage therefore finds every earlier output in the cache. A basis is keyed by the
// preprocess key and its options, a product by the key of its declared input (surface, samples,
// embedding or basis) and its id, so a product is shared by every stage and variant that declares
// it from the same input: a changed flip scorer keeps the refine stage's basis, a changed
// embedding keeps the curvature features.
//
// Geodesic distances (#S x #V) are cached as 32-bit floats (half the disk: ~20 MB per 5k-vertex
// shape with 1,000 samples) and rounded to float precision also when computed, so a cold and a
// warm run give identical results. D is only read or computed when the embedding, symmetry or
// symmetrize output is missing, and it is released when the shape is done.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "harness/cache.h"
#include "harness/config.h"
#include "registry/dataset.h"
#include "registry/types.h"

namespace symembed {

// Thread-safe counts of stage executions (cache misses) and cache hits, by stage name
// ("preprocess", ..., "geodesics", "laplace_basis", a product's name, "flip", "matching", "refine", "oracle").
class StageCounters {
 public:
  void Executed(const std::string& stage);
  void Hit(const std::string& stage);
  // Adds other's counts to these.
  void Add(const StageCounters& other);
  std::map<std::string, int> executed() const;
  std::map<std::string, int> hits() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, int> executed_, hits_;
};

using MeshLoader = std::function<Surface(const std::string& path)>;

// Seconds per stage, in pipeline order. For a cache hit it is the time of the computation that
// filled the entry (so timings do not depend on the cache); `cached` says which were hits.
struct StageTime {
  std::string stage;
  double seconds = 0.0;
  bool cached = false;
};

struct ShapeOutcome {
  std::string name;
  Surface input;                      // as loaded, input vertex ids
  std::shared_ptr<ShapeData> data;    // with what the per-pair stages need (basis, products)
  // The shape under the symmetry stage's second plane hypothesis (SymmetryStage::RunAlternative),
  // or null: each pair takes whichever of data and alternative its flip stage scores better.
  std::shared_ptr<ShapeData> alternative;
  std::vector<int> kept_of_input;     // #V_input: preprocessed id of each input vertex, -1: removed
  std::vector<int> nearest_kept;      // #V_input: preprocessed id of the nearest kept vertex
  ShapeGroundTruth ground_truth;      // input ids (empty when the dataset has none)
  std::vector<StageTime> times;
  Report report;                      // preprocess report, then stage measures
  // What went wrong without failing the shape (a second plane hypothesis dropped), one line each.
  std::vector<std::string> warnings;
  uint64_t key = 0;  // cache key of `data` and `alternative` (all stages, basis and products)
  // Cache key of the preprocessed surface: the mesh file's content and the preprocessing
  // options, so equal keys mean the same input and preprocessed surfaces (0: not computed).
  uint64_t surface_key = 0;
};

struct ShapeContext {
  const DiskCache* cache = nullptr;
  StageCounters* counters = nullptr;
};

// The content key of a mesh file, the root of every per-shape cache key: H(key scheme, file
// extension, the file's bytes). Files with equal keys have equal per-shape outputs whatever the
// shapes' names. Throws IoError when the file cannot be read.
uint64_t MeshKey(const std::string& mesh_path);

// The cache keys of the per-shape stages' outputs: from a MeshKey, for each per-shape kind of
// kPipelineStageKinds (registry/stage_kinds.h) in its order, H(previous key, kind, OptionsText of
// the pipeline's stage of that kind). A kind enters the chain by being a row of the table.
class ShapeStageKeys {
 public:
  ShapeStageKeys(uint64_t mesh_key, const Pipeline& pipeline);
  // The key of a per-shape kind's output ("preprocess", ...); a programming error (Check) for
  // any other name.
  uint64_t Of(const std::string& kind) const;
  // The key of the last per-shape kind's output: every per-shape stage's options are in it.
  uint64_t Last() const { return keys_.back().second; }

 private:
  std::vector<std::pair<std::string, uint64_t>> keys_;  // per-shape kind, key; table order
};

// The content key of a mesh given as arrays instead of a file (the Python module): H(key
// scheme, "arrays", #V, #F, the coordinates and ids row by row). A file's MeshKey hashes its
// bytes, so the same mesh read from a file and passed as arrays is cached under two keys.
uint64_t SurfaceMeshKey(const Surface& surface);

// Runs or loads every per-shape stage of `pipeline` on `input`, the mesh of a file whose MeshKey
// is mesh_key, loaded in load_seconds (the first time entry). The outcome has no name and no
// ground truth: it is what every dataset shape with that file content shares (OutcomeOfShape).
// Throws what a stage throws (InvalidInputError, SolverError, ...): the caller records it.
ShapeOutcome ComputeMeshOutcome(Surface input, double load_seconds, uint64_t mesh_key,
                                const Pipeline& pipeline, const ShapeContext& context);

// The outcome of dataset shape `shape` from the outcome of its mesh content: named shape.name
// (data and alternative too: copied when `content` shares them with another outcome), with
// `truth` and the shapes.csv measures against it. `reused`: the content was computed for another
// shape, so every time entry is marked cached, as a cache hit is (the seconds of the
// computation).
ShapeOutcome OutcomeOfShape(ShapeOutcome content, const DatasetShape& shape, ShapeGroundTruth truth,
                            bool reused);

// Maps every input vertex to a preprocessed vertex: itself when kept, else the kept vertex
// nearest in input coordinates. input_ids: #V_kept input id of each kept vertex.
void InputToKept(const Eigen::MatrixX3d& input_V, const std::vector<int>& input_ids,
                 std::vector<int>* kept_of_input, std::vector<int>* nearest_kept);

// How well the canonical symmetric embedding's plane x = 0 matches the dataset's symmetric
// ground truth: the mean over lines with both ids of ||M y_a - y_b|| with M = diag(-1, 1, 1),
// a = ids[i], b = sym_ids[i] (vertex ids of Y), divided by the RMS distance of Y's rows to their
// centroid. About 0.03 on TOSCA shapes whose plane is the left-right one; near 1 when the
// detected plane is perpendicular to it. Returns -1 when no line has both ids.
double SymmetryGroundTruthError(const Eigen::MatrixX3d& Y, const std::vector<int>& ids,
                                const std::vector<int>& sym_ids);

// How far the surface's own geodesics are from symmetric under the ground-truth symmetry,
// which bounds how well any symmetry plane of its embedding can do: over up to `max_lines` of
// the lines (a_i, b_i) with both ids (evenly spread over them), the mean over pairs of lines of
// |d(a_i, a_j) - d(b_i, b_j)| divided by the largest d(a_i, a_j), d the edge-graph distance of
// `surface` (ids are its vertex ids). About 0 for an intrinsically symmetric surface; a pose
// that stretches or compresses one side more than the other raises it. Pairs whose distance is
// infinite on either side (different components) are skipped. Returns -1 with fewer than two
// usable lines.
double GroundTruthGeodesicAsymmetry(const Surface& surface, const std::vector<int>& ids,
                                    const std::vector<int>& sym_ids, int max_lines = 64);

// How far the symmetry stage's self map moves the samples: the mean distance in data.embedding
// (before symmetrization) between each sample and its image under data.symmetry.sigma, over the
// samples' RMS radius. A left-right self map moves the limbs and flanks across the body; one
// near the identity moves each sample to a neighbour, near 0. Returns -1 without a valid self
// map of the samples.
double SelfMapDisplacement(const ShapeData& data);

// The canonical embedding's spread across its symmetry plane: the standard deviation of Y along
// x over the smaller of those along y and z. A body whose sides the symmetrization pressed
// together (a self map that pairs samples on one side) is thin along x. Returns -1 for fewer
// than 2 rows or no spread along y or z.
double CanonicalXSpread(const Eigen::MatrixX3d& Y);

// The YAML text of a stage's resolved options (hashed into cache keys), without the options
// that cannot change a result (`threads`), so that they do not invalidate cached outputs.
std::string OptionsText(const Stage& stage);

}  // namespace symembed
