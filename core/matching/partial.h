// Correspondence between a partial shape (a cut, a scan of part of a body) and a shape it is a
// part of, from geodesic distances alone: neither shape's embedding, frame or symmetry plane is
// used, since a partial surface has none that agrees with the whole's.
//
// Between two points of the part whose shortest path on the whole stays inside the part, the
// part's geodesic distance is the whole's. So a point of the part is placed on the whole by its
// distances to landmarks whose images are known ("geodesic coordinates"), and the landmarks'
// images are found by hypothesis and test:
//   1. three far-apart samples of the part (from the first `pool` farthest-point samples) and
//      every triple of the whole's samples whose mutual distances agree with theirs within
//      `tolerance` (times the square root of the whole's area);
//   2. each such triple maps some of the part's samples to the whole's sample of the nearest
//      distances (L1) to it; the triples whose mapped samples keep their mutual distances best
//      are kept (a few query samples first, then `queries`);
//   3. each kept triple maps `landmarks` samples of the part, then again with the distances to
//      all of them, `iterations` times (L1 over the landmarks, which tolerates a landmark whose
//      path on the part goes around the cut);
//   4. of the distinct refined maps, the one of lowest residual among those that keep the
//      surface's orientation is chosen. Mirror images under an intrinsic left-right symmetry
//      keep every distance but turn the orientation (the sign of a small triangle of samples
//      against the vertex normal), so the orientation tells them apart. A map that turns it and
//      keeps the distances as well as the best map that does not (within 1.5 times its
//      residual) is the mirror image of a right map the triples may have missed: with the
//      whole's left-right self map known, that map's mirror image joins the maps compared. A body
//      turned front to back keeps both; of the maps whose residual is within 1.5 times the least,
//      one whose samples' shape index (core/curvature.h, smoothed over 0.05 sqrt(area of the
//      whole)) disagrees with their images' clearly less (below 0.75 times) than the chosen map's
//      is taken instead: where a body bulges and where it hollows tells front from back.
// A seed (the pair's map from elsewhere, e.g. the embeddings') adds one more map, refined in
// full, kept over the triples' when it keeps the orientation with a residual within 1.5 times
// theirs: it tells which way a nearly front-back symmetric body is turned. Where it is kept, the
// lowest-residual map below its residual that keeps the orientation and turns the body the same
// way (landmarks' images within 0.25 sqrt(area) of the seed's on average) replaces it.
// Every vertex of the source is then mapped by its distances to the landmarks, searched near
// the image of its nearest sample. Distances are along mesh edges (core/mesh_graph.h).
//
// Units: the two surfaces' coordinates times their `unit` (e.g. 1 / ShapeData::scale, the
// input units) must be in one unit; the part is the one of smaller area in that unit (either
// the source or the target). Deterministic. Throws InvalidInputError for a surface without
// faces or with fewer samples than `landmarks`, and for a whole's mirror map (PartialMirrors)
// whose size is not its samples' or with an index out of their range.
//
// Related: generalized MDS, which embeds a part into a whole's geodesic metric [Bronstein,
// Bronstein & Kimmel 2006, PNAS]; RANSAC [Fischler & Bolles 1981].
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "core/edge_distance_cache.h"
#include "core/matching/match.h"
#include "core/mesh.h"
#include "core/range.h"

namespace symembed {

struct PartialMatchOptions {
  // A shape is matched as a part when its open boundary is longer than this times the square
  // root of its area (BoundaryRatio); 0: never. A closed shape has 0; small holes stay below.
  double boundary_ratio = 0.4;
  static constexpr Range kBoundaryRatio = Range::AtLeast(0.0);
  // Samples (prefixes of the shapes' farthest-point samples) of the part and of the whole.
  int part_samples = 120;
  static constexpr Range kPartSamples = Range::Closed(10, 2000);
  int whole_samples = 300;
  static constexpr Range kWholeSamples = Range::Closed(10, 4000);
  // Triples of the part's first `pool` samples tried, spread over all of them.
  int triples = 16;
  static constexpr Range kTriples = Range::Closed(1, 200);
  int pool = 10;
  static constexpr Range kPool = Range::Closed(3, 100);
  // Distances agree within tolerance * sqrt(area of the whole).
  double tolerance = 0.03;
  static constexpr Range kTolerance = Range::OpenClosed(0.0, 1.0);
  // Samples of the part mapped to score a triple.
  int queries = 30;
  static constexpr Range kQueries = Range::Closed(4, 500);
  // Landmarks of the refined maps, refinement rounds, distinct maps compared.
  int landmarks = 40;
  static constexpr Range kLandmarks = Range::Closed(4, 500);
  int iterations = 3;
  static constexpr Range kIterations = Range::Closed(0, 100);
  int hypotheses = 6;
  static constexpr Range kHypotheses = Range::Closed(1, 100);

