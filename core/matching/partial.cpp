#include "core/matching/partial.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <sstream>
#include <utility>

#include "core/curvature.h"
#include "core/errors.h"
#include "core/laplacian.h"
#include "core/matching/l1_nearest.h"
#include "core/mesh_graph.h"

namespace symembed {
namespace {

// The seed's map is kept over the best of the triples' when its residual is at most this
// times theirs: distances alone do not tell apart two maps of a nearly symmetric body.
constexpr double kSeedResidualSlack = 1.5;
// Two maps whose landmarks' images lie on average within this times the square root of the
// whole's area of each other turn the body the same way; turned front to back, a body's
// landmarks move by about half its girth.
constexpr double kSameTurn = 0.25;
// Of the maps within that slack that keep the orientation, one whose shape disagrees clearly
// less (below this times the chosen map's) replaces it: a body turned front to back keeps
// distances and orientation, but not where it bulges and where it hollows.
constexpr double kShapeClearlyLess = 0.75;
// Mirror images added at most (of the maps that turn the orientation, the lowest residual first).
constexpr int kMirroredMaps = 3;
// The shape index is smoothed over this radius times the square root of the whole's area.
constexpr double kShapeRadius = 0.05;

// Rows of one call without a cache of the caller's: bounded by what one call computes.
constexpr size_t kCallRowBytes = size_t{1} << 40;

// The cache of `rows`, or `own` (for this call alone), and the two surfaces' keys in it.
PartialRows RowsOf(const PartialRows& rows, EdgeDistanceCache* own) {
  if (rows.cache != nullptr) return rows;
  return PartialRows{own, 1, 2};
}

// One shape of the pair, in the common unit.
struct PartialSide {
  const Surface* surface = nullptr;
  EdgeDistanceCache* cache = nullptr;
  uint64_t key = 0;  // of the surface in *cache
  double unit = 1.0;
  double area = 0.0;  // in the common unit
  MeshGraph graph;
  std::vector<int> samples;
  Eigen::MatrixXd D;   // #samples x #V distances from each sample, common unit
  Eigen::MatrixXd DS;  // #samples x #samples
  Eigen::MatrixX3d normals;
  Eigen::VectorXd shape_index;  // #V, smoothed over one radius in the common unit (SetShape)

