#include "stages/geodesics/fast_marching.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/errors.h"

namespace symembed {

bool FastMarchingOptions::IsValid(std::string* error) const {
  const std::string why = FirstViolation({{"max_unfold_steps", kMaxUnfoldSteps, max_unfold_steps}});
  if (why.empty()) return common.IsValid(error);
  if (error) *error = why;
  return false;
}

namespace {

// A planar update stencil of vertex c from p and r, with p - c and r - c as 2D vectors.
struct Stencil {
  int c, p, r;
  Eigen::Vector2d pv, rv;
};

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Faces around each undirected edge, for walking across edges while unfolding.
class EdgeFaces {
 public:
  explicit EdgeFaces(const Surface& s) {
    items_.reserve(3 * s.NumFaces());
    for (int f = 0; f < s.NumFaces(); ++f) {
      for (int k = 0; k < 3; ++k) {
        const auto [a, b] = std::minmax(s.F(f, k), s.F(f, (k + 1) % 3));
        items_.push_back({a, b, f});
      }
    }
    std::sort(items_.begin(), items_.end());
  }
  // The other face of a manifold edge {x, y} seen from face g; -1 on boundary or
  // non-manifold edges.
  int Across(int x, int y, int g) const {
    const auto [a, b] = std::minmax(x, y);
    auto lo = std::lower_bound(items_.begin(), items_.end(), std::array<int, 3>{a, b, -1});
    auto hi = std::upper_bound(lo, items_.end(),
                               std::array<int, 3>{a, b, std::numeric_limits<int>::max()});
    if (hi - lo != 2) return -1;
    return (*lo)[2] == g ? (*(lo + 1))[2] : (*lo)[2];
  }