  bool IsValid(std::string* error) const;
};

// Length of the open boundary (edges of one face) over the square root of the area;
// scale-invariant. 0 for a closed surface or one without faces.
double BoundaryRatio(const Surface& surface);

// Whether the pair is matched as part and whole: either shape's BoundaryRatio above
// options.boundary_ratio (> 0).
bool IsPartialPair(const Surface& source, const Surface& target,
                   const PartialMatchOptions& options);

// Smoothed shape indices of surfaces kept across calls: a whole shape's is the same in every
// pair it is in. Keyed by the surface's key (as in EdgeDistanceCache) and the smoothing radius
// (its bits), so a value from the cache is the one the call would compute. Thread-safe: a value
// missing in two threads at once is computed in both, with the same result. When the values
// kept exceed `max_bytes`, all are dropped.
class ShapeIndexCache {
 public:
  explicit ShapeIndexCache(size_t max_bytes) : max_bytes_(max_bytes) {}
  ShapeIndexCache(const ShapeIndexCache&) = delete;
  ShapeIndexCache& operator=(const ShapeIndexCache&) = delete;

  // The value kept for (surface_key, radius), or compute()'s, then kept.
  Eigen::VectorXd Get(uint64_t surface_key, double radius,
                      const std::function<Eigen::VectorXd()>& compute);
  size_t Size() const;

 private:
  size_t max_bytes_;
  mutable std::mutex mutex_;
  std::map<std::pair<uint64_t, uint64_t>, Eigen::VectorXd> values_;
  size_t bytes_ = 0;
};

// Distance rows kept across calls (EdgeDistanceCache) and the keys of the two surfaces in it,
// derived from their content; optionally their smoothed shape indices (ShapeIndexCache) under
// the same keys. Without a cache, a call keeps its own rows for itself and computes the shape
// indices.
struct PartialRows {
  EdgeDistanceCache* cache = nullptr;
  uint64_t source_key = 0;
  uint64_t target_key = 0;
  ShapeIndexCache* shape_index = nullptr;
};

// The left-right self maps of the two surfaces on the samples given to MatchPartial (sigma[i]:
// the index of sample i's mirror image among the same samples, as SymmetryResult::sigma), each
// null when unknown. Only the whole's is read; a vertex goes where its nearest sample along the
// edges goes.
struct PartialMirrors {
  const std::vector<int>* source_sigma = nullptr;
  const std::vector<int>* target_sigma = nullptr;
};

// map[v]: the target vertex of source vertex v. samples: farthest-point samples of each
// surface in sampling order (the first spread widest). status.residual: the chosen map's mean
// L1 disagreement of distances to the landmarks per landmark, over the whole's square root of
// area; status.message: the part, the orientation agreement and the maps compared.
MatchResult MatchPartial(const Surface& source, const std::vector<int>& source_samples,
                         double source_unit, const Surface& target,
                         const std::vector<int>& target_samples, double target_unit,
                         const PartialMatchOptions& options = {},
                         const std::vector<int>* seed = nullptr, const PartialRows& rows = {},
                         const PartialMirrors& mirrors = {});

// How well `map` (source vertex -> target vertex) keeps geodesic distances on the part (the
// shape of smaller area in the common unit): the median over pairs of `count` landmarks of
// the part (its first samples) of |distance between them - distance between their
// counterparts|, over the square root of the part's area. The counterpart of a source landmark
// is its image; of a target landmark, the source vertex whose image is nearest to it. Lower is
// better; 0 for a map that keeps every such distance.
double LandmarkDistortion(const Surface& source, const std::vector<int>& source_samples,
                          double source_unit, const Surface& target,
                          const std::vector<int>& target_samples, double target_unit,
                          const std::vector<int>& map, int count = 40,
                          const PartialRows& rows = {});

}  // namespace symembed