  void Prepare(const Surface& s, EdgeDistanceCache* rows, uint64_t rows_key,
               const std::vector<int>& all_samples, int count, double u, const char* which) {
    if (s.NumFaces() == 0) throw InvalidInputError(std::string(which) + " surface has no faces");
    surface = &s;
    cache = rows;
    key = rows_key;
    unit = u;
    area = TotalArea(s) * u * u;
    graph = BuildMeshGraph(s);
    samples.assign(all_samples.begin(),
                   all_samples.begin() + std::min<size_t>(count, all_samples.size()));
    D = Distances(samples);
    DS.resize(samples.size(), samples.size());
    for (size_t i = 0; i < samples.size(); ++i) {
      for (size_t j = 0; j < samples.size(); ++j) DS(i, j) = D(i, samples[j]);
    }
    normals = VertexNormals(s);
    // The faces of an open surface may be consistently oriented either way (no inside to point
    // away from); the normals are turned to point away from the centroid on the whole, as a
    // body's outward normals do, so that the orientation of two shapes compares.
    const Eigen::RowVector3d centroid = s.V.colwise().mean();
    double outward = 0.0;
    for (int v = 0; v < s.NumVertices(); ++v) outward += normals.row(v).dot(s.V.row(v) - centroid);
    if (outward < 0.0) normals = -normals;
  }
  int NumSamples() const { return static_cast<int>(samples.size()); }
  // The shape index (core/curvature.h) smoothed over `radius` in the common unit, so that
  // both shapes' are smoothed alike whatever their extent.
  // `kept`: where values are kept across calls under this side's key, or null.
  void SetShape(double radius, ShapeIndexCache* kept) {
    CurvatureOptions curvature;
    curvature.smoothing_rings = 0;
    curvature.smoothing_radius = radius / std::sqrt(area);
    auto compute = [&] { return ComputeCurvature(*surface, curvature).shape_index; };
    shape_index = kept ? kept->Get(key, curvature.smoothing_radius, compute) : compute();
  }
  // Distances (common unit) from each of `sources` to every vertex.
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const {
    return cache->Rows(key, graph, sources) * unit;
  }
};

// Triple (a, b, c) of part samples and its images (A, B, C) among the whole's samples.
struct TripleHypothesis {
  double score = 0.0;
  int a = 0, b = 0, c = 0, A = 0, B = 0, C = 0;
};

// The whole's sample nearest in L1 to part sample q's distances to a, b, c under (A, B, C):
// whole_samples holds the whole's sample-to-sample distances (row A: from sample A).
int MapQuery(const PartialSide& part, const L1Columns& whole_samples, const TripleHypothesis& h,
             int q) {
  const double x[3] = {part.DS(h.a, q), part.DS(h.b, q), part.DS(h.c, q)};
  const int rows[3] = {h.A, h.B, h.C};
  return whole_samples.Nearest(x, rows, 3).first;
}

// Mean disagreement of the mutual distances of the query samples and of their images.
double TripleScore(const PartialSide& part, const PartialSide& whole,
                   const L1Columns& whole_samples, const TripleHypothesis& h,
                   const std::vector<int>& queries) {
  std::vector<int> image(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    image[i] = MapQuery(part, whole_samples, h, queries[i]);
  }
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    for (size_t j = i + 1; j < queries.size(); ++j) {
      sum += std::abs(whole.DS(image[i], image[j]) - part.DS(queries[i], queries[j]));
      ++count;
    }
  }
  return count > 0 ? sum / count : 0.0;
}

// The t-th of `count` triples spread over the lexicographic order of the triples of [0, pool).
void SpreadTriple(int t, int count, int pool, int* a, int* b, int* c) {
  const long total = static_cast<long>(pool) * (pool - 1) * (pool - 2) / 6;
  long index = total * t / std::max(count, 1);
  for (int i = 0; i < pool; ++i) {
    for (int j = i + 1; j < pool; ++j) {
      for (int k = j + 1; k < pool; ++k) {
        if (index-- == 0) {
          *a = i, *b = j, *c = k;
          return;
        }
      }
    }
  }
  *a = 0, *b = 1, *c = 2;
}

std::vector<TripleHypothesis> TripleHypotheses(const PartialSide& part, const PartialSide& whole,
                                               const PartialMatchOptions& o) {
  const double tol = o.tolerance * std::sqrt(whole.area);
  const int ns = whole.NumSamples();
  const int pool = std::min(o.pool, part.NumSamples());
  const int nq = std::min(o.queries, part.NumSamples());
  std::vector<int> queries(nq), first_queries;
  std::iota(queries.begin(), queries.end(), 0);
  // A few queries beyond the pool rank the candidates before the full score.
  for (int q = pool; q < std::min(pool + 6, part.NumSamples()); ++q) first_queries.push_back(q);
  if (first_queries.size() < 3) first_queries = queries;
  const L1Columns whole_samples(whole.DS.transpose());
  constexpr int kFirstKept = 300;
  constexpr int kKeptPerTriple = 4;
  std::vector<TripleHypothesis> kept;
  const int triples = std::min<long>(o.triples, static_cast<long>(pool) * (pool - 1) * (pool - 2) / 6);
  for (int t = 0; t < triples; ++t) {
    TripleHypothesis h;
    SpreadTriple(t, triples, pool, &h.a, &h.b, &h.c);
    const double dab = part.DS(h.a, h.b), dac = part.DS(h.a, h.c), dbc = part.DS(h.b, h.c);
    std::vector<TripleHypothesis> candidates;
    for (int A = 0; A < ns; ++A) {
      for (int B = 0; B < ns; ++B) {
        if (std::abs(whole.DS(A, B) - dab) >= tol) continue;
        for (int C = 0; C < ns; ++C) {
          if (std::abs(whole.DS(A, C) - dac) >= tol || std::abs(whole.DS(B, C) - dbc) >= tol) {
            continue;
          }
          TripleHypothesis c = h;
          c.A = A, c.B = B, c.C = C;
          candidates.push_back(c);
        }
      }
    }
    for (TripleHypothesis& c : candidates)
      c.score = TripleScore(part, whole, whole_samples, c, first_queries);
    auto by_score = [](const TripleHypothesis& x, const TripleHypothesis& y) {
      return x.score < y.score || (x.score == y.score && std::tie(x.A, x.B, x.C) < std::tie(y.A, y.B, y.C));
    };
    const size_t first = std::min<size_t>(kFirstKept, candidates.size());
    std::partial_sort(candidates.begin(), candidates.begin() + first, candidates.end(), by_score);
    candidates.resize(first);
    for (TripleHypothesis& c : candidates)
      c.score = TripleScore(part, whole, whole_samples, c, queries);
    std::sort(candidates.begin(), candidates.end(), by_score);
    for (size_t i = 0; i < std::min<size_t>(kKeptPerTriple, candidates.size()); ++i) {
      kept.push_back(candidates[i]);
    }
  }
  std::stable_sort(kept.begin(), kept.end(),
                   [](const TripleHypothesis& x, const TripleHypothesis& y) { return x.score < y.score; });
  return kept;
}

// The whole's vertex nearest in L1 to each of `vertices`' distances to the landmarks.
std::vector<int> MapVerticesBrute(const Eigen::MatrixXd& part_rows, const Eigen::MatrixXd& whole_rows,
                                  const std::vector<int>& vertices, double* mean_cost) {
  const L1Columns columns(whole_rows);
  std::vector<int> image(vertices.size());
  double sum = 0.0;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const auto [j, cost] = columns.Nearest(part_rows.col(vertices[i]).data());
    image[i] = j;
    sum += cost;
  }
  if (mean_cost) *mean_cost = vertices.empty() ? 0.0 : sum / vertices.size() / part_rows.rows();
  return image;
}