 private:
  std::vector<std::array<int, 3>> items_;
};

// Third vertex of face h given two of its vertices, or -1.
int ThirdVertex(const Surface& s, int h, int x, int y) {
  for (int k = 0; k < 3; ++k) {
    const int z = s.F(h, k);
    if (z != x && z != y) return z;
  }
  return -1;
}

// True when segment (0, d) crosses segment (x, y) (proper or touching).
bool SegmentFromOriginCrosses(const Eigen::Vector2d& d, const Eigen::Vector2d& x,
                              const Eigen::Vector2d& y) {
  const double s1 = Cross2(d, x), s2 = Cross2(d, y);
  if (s1 * s2 > 0.0) return false;
  const Eigen::Vector2d e = y - x;
  const double t1 = Cross2(e, -x), t2 = Cross2(e, d - x);
  return t1 * t2 <= 0.0;
}

// Splits the obtuse corner (c; a, b) of face f by unfolding the triangles beyond edge (a, b)
// into the plane of f, in a frame with c at the origin, a on +x and b in the upper half plane.
// On success, appends the two acute virtual stencils and returns true.
bool SplitObtuseCorner(const Surface& s, const EdgeFaces& edge_faces, int f, int c, int a, int b,
                       const Eigen::Vector2d& a2, const Eigen::Vector2d& b2, int max_steps,
                       std::vector<Stencil>* out) {
  const double theta = std::atan2(b2.y(), b2.x());
  // Directions D with both angles (A, C, D) and (D, C, B) below 90 degrees.
  const double cone_lo = theta - M_PI / 2, cone_hi = M_PI / 2;
  int x = a, y = b, g = f;
  Eigen::Vector2d x2 = a2, y2 = b2, w2 = Eigen::Vector2d::Zero();
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> strip = {{x2, y2}};
  for (int step = 0; step < max_steps; ++step) {
    const int h = edge_faces.Across(x, y, g);
    if (h < 0) return false;
    const int z = ThirdVertex(s, h, x, y);
    if (z < 0 || z == c) return false;
    // Unfold z: its distances to x and y are kept; it goes on the side of (x, y) away from w.
    const double lx = (s.V.row(z) - s.V.row(x)).norm(), ly = (s.V.row(z) - s.V.row(y)).norm();
    const Eigen::Vector2d e = y2 - x2;
    const double len = e.norm();
    if (len <= 0.0) return false;
    const Eigen::Vector2d u = e / len;
    Eigen::Vector2d perp(-u.y(), u.x());
    if (perp.dot(w2 - x2) > 0.0) perp = -perp;
    const double along = (lx * lx - ly * ly + len * len) / (2.0 * len);
    const double height = std::sqrt(std::max(lx * lx - along * along, 0.0));
    const Eigen::Vector2d z2 = x2 + along * u + height * perp;
    const double phi = std::atan2(z2.y(), z2.x());
    if (phi > cone_lo && phi < cone_hi) {
      // The virtual edge must stay inside the unfolded strip.
      for (const auto& [p, q] : strip) {
        if (!SegmentFromOriginCrosses(z2, p, q)) return false;
      }
      out->push_back({c, a, z, a2, z2});
      out->push_back({c, z, b, z2, b2});
      return true;
    }
    if (phi <= cone_lo) {
      w2 = x2;
      x = z;
      x2 = z2;
    } else {
      w2 = y2;
      y = z;
      y2 = z2;
    }
    strip.emplace_back(x2, y2);
    g = h;
  }
  return false;
}

}  // namespace

FastMarchingGeodesicSolver::FastMarchingGeodesicSolver(const Surface& s,
                                                       const FastMarchingOptions& options)
    : num_vertices_(s.NumVertices()), options_(options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("geodesics/fast_marching: " + error);
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int v = s.F(f, k);
      if (v < 0 || v >= num_vertices_) {
        throw InvalidInputError("face " + std::to_string(f) + " has a bad vertex id");
      }
    }
  }
  const EdgeFaces edge_faces(s);
  std::vector<Stencil> stencils;
  stencils.reserve(3 * s.NumFaces() + 64);
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int c = s.F(f, k), a = s.F(f, (k + 1) % 3), b = s.F(f, (k + 2) % 3);
      if (c == a || c == b || a == b) continue;
      const Eigen::Vector3d ea = s.V.row(a) - s.V.row(c), eb = s.V.row(b) - s.V.row(c);
      const double la = ea.norm(), lb = eb.norm();
      const double theta = std::atan2(ea.cross(eb).norm(), ea.dot(eb));
      const Eigen::Vector2d a2(la, 0.0), b2(lb * std::cos(theta), lb * std::sin(theta));
      if (ea.dot(eb) < 0.0) {
        ++obtuse_corners_;
        if (options.max_unfold_steps > 0 &&
            SplitObtuseCorner(s, edge_faces, f, c, a, b, a2, b2, options.max_unfold_steps,
                              &stencils)) {
          ++split_corners_;
          continue;
        }
      }
      stencils.push_back({c, a, b, a2, b2});
    }
  }
  // Each stencil is triggered by either of its two base vertices.
  offsets_.assign(num_vertices_ + 1, 0);
  for (const Stencil& st : stencils) {
    ++offsets_[st.p + 1];
    ++offsets_[st.r + 1];
  }
  for (int v = 0; v < num_vertices_; ++v) offsets_[v + 1] += offsets_[v];
  updates_.resize(offsets_.back());
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (const Stencil& st : stencils) {
    const double g00 = st.pv.squaredNorm(), g01 = st.pv.dot(st.rv), g11 = st.rv.squaredNorm();
    const double det = g00 * g11 - g01 * g01;
    // A (nearly) degenerate triangle only contributes its edges: Q = 0 disables the planar
    // update.
    double q00 = 0.0, q01 = 0.0, q11 = 0.0;
    if (det > 1e-12 * g00 * g11) {
      q00 = g11 / det;
      q01 = -g01 / det;
      q11 = g00 / det;
    }
    const double lp = st.pv.norm(), lr = st.rv.norm();
    const float f00 = static_cast<float>(q00), f01 = static_cast<float>(q01),
                f11 = static_cast<float>(q11);
    updates_[fill[st.p]++] = {
        st.c, st.r, f00, f01, f11, static_cast<float>(lp), static_cast<float>(lr)};
    updates_[fill[st.r]++] = {
        st.c, st.p, f11, f01, f00, static_cast<float>(lr), static_cast<float>(lp)};
  }
}

// Per-thread state of one sweep: an indexed binary min-heap on T with decrease-key (each
// vertex is in the heap at most once, so the heap stays as small as the narrow band) and the
// accepted flags.
template <typename Scalar>
struct FastMarchingGeodesicSolver::Workspace {
  std::vector<int> heap;      // vertex ids, heap-ordered by T
  std::vector<int> position;  // #V: index in heap, -1 when not in the heap
  std::vector<char> accepted;
  const Scalar* T = nullptr;

