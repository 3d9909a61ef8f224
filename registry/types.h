// Data passed between stages. Shapes and units follow libigl notation in each comment.
#pragma once

#include <Eigen/Core>
#include <any>
#include <array>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/matching/match.h"
#include "core/mesh.h"
#include "core/spectral.h"
#include "core/stage_status.h"
#include "registry/shape_products.h"

namespace symembed {

// Named counters of what a stage changed or measured ("flipped_faces": 3, ...), in order.
using Report = std::vector<std::pair<std::string, double>>;

struct PreprocessResult {
  Surface surface;             // repaired surface, scaled to unit total area
  std::vector<int> input_ids;  // #V: input vertex id of each kept vertex
  double scale = 1.0;          // output coordinates = input coordinates * scale (after centring)
  Report report;               // every change counted
  StageStatus status;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&PreprocessResult::surface, &PreprocessResult::input_ids,
                           &PreprocessResult::scale, &PreprocessResult::report,
                           &PreprocessResult::status);
  }
};

struct SamplingResult {
  std::vector<int> samples;      // #S vertex ids, in sampling order
  double coverage_radius = 0.0;  // max over vertices of the distance to the nearest sample
  StageStatus status;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&SamplingResult::samples, &SamplingResult::coverage_radius,
                           &SamplingResult::status);
  }
};

struct EmbeddingResult {
  Eigen::MatrixXd Y;                   // #V x dims embedding of every vertex (sample rows exact)
  double normalized_stress = 0.0;      // sqrt(stress / sum d_ij^2) over sample pairs
  int reflection = 1;                  // sign of det of the Procrustes fit input -> embedding
  std::vector<double> stress_history;  // per iteration (lsmds), empty otherwise
  StageStatus status;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&EmbeddingResult::Y, &EmbeddingResult::normalized_stress,
                           &EmbeddingResult::reflection, &EmbeddingResult::stress_history,
                           &EmbeddingResult::status);
  }
};

struct SymmetryResult {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit plane normal in the 3D embedding
  double offset = 0.0;                                // plane: normal . y = offset
  std::vector<int> sigma;      // #S: sample index -> index of its mirror sample
  Eigen::VectorXd confidence;  // #S in [0, 1]
  double score = 0.0;          // symmetry quality, lower is better (relative to size)
  // > 0: a candidate whose self map moves the samples at least this much (the measure of
  // `self_map_displacement`) nearly tied with this one; the stage's RunAlternative proposes it.
  double tie_displacement = 0.0;
  StageStatus status;
  // The stage's own record of the detection, for its RunAlternative on the same input in the
  // same process (the per-shape chain drops it once the second plane is computed); empty when
  // the stage keeps none or the result was read from the cache. Not a member of the cache entry.
  std::any detection;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&SymmetryResult::normal, &SymmetryResult::offset, &SymmetryResult::sigma,
                           &SymmetryResult::confidence, &SymmetryResult::score,
                           &SymmetryResult::tie_displacement, &SymmetryResult::status);
  }
};

struct SymmetrizeResult {
  Eigen::MatrixX3d Y;             // #V x 3, symmetric about the plane x = 0
  double asymmetry_before = 0.0;  // mean ||M y_i - y_sigma(i)|| / size, M = diag(-1,1,1)
  double asymmetry_after = 0.0;
  StageStatus status;
  // Its members in the order of its cache entries (registry/serialize.h).
  static constexpr auto Members() {
    return std::make_tuple(&SymmetrizeResult::Y, &SymmetrizeResult::asymmetry_before,
                           &SymmetrizeResult::asymmetry_after, &SymmetrizeResult::status);
  }
};

// Everything the per-pair stages need about one shape. Built once per shape and shared by
// every pair and every variant that resolves to the same per-shape stages.
struct ShapeData {
  std::string name;
  Surface surface;             // after preprocessing
  std::vector<int> input_ids;  // #V: input vertex id of each vertex
  double scale = 1.0;
  std::vector<int> samples;   // #S
  EmbeddingResult embedding;  // before symmetrization
  SymmetryResult symmetry;
  Eigen::MatrixX3d Y;  // #V x 3 canonical symmetric embedding (plane normal = x)
  // What the per-pair stages declared they need (PairStage::Needs, registry/product_needs.h):
  // the Laplace-Beltrami basis with the most eigenpairs any of them reads (empty when none; a
  // stage reads its leading eigenpairs), and their products.
  LaplaceBasis basis;
  ShapeProducts products;
};

// The product `key` of a shape. Throws InvalidInputError naming the shape and the product when
// it is missing (the stage did not declare it) or has another type.
template <typename T>
const T& ProductOf(const ShapeData& shape, const ProductKey<T>& key) {
  const T* value = shape.products.Find(key);
  if (value == nullptr) ThrowMissingProduct(shape.name, key.Id());
  return *value;
}

// Ground truth of one pair in the vertex ids of the preprocessed shapes: line i says that
// source_ids[i] corresponds to target_ids[i] (and to target_sym_ids[i] under the symmetry).
// Lines whose vertex was removed by preprocessing are dropped.
// The ground-truth lines of a pair: line r says that source vertex source_ids[r] corresponds to
// target vertex target_ids[r] (and to target_sym_ids[r] under the left-right symmetry). The
// ids are in one id space, named by the type: InputGroundTruth in the vertex ids of the input
// mesh files (the datasets', the evaluator's and the maps' space), PreprocessedGroundTruth in
// those of the preprocessed surfaces the stages see (ToPreprocessedIds, pair_pipeline.h). The
// two are distinct types so that one cannot be passed for the other.
template <typename IdSpace>
struct GroundTruthLines {
  std::vector<int> source_ids;
  std::vector<int> target_ids;
  std::vector<int> target_sym_ids;  // empty when the dataset has no symmetric ground truth
};
struct InputIdSpace {};
struct PreprocessedIdSpace {};
using InputGroundTruth = GroundTruthLines<InputIdSpace>;
using PreprocessedGroundTruth = GroundTruthLines<PreprocessedIdSpace>;

struct PairInput {
  const ShapeData& source;
  const ShapeData& target;
  const PreprocessedGroundTruth* ground_truth = nullptr;  // only the oracle may use it
};

// The four proper rotations that remain once both shapes are in their canonical frames:
// {I, Rx(pi), Ry(pi), Rz(pi)}, applied to the target embedding (y' = R y).
std::array<Eigen::Matrix3d, 4> CandidateRotations();

// A shape's canonical embedding Y rotated by R, with the normals of the embedded surface (Y
// on the shape's faces) rotated alike: what the matching stage compares.
EmbeddedPoints EmbeddedShape(const ShapeData& shape,
                             const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity());

struct FlipResult {
  std::array<double, 4> scores{};  // per candidate, lower is better
  // Index into CandidateRotations(): the argmin of scores unless the stage's last step decides
  // otherwise (MakeFlipResult; the extrinsic scorer's refined term).
  int chosen = 0;
  StageStatus status;
};

}  // namespace symembed