// Refines the images of the landmarks (part vertices, whose distances to every part vertex
// are part_rows) from `images` (whole vertices): each round maps them by their distances to all
// of them. *whole_rows: on return, the distances from the final images.
std::vector<int> RefineLandmarks(const PartialSide& whole, const std::vector<int>& landmarks,
                                 const Eigen::MatrixXd& part_rows, std::vector<int> images,
                                 int iterations, Eigen::MatrixXd* whole_rows) {
  for (int it = 0; it < iterations; ++it) {
    std::vector<int> next = MapVerticesBrute(part_rows, *whole_rows, landmarks, nullptr);
    if (next == images) break;
    images = std::move(next);
    *whole_rows = whole.Distances(images);
  }
  return images;
}

// Share of the part's samples whose small triangle (the sample and its two nearest samples)
// keeps its orientation against the vertex normal under `image` (whole vertex per sample).
double OrientationAgreement(const PartialSide& part, const PartialSide& whole,
                            const std::vector<int>& image) {
  const int n = part.NumSamples();
  int agree = 0, total = 0;
  for (int i = 0; i < n; ++i) {
    int j = -1, k = -1;
    for (int m = 0; m < n; ++m) {
      if (m == i) continue;
      if (j < 0 || part.DS(i, m) < part.DS(i, j)) {
        k = j;
        j = m;
      } else if (k < 0 || part.DS(i, m) < part.DS(i, k)) {
        k = m;
      }
    }
    if (k < 0) continue;
    const Eigen::MatrixX3d& P = part.surface->V;
    const Eigen::MatrixX3d& W = whole.surface->V;
    const int p = part.samples[i], q = part.samples[j], r = part.samples[k];
    const double sp = (P.row(q) - P.row(p)).cross(P.row(r) - P.row(p)).dot(part.normals.row(p));
    const double sw = (W.row(image[j]) - W.row(image[i]))
                          .cross(W.row(image[k]) - W.row(image[i]))
                          .dot(whole.normals.row(image[i]));
    if (sp == 0.0 || sw == 0.0) continue;
    ++total;
    if ((sp > 0) == (sw > 0)) ++agree;
  }
  return total > 0 ? static_cast<double>(agree) / total : 0.5;
}