  void Reset(int n, const Scalar* values) {
    heap.clear();
    position.assign(n, -1);
    accepted.assign(n, 0);
    T = values;
  }
  void SiftUp(int i) {
    const int v = heap[i];
    while (i > 0) {
      const int parent = (i - 1) / 2;
      if (T[heap[parent]] <= T[v]) break;
      heap[i] = heap[parent];
      position[heap[i]] = i;
      i = parent;
    }
    heap[i] = v;
    position[v] = i;
  }
  // Inserts v or, when it is already in the heap, restores order after T[v] decreased.
  void PushOrDecrease(int v) {
    if (position[v] < 0) {
      heap.push_back(v);
      position[v] = static_cast<int>(heap.size()) - 1;
    }
    SiftUp(position[v]);
  }
  int PopMin() {
    const int top = heap[0];
    position[top] = -1;
    const int last = heap.back();
    heap.pop_back();
    const int n = static_cast<int>(heap.size());
    if (n > 0) {
      int i = 0;
      while (true) {
        int child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && T[heap[child + 1]] < T[heap[child]]) ++child;
        if (T[last] <= T[heap[child]]) break;
        heap[i] = heap[child];
        position[heap[i]] = i;
        i = child;
      }
      heap[i] = last;
      position[last] = i;
    }
    return top;
  }
};

template <typename Scalar>
void FastMarchingGeodesicSolver::Solve(int source, Scalar* T, Workspace<Scalar>* ws) const {
  const int n = num_vertices_;
  std::fill(T, T + n, std::numeric_limits<Scalar>::infinity());
  ws->Reset(n, T);
  std::vector<char>& accepted = ws->accepted;
  T[source] = 0;
  ws->PushOrDecrease(source);
  while (!ws->heap.empty()) {
    const int v = ws->PopMin();
    accepted[v] = 1;
    const double tv = T[v];
    for (int k = offsets_[v]; k < offsets_[v + 1]; ++k) {
      const Update& u = updates_[k];
      if (accepted[u.target]) continue;
      double best = tv + u.len_v;
      if (accepted[u.other]) {
        const double to = T[u.other];
        best = std::min(best, to + u.len_o);
        // Larger root of a p^2 - 2 b p + c = 0 (see the header).
        const double qvv = u.q_vv, qvo = u.q_vo, qoo = u.q_oo;
        const double a = qvv + 2.0 * qvo + qoo;
        if (a > 0.0) {
          const double b = (qvv + qvo) * tv + (qvo + qoo) * to;
          const double c = qvv * tv * tv + 2.0 * qvo * tv * to + qoo * to * to - 1.0;
          const double disc = b * b - a * c;
          if (disc >= 0.0) {
            const double p = (b + std::sqrt(disc)) / a;
            // Causality: the gradient direction lies in the cone of the two edges.
            if (qvv * (p - tv) + qvo * (p - to) >= 0.0 && qvo * (p - tv) + qoo * (p - to) >= 0.0) {
              best = std::min(best, p);
            }
          }
        }
      }
      if (best < T[u.target]) {
        T[u.target] = static_cast<Scalar>(best);
        ws->PushOrDecrease(u.target);
      }
    }
  }
}

Eigen::MatrixXd FastMarchingGeodesicSolver::Distances(const std::vector<int>& sources) const {
  const int n = num_vertices_;
  if (options_.common.precision == GeodesicPrecision::kFloat) {
    return ParallelRows(sources, n, options_.common.threads, [&](int i, double* out) {
      thread_local std::vector<float> T;
      thread_local Workspace<float> ws;
      T.resize(n);
      Solve<float>(sources[i], T.data(), &ws);
      for (int v = 0; v < n; ++v) out[v] = T[v];
    });
  }
  return ParallelRows(sources, n, options_.common.threads, [&](int i, double* out) {
    thread_local Workspace<double> ws;
    Solve<double>(sources[i], out, &ws);
  });
}

Eigen::MatrixXd FastMarchingDistances(const Surface& surface, const std::vector<int>& sources,
                                      const FastMarchingOptions& options) {
  return FastMarchingGeodesicSolver(surface, options).Distances(sources);
}

}  // namespace symembed
