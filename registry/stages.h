// The stage interfaces, one per stage kind (registry/stage_kinds.h; docs/design.md). Each
// implementation is a thin adapter around a free function; it parses its options in its
// factory (OptionReader) and does no file I/O. Stages are const after construction and safe to call from several threads.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "registry/product_needs.h"
#include "registry/types.h"

namespace symembed {

class Stage {
 public:
  virtual ~Stage() = default;
  // The resolved options of this stage (type and every option with defaults filled in).
  const YAML::Node& resolved_options() const { return resolved_options_; }
  void set_resolved_options(YAML::Node node) { resolved_options_ = std::move(node); }
  // The defaults of its options read only when given, which were not (OptionReader::
  // unset_defaults; not part of the resolved options or of any cache key).
  const YAML::Node& unset_defaults() const { return unset_defaults_; }
  void set_unset_defaults(YAML::Node node) { unset_defaults_ = std::move(node); }

 private:
  YAML::Node resolved_options_;
  YAML::Node unset_defaults_;
};

class PreprocessStage : public Stage {
 public:
  virtual PreprocessResult Run(const Surface& input) const = 0;
};

class SamplingStage : public Stage {
 public:
  virtual SamplingResult Run(const Surface& surface) const = 0;
};

// Distances from a set of sources to every vertex, on one prepared surface. A solver keeps
// what it may reuse across sources (a factorisation, a graph).
class GeodesicSolver {
 public:
  virtual ~GeodesicSolver() = default;
  // #sources x #V distances (in the surface's units). Thread-safe.
  virtual Eigen::MatrixXd Distances(const std::vector<int>& sources) const = 0;
};

class GeodesicsStage : public Stage {
 public:
  virtual std::unique_ptr<GeodesicSolver> Prepare(const Surface& surface) const = 0;
};

struct EmbeddingInput {
  const Surface& surface;
  const std::vector<int>& samples;    // #S
  const Eigen::MatrixXd& D;           // #S x #V geodesic distances from each sample
};

class EmbeddingStage : public Stage {
 public:
  virtual EmbeddingResult Run(const EmbeddingInput& input) const = 0;
};

struct SymmetryInput {
  const Surface& surface;
  const std::vector<int>& samples;
  const Eigen::MatrixXd& D;           // #S x #V
  const EmbeddingResult& embedding;   // 3D
};

class SymmetryStage : public Stage {
 public:
  virtual SymmetryResult Run(const SymmetryInput& input) const = 0;
  // A second plane hypothesis when `chosen` (Run's result) is doubtful: the runner keeps the
  // shape under both, and each pair takes the one whose chosen rotation its flip stage scores
  // lower. An empty sigma means none (the default).
  virtual SymmetryResult RunAlternative(const SymmetryInput& input,
                                        const SymmetryResult& chosen) const {
    (void)input;
    (void)chosen;
    return SymmetryResult{};
  }
};

class SymmetrizeStage : public Stage {
 public:
  // Returns the embedding moved so that the symmetry plane is x = 0, and symmetrized.
  virtual SymmetrizeResult Run(const SymmetryInput& input, const SymmetryResult& symmetry) const = 0;
};

// Per-pair stages declare what they read of each shape beyond the per-shape stages' outputs (a
// basis, products: registry/product_needs.h); the runner computes it once per shape into
// ShapeData::basis and ShapeData::products, cached.
class PairStage : public Stage {
 public:
  virtual ShapeNeeds Needs() const { return {}; }
};

class FlipStage : public PairStage {
 public:
  virtual FlipResult Run(const PairInput& pair) const = 0;
};

// A pair's map on the surfaces (MatchingStage::MatchSurfaces) and how well it and the seed it was
// given (the embeddings' map) keep the part's geodesic distances (LandmarkDistortion, lower is
// better).
struct SurfaceMatch {
  MatchResult result;
  double distortion = 0.0;
  double seed_distortion = 0.0;
};

class MatchingStage : public PairStage {
 public:
  // source: points of the source embedding; target: the target embedding, already rotated.
  virtual MatchResult Run(const EmbeddedPoints& source, const EmbeddedPoints& target) const = 0;
  // The source's points of every vertex moved towards the target before Run (pair: the two
  // shapes; source, target: as for Run, every vertex). Returns false, leaving *moved alone, for a
  // stage that matches the points as they are (the default).
  virtual bool Align(const PairInput& pair, const EmbeddedPoints& source,
                     const EmbeddedPoints& target, EmbeddedPoints* moved) const {
    (void)pair, (void)source, (void)target, (void)moved;
    return false;
  }
  // The map of a pair this stage matches on the surfaces as well as in the embeddings (a
  // partial shape, core/matching/partial.h), given the embeddings' map as a seed: returns true
  // with *out set, or false, leaving *out alone, for a pair matched in the embeddings alone by
  // Align and Run (the default).
  virtual bool MatchSurfaces(const PairInput& pair, const std::vector<int>& seed,
                             SurfaceMatch* out) const {
    (void)pair, (void)seed, (void)out;
    return false;
  }
};

// What a refine stage starts from: the two shapes, the matching stage's map, and the embedded
// points it matched (every vertex: the source's as the matching stage's Align moved them, the
// target's turned by the chosen rotation), in one frame where a vertex and its image lie close.
// The points are null when the caller has no embedding (a map from elsewhere). `part_and_whole`:
// the matching stage mapped the surfaces of a part and a whole (MatchSurfaces), so the map
// must not be pulled over the whole; a stage refines it as such (core/fmap/partial_zoomout.h)
// or returns it unchanged, and never reads the points.
struct RefineInput {
  const PairInput& pair;
  const std::vector<int>& initial_map;  // #V_source: target vertex of each source vertex
  const EmbeddedPoints* source_points = nullptr;
  const EmbeddedPoints* target_points = nullptr;
  bool part_and_whole = false;
};

class RefineStage : public PairStage {
 public:
  virtual MatchResult Run(const RefineInput& input) const = 0;
  // A map refined without embedded points.
  MatchResult Run(const PairInput& pair, const std::vector<int>& initial_map) const {
    return Run(RefineInput{pair, initial_map});
  }
};

}  // namespace symembed