// The whole's left-right self map on its vertices from the one on its samples (`sigma` over
// `samples`): each vertex goes where its nearest sample along the edges goes.
std::vector<int> MirrorOfVertices(const PartialSide& side, const std::vector<int>& samples,
                                  const std::vector<int>& sigma, const char* which) {
  if (sigma.size() != samples.size()) {
    throw InvalidInputError(std::string("partial matching: the ") + which + "'s mirror map has " +
                            std::to_string(sigma.size()) + " entries for " +
                            std::to_string(samples.size()) + " samples");
  }
  for (int s : sigma) {
    if (s < 0 || s >= static_cast<int>(samples.size())) {
      throw InvalidInputError(std::string("partial matching: the ") + which +
                              "'s mirror map names sample " + std::to_string(s) + " of " +
                              std::to_string(samples.size()));
    }
  }
  const std::vector<int> nearest = NearestSeeds(side.graph, samples);
  std::vector<int> mirror(nearest.size());
  for (size_t v = 0; v < nearest.size(); ++v) {
    mirror[v] = nearest[v] < 0 ? static_cast<int>(v) : samples[sigma[nearest[v]]];
  }
  return mirror;
}

// Maps every vertex of `from` to a vertex of `to` by its distances to the landmarks (rows
// from_rows, to_rows: k x #V), searching near the image of its nearest anchor: anchors_from[i]
// (a vertex of `from`) has image anchors_to[i].
std::vector<int> MapAllVertices(const PartialSide& from, const PartialSide& to,
                                const Eigen::MatrixXd& from_rows, const Eigen::MatrixXd& to_rows,
                                const std::vector<int>& anchors_from,
                                const std::vector<int>& anchors_to) {
  const int n = from.surface->NumVertices();
  const std::vector<int> seed = NearestSeeds(from.graph, anchors_from);
  std::vector<std::vector<int>> cell(anchors_from.size());
  for (int v = 0; v < n; ++v) {
    if (seed[v] >= 0) cell[seed[v]].push_back(v);
  }
  // The radius of each cell (common unit): its farthest vertex from the anchor in space, which
  // within a cell this small is close to the distance along the surface.
  std::vector<double> radius(anchors_from.size(), 0.0);
  std::vector<double> radii;
  for (size_t i = 0; i < anchors_from.size(); ++i) {
    if (cell[i].empty()) continue;
    for (int v : cell[i]) {
      radius[i] = std::max(
          radius[i], (from.surface->V.row(v) - from.surface->V.row(anchors_from[i])).norm() * from.unit);
    }
    radii.push_back(radius[i]);
  }
  double cap = std::numeric_limits<double>::infinity();
  if (!radii.empty()) {
    std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
    cap = 3.0 * radii[radii.size() / 2];
  }
  std::vector<int> map(n, anchors_to.empty() ? 0 : anchors_to[0]);
  std::vector<std::pair<int, double>> ball;
  DijkstraWorkspace<double> ball_ws;
  for (size_t i = 0; i < anchors_from.size(); ++i) {
    if (cell[i].empty()) continue;
    const double r = std::min(2.0 * radius[i], cap) + 2.0 * to.graph.max_length * to.unit;
    DijkstraBall(to.graph, anchors_to[i], r / to.unit, &ball, &ball_ws);
    Eigen::MatrixXd ball_rows(to_rows.rows(), ball.size());
    for (size_t j = 0; j < ball.size(); ++j) ball_rows.col(j) = to_rows.col(ball[j].first);
    const L1Columns columns(ball_rows);
    for (int v : cell[i]) {
      // The first vertex of the ball with the lowest finite cost; the anchor's image if none.
      const auto [j, cost] = columns.Nearest(from_rows.col(v).data());
      map[v] = cost < std::numeric_limits<double>::infinity() ? ball[j].first : anchors_to[i];
    }
  }
  return map;
}

}  // namespace

Eigen::VectorXd ShapeIndexCache::Get(uint64_t surface_key, double radius,
                                     const std::function<Eigen::VectorXd()>& compute) {
  uint64_t bits = 0;
  static_assert(sizeof bits == sizeof radius, "a double's bits key the radius");
  std::memcpy(&bits, &radius, sizeof bits);
  const std::pair<uint64_t, uint64_t> key{surface_key, bits};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = values_.find(key);
    if (it != values_.end()) return it->second;
  }
  Eigen::VectorXd value = compute();
  const size_t bytes = sizeof(double) * static_cast<size_t>(value.size());
  std::lock_guard<std::mutex> lock(mutex_);
  if (bytes_ + bytes > max_bytes_) {
    values_.clear();
    bytes_ = 0;
  }
  if (bytes <= max_bytes_ && values_.emplace(key, value).second) bytes_ += bytes;
  return value;
}

size_t ShapeIndexCache::Size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return values_.size();
}

bool PartialMatchOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  out << FirstViolation({{"boundary_ratio", kBoundaryRatio, boundary_ratio},
                         {"part_samples", kPartSamples, part_samples},
                         {"whole_samples", kWholeSamples, whole_samples},
                         {"triples", kTriples, triples},
                         {"pool", kPool, pool},
                         {"tolerance", kTolerance, tolerance},
                         {"queries", kQueries, queries},
                         {"landmarks", kLandmarks, landmarks},
                         {"iterations", kIterations, iterations},
                         {"hypotheses", kHypotheses, hypotheses}});
  if (out.str().empty() && landmarks > part_samples) {
    out << "landmarks (" << landmarks << ") must not exceed part_samples (" << part_samples << ")";
  }
  if (error) *error = out.str();
  return out.str().empty();
}

double BoundaryRatio(const Surface& surface) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * surface.NumFaces());
  for (int f = 0; f < surface.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = surface.F(f, k), b = surface.F(f, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  double length = 0.0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) length += (surface.V.row(edges[i].first) - surface.V.row(edges[i].second)).norm();
    i = j;
  }
  const double area = TotalArea(surface);
  return area > 0.0 ? length / std::sqrt(area) : 0.0;
}

bool IsPartialPair(const Surface& source, const Surface& target,
                   const PartialMatchOptions& options) {
  if (options.boundary_ratio <= 0.0) return false;
  return BoundaryRatio(source) > options.boundary_ratio ||
         BoundaryRatio(target) > options.boundary_ratio;
}

MatchResult MatchPartial(const Surface& source, const std::vector<int>& source_samples,
                         double source_unit, const Surface& target,
                         const std::vector<int>& target_samples, double target_unit,
                         const PartialMatchOptions& options, const std::vector<int>* seed,
                         const PartialRows& cached, const PartialMirrors& mirrors) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("partial matching: " + error);
  EdgeDistanceCache own(kCallRowBytes);
  const PartialRows rows = RowsOf(cached, &own);
  const bool source_is_part =
      TotalArea(source) * source_unit * source_unit <= TotalArea(target) * target_unit * target_unit;
  PartialSide part, whole;
  if (source_is_part) {
    part.Prepare(source, rows.cache, rows.source_key, source_samples, options.part_samples,
                 source_unit, "source");
    whole.Prepare(target, rows.cache, rows.target_key, target_samples, options.whole_samples,
                  target_unit, "target");
  } else {
    part.Prepare(target, rows.cache, rows.target_key, target_samples, options.part_samples,
                 target_unit, "target");
    whole.Prepare(source, rows.cache, rows.source_key, source_samples, options.whole_samples,
                  source_unit, "source");
  }
  if (part.NumSamples() < options.landmarks || whole.NumSamples() < 3) {
    throw InvalidInputError("partial matching needs " + std::to_string(options.landmarks) +
                            " samples of the part and 3 of the whole; they have " +
                            std::to_string(part.NumSamples()) + " and " +
                            std::to_string(whole.NumSamples()));
  }
  part.SetShape(kShapeRadius * std::sqrt(whole.area), rows.shape_index);
  whole.SetShape(kShapeRadius * std::sqrt(whole.area), rows.shape_index);
  const std::vector<TripleHypothesis> triples = TripleHypotheses(part, whole, options);

  const std::vector<int> landmarks(part.samples.begin(), part.samples.begin() + options.landmarks);

  // The landmarks are the part's first samples, whose distance rows are at hand.
  const Eigen::MatrixXd part_rows = part.D.topRows(options.landmarks);
  struct Refined {
    std::vector<int> images;         // whole vertex of each landmark
    Eigen::MatrixXd whole_rows;      // distances from the images
    std::vector<int> sample_images;  // whole vertex of each part sample
    double residual = 0.0;           // per landmark, over sqrt(area of the whole)
    double orientation = 0.0;
    double shape = 0.0;              // mean shape-index disagreement of the samples
  };
  auto evaluate = [&](Refined* r) {
    double cost = 0.0;
    r->sample_images = MapVerticesBrute(part_rows, r->whole_rows, part.samples, &cost);
    r->residual = cost / std::sqrt(whole.area);
    r->orientation = OrientationAgreement(part, whole, r->sample_images);
    double disagreement = 0.0;
    for (size_t i = 0; i < part.samples.size(); ++i) {
      disagreement += std::abs(part.shape_index(part.samples[i]) -
                               whole.shape_index(r->sample_images[i]));
    }
    r->shape = disagreement / part.samples.size();
  };
  // The map to keep of `maps`: the lowest residual among those that keep the orientation (of
  // all, when none does).
  auto choose = [](const std::vector<Refined>& maps, int skip, int skip_too) {
    int chosen = -1;
    for (int pass = 0; pass < 2 && chosen < 0; ++pass) {
      for (size_t i = 0; i < maps.size(); ++i) {
        const int at = static_cast<int>(i);
        if (at == skip || at == skip_too || (pass == 0 && maps[i].orientation <= 0.5)) continue;
        if (chosen < 0 || maps[i].residual < maps[chosen].residual) chosen = at;
      }
    }
    return chosen;
  };
  const double distinct = 0.05 * std::sqrt(whole.area);
  auto mean_gap = [&](const std::vector<int>& x, const std::vector<int>& y) {
    double sum = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
      sum += (whole.surface->V.row(x[i]) - whole.surface->V.row(y[i])).norm() * whole.unit;
    }
    return x.empty() ? 0.0 : sum / x.size();
  };
  // Each distinct start gets one round of refinement; the two best get the rest.
  std::vector<Refined> refined;
  std::vector<std::vector<int>> starts;
  // Refines `start` (the landmarks' images) one round and adds the map unless it is near one
  // already refined; returns whether it was added. A start near an earlier start, or near a
  // map already refined, would refine to that map and is skipped.
  auto add_start = [&](std::vector<int> start) {
    bool seen = false;
    for (const auto& s : starts) seen = seen || mean_gap(s, start) < distinct;
    for (const Refined& r : refined) seen = seen || mean_gap(r.images, start) < distinct;
    if (seen) return false;
    starts.push_back(start);
    Refined r;
    r.whole_rows = whole.Distances(start);
    r.images = RefineLandmarks(whole, landmarks, part_rows, std::move(start),
                               std::min(options.iterations, 1), &r.whole_rows);
    evaluate(&r);
    for (const Refined& other : refined) {
      if (mean_gap(other.sample_images, r.sample_images) < distinct) return false;
    }
    refined.push_back(std::move(r));
    return true;
  };
  for (const TripleHypothesis& h : triples) {
    if (static_cast<int>(refined.size()) >= options.hypotheses) break;
    // The landmarks' first images: by their distances to the triple, over every vertex.
    Eigen::MatrixXd whole3(3, whole.surface->NumVertices());
    whole3.row(0) = whole.D.row(h.A);
    whole3.row(1) = whole.D.row(h.B);
    whole3.row(2) = whole.D.row(h.C);
    Eigen::MatrixXd part3(3, part.surface->NumVertices());
    part3.row(0) = part.D.row(h.a);
    part3.row(1) = part.D.row(h.b);
    part3.row(2) = part.D.row(h.c);
    add_start(MapVerticesBrute(part3, whole3, landmarks, nullptr));
  }
  if (refined.empty()) {
    throw SolverError("partial matching found no triple of the whole's samples whose distances "
                      "agree with the part's within the tolerance");
  }
  // The mirror images of the maps that turn the orientation but keep the distances about as
  // well as the best map that keeps it: the triples may have reached a right map's mirror
  // image only.
  int mirrored = 0;
  const std::vector<int>* whole_sigma =
      source_is_part ? mirrors.target_sigma : mirrors.source_sigma;
  if (whole_sigma != nullptr && !whole_sigma->empty()) {
    const std::vector<int>& whole_samples = source_is_part ? target_samples : source_samples;
    const std::vector<int> mirror =
        MirrorOfVertices(whole, whole_samples, *whole_sigma, source_is_part ? "target" : "source");
    double least_kept = std::numeric_limits<double>::infinity();
    for (const Refined& r : refined) {
      if (r.orientation > 0.5) least_kept = std::min(least_kept, r.residual);
    }
    std::vector<int> turned;
    for (size_t i = 0; i < refined.size(); ++i) {
      if (refined[i].orientation <= 0.5 && refined[i].residual <= kSeedResidualSlack * least_kept) {
        turned.push_back(static_cast<int>(i));
      }
    }
    std::stable_sort(turned.begin(), turned.end(),
                     [&](int a, int b) { return refined[a].residual < refined[b].residual; });
    for (int i : turned) {
      if (mirrored >= kMirroredMaps) break;
      std::vector<int> start(landmarks.size());
      for (size_t k = 0; k < landmarks.size(); ++k) start[k] = mirror[refined[i].images[k]];
      mirrored += add_start(std::move(start));
    }
  }
  // The seed's map of the landmarks, refined in full: kept where the distances and the
  // orientation cannot tell it from the map chosen above.
  int seeded = -1;
  if (seed != nullptr && seed->size() == static_cast<size_t>(source.NumVertices())) {
    std::vector<int> start(landmarks.size());
    for (size_t i = 0; i < landmarks.size(); ++i) {
      if (source_is_part) {
        start[i] = (*seed)[landmarks[i]];
      } else {
        double nearest = std::numeric_limits<double>::infinity();
        for (size_t v = 0; v < seed->size(); ++v) {
          if (part.D(i, (*seed)[v]) < nearest) {
            nearest = part.D(i, (*seed)[v]);
            start[i] = static_cast<int>(v);
          }
        }
      }
    }
    Refined r;
    r.whole_rows = whole.Distances(start);
    r.images = RefineLandmarks(whole, landmarks, part_rows, start, options.iterations,
                               &r.whole_rows);
    evaluate(&r);
    refined.push_back(std::move(r));
    seeded = static_cast<int>(refined.size()) - 1;
  }
  if (options.iterations > 1) {
    const int first = choose(refined, seeded, -1);
    const int second = choose(refined, first, seeded);
    for (int i : {first, second}) {
      if (i < 0) continue;
      refined[i].images = RefineLandmarks(whole, landmarks, part_rows, refined[i].images,
                                          options.iterations - 1, &refined[i].whole_rows);
      evaluate(&refined[i]);
    }
  }
  int chosen = choose(refined, seeded, -1);
  if (chosen < 0) chosen = seeded;
  if (seeded >= 0 && refined[seeded].orientation > 0.5 &&
      (refined[chosen].orientation <= 0.5 ||
       refined[seeded].residual <= kSeedResidualSlack * refined[chosen].residual)) {
    chosen = seeded;
  }
  // The seed tells which way the body is turned, not where each landmark lies: of the maps that
  // keep the orientation with a lower residual than the seed's kept one, the lowest within
  // kSameTurn of it is the seed's turn placed better.
  bool seed_turn = false;
  if (seeded >= 0 && chosen == seeded) {
    const double reach = kSameTurn * std::sqrt(whole.area) * static_cast<double>(landmarks.size());
    for (size_t i = 0; i < refined.size(); ++i) {
      const Refined& r = refined[i];
      if (r.orientation <= 0.5 || r.residual >= refined[chosen].residual) continue;
      double apart = 0.0;
      for (size_t k = 0; k < landmarks.size(); ++k) {
        apart += refined[seeded].whole_rows(k, r.images[k]);
      }
      if (apart <= reach) chosen = static_cast<int>(i), seed_turn = true;
    }
  }
  // Distances and orientation cannot tell maps within the slack apart; the shape can.
  double least_residual = std::numeric_limits<double>::infinity();
  for (const Refined& r : refined) {
    if (r.orientation > 0.5) least_residual = std::min(least_residual, r.residual);
  }
  int by_shape = -1;
  for (size_t i = 0; i < refined.size(); ++i) {
    const Refined& r = refined[i];
    if (r.orientation <= 0.5 || r.residual > kSeedResidualSlack * least_residual) continue;
    if (by_shape < 0 || r.shape < refined[by_shape].shape) by_shape = static_cast<int>(i);
  }
  const bool shape_decided = by_shape >= 0 && by_shape != chosen &&
                             refined[by_shape].shape < kShapeClearlyLess * refined[chosen].shape;
  if (shape_decided) chosen = by_shape;
  const Refined& best = refined[chosen];

  MatchResult result;
  if (source_is_part) {
    result.map = MapAllVertices(part, whole, part_rows, best.whole_rows, part.samples,
                                best.sample_images);
  } else {
    result.map = MapAllVertices(whole, part, best.whole_rows, part_rows,
                                best.sample_images, part.samples);
  }
  std::ostringstream message;
  message << "partial: the " << (source_is_part ? "source" : "target") << " is the part ("
          << static_cast<int>(std::lround(100.0 * part.area / whole.area))
          << "% of the whole's area); map by geodesic landmarks, residual " << best.residual
          << ", orientation kept by " << best.orientation << " of the samples; " << refined.size()
          << " distinct maps from " << triples.size() << " triple hypotheses"
          << (mirrored > 0 ? " and " + std::to_string(mirrored) + " mirror images" : "")
          << (seeded < 0                    ? ""
              : chosen == seeded            ? ", the seed's kept"
              : seed_turn && !shape_decided ? ", the seed's turn kept"
                                            : ", not the seed's")
          << ", shape disagreement " << best.shape << (shape_decided ? ", chosen by shape" : "");
  result.status.residual = best.residual;
  result.status.iterations = static_cast<int>(refined.size());
  result.status.message = message.str();
  return result;
}

double LandmarkDistortion(const Surface& source, const std::vector<int>& source_samples,
                          double source_unit, const Surface& target,
                          const std::vector<int>& target_samples, double target_unit,
                          const std::vector<int>& map, int count, const PartialRows& cached) {
  EdgeDistanceCache own(kCallRowBytes);
  const PartialRows rows = RowsOf(cached, &own);
  const MeshGraph source_graph = BuildMeshGraph(source), target_graph = BuildMeshGraph(target);
  auto distances = [&](const MeshGraph& graph, uint64_t key, const std::vector<int>& sources,
                       double unit) -> Eigen::MatrixXd {
    return rows.cache->Rows(key, graph, sources) * unit;
  };
  const double source_area = TotalArea(source) * source_unit * source_unit;
  const double target_area = TotalArea(target) * target_unit * target_unit;
  const bool source_is_part = source_area <= target_area;
  const std::vector<int>& samples = source_is_part ? source_samples : target_samples;
  const std::vector<int> landmarks(samples.begin(),
                                   samples.begin() + std::min<size_t>(count, samples.size()));
  const int n = static_cast<int>(landmarks.size());
  if (n < 2) return 0.0;
  Eigen::MatrixXd on_part, on_other;
  std::vector<int> counterparts(n);
  if (source_is_part) {
    on_part = distances(source_graph, rows.source_key, landmarks, source_unit);
    for (int i = 0; i < n; ++i) counterparts[i] = map[landmarks[i]];
    on_other = distances(target_graph, rows.target_key, counterparts, target_unit);
  } else {
    on_part = distances(target_graph, rows.target_key, landmarks, target_unit);
    for (int i = 0; i < n; ++i) {
      double nearest = std::numeric_limits<double>::infinity();
      for (size_t v = 0; v < map.size(); ++v) {
        if (on_part(i, map[v]) < nearest) {
          nearest = on_part(i, map[v]);
          counterparts[i] = static_cast<int>(v);
        }
      }
    }
    on_other = distances(source_graph, rows.source_key, counterparts, source_unit);
  }
  std::vector<double> gaps;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      gaps.push_back(std::abs(on_part(i, landmarks[j]) - on_other(i, counterparts[j])));
    }
  }
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2] / std::sqrt(std::min(source_area, target_area));
}

}  // namespace symembed
