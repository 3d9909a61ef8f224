#include "stages/geodesics/heat.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

bool HeatOptions::IsValid(std::string* error) const {
  const std::string why = FirstViolation({{"time_factor", kTimeFactor, time_factor}});
  if (why.empty()) return common.IsValid(error);
  if (error) *error = why;
  return false;
}

namespace {

// Sources per block: the solves of a block share one pass over the factor's structure per
// column and one allocation.
constexpr int kBlock = 16;

std::unique_ptr<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>> Factorize(
    const Eigen::SparseMatrix<double>& A, const char* what) {
  auto factor = std::make_unique<Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>>(A);
  if (factor->info() != Eigen::Success) {
    throw SolverError(std::string("heat method: factorisation of the ") + what + " failed");
  }
  return factor;
}

// Whether each vertex is in a face. Throws InvalidInputError for a surface without faces or a
// face with a vertex id out of range.
std::vector<char> UsedVertices(const Surface& s) {
  const int n = s.NumVertices(), nf = s.NumFaces();
  if (nf == 0) throw InvalidInputError("heat method: surface has no faces");
  std::vector<char> used(n, 0);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (s.F(f, k) < 0 || s.F(f, k) >= n) {
        throw InvalidInputError("heat method: face " + std::to_string(f) + " has a bad vertex id");
      }
      used[s.F(f, k)] = 1;
    }
  }
  return used;
}

// Whether each vertex is on the boundary (an endpoint of an edge with exactly one face).
std::vector<char> BoundaryVertices(const Surface& s, bool* has_boundary) {
  const int nf = s.NumFaces();
  std::vector<char> boundary(s.NumVertices(), 0);
  std::vector<std::pair<int, int>> edges;
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(s.F(f, k), s.F(f, (k + 1) % 3)));
  }
  std::sort(edges.begin(), edges.end());
  *has_boundary = false;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) {
      boundary[edges[i].first] = boundary[edges[i].second] = 1;
      *has_boundary = true;
    }
    i = j;
  }
  return boundary;
}

// The n x n diagonal matrix with `values` where `keep` is set (all when keep is empty).
Eigen::SparseMatrix<double> Diagonal(const Eigen::VectorXd& values, const std::vector<char>& keep) {
  const int n = static_cast<int>(values.size());
  std::vector<Eigen::Triplet<double>> triplets;
  for (int v = 0; v < n; ++v) {
    if (keep.empty() || keep[v]) triplets.emplace_back(v, v, values(v));
  }
  Eigen::SparseMatrix<double> D(n, n);
  D.setFromTriplets(triplets.begin(), triplets.end());
  return D;
}

// A with the rows and columns of fixed vertices replaced by identity rows and columns (u = 0
// there).
Eigen::SparseMatrix<double> WithFixedVertices(const Eigen::SparseMatrix<double>& A,
                                              const std::vector<char>& fixed_vertex) {
  const int n = static_cast<int>(A.rows());
  std::vector<Eigen::Triplet<double>> triplets;
  for (int col = 0; col < A.outerSize(); ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      const bool fixed = fixed_vertex[it.row()] || fixed_vertex[it.col()];
      if (!fixed) triplets.emplace_back(it.row(), it.col(), it.value());
    }
  }
  for (int v = 0; v < n; ++v) {
    if (fixed_vertex[v]) triplets.emplace_back(v, v, 1.0);
  }
  Eigen::SparseMatrix<double> AD(n, n);
  AD.setFromTriplets(triplets.begin(), triplets.end());
  return AD;
}

// Face operators, in each face's 2D layout (p_0 at the origin, p_1 on +x). The gradient of the
// linear interpolant is sum_k u_k rot90(p_j - p_i) / (2A) with (k, i, j) counter-clockwise;
// vertex k's divergence weight is (cot(angle at j) (p_i - p_k) + cot(angle at i) (p_j - p_k)) / 2
// [Crane et al. 2013, Sec. 3.2]. grad[k], div[k]: nf x 2, for the first nf faces of tri.
void FaceOperators(const IntrinsicTriangulation& tri, int nf, Eigen::MatrixX2d grad[3],
                   Eigen::MatrixX2d div[3]) {
  for (int k = 0; k < 3; ++k) {
    grad[k] = Eigen::MatrixX2d::Zero(nf, 2);
    div[k] = Eigen::MatrixX2d::Zero(nf, 2);
  }
  for (int f = 0; f < nf; ++f) {
    const Eigen::Matrix<double, 3, 2> p = IntrinsicLayout(tri, f);
    const double double_area = p(1, 0) * p(2, 1);  // base times height
    if (!(double_area > 0.0)) continue;            // a degenerate face carries no gradient
    auto cot = [&](int m) {
      const Eigen::Vector2d u = p.row((m + 1) % 3) - p.row(m), w = p.row((m + 2) % 3) - p.row(m);
      return u.dot(w) / (u.x() * w.y() - u.y() * w.x());
    };
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      const Eigen::RowVector2d e = p.row(j) - p.row(i);
      grad[k].row(f) << -e.y() / double_area, e.x() / double_area;
      div[k].row(f) = 0.5 * (cot(j) * (p.row(i) - p.row(k)) + cot(i) * (p.row(j) - p.row(k)));
    }
  }
}

}  // namespace

HeatGeodesicSolver::HeatGeodesicSolver(const Surface& s, const HeatOptions& options)
    : surface_(s), options_(options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("geodesics/heat: " + error);
  const int n = s.NumVertices();
  used_vertex_ = UsedVertices(s);
  boundary_vertex_ = BoundaryVertices(s, &has_boundary_);
  const double h = MeanEdgeLength(s);
  t_ = options.time_factor * h * h;
  const IntrinsicTriangulation tri =
      options.intrinsic_delaunay ? IntrinsicDelaunay(s) : IntrinsicFromSurface(s);
  flips_ = tri.flips;
  faces_ = tri.F;
  const Eigen::SparseMatrix<double> K = IntrinsicCotanStiffness(tri, n);
  const Eigen::VectorXd vertex_areas = IntrinsicVertexAreas(tri, n);
  const Eigen::SparseMatrix<double> M = Diagonal(vertex_areas, {});
  // Vertices in no face have empty rows; a unit diagonal keeps the systems non-singular.
  std::vector<char> unused_vertex(n);
  for (int v = 0; v < n; ++v) unused_vertex[v] = !used_vertex_[v];
  const Eigen::SparseMatrix<double> unused = Diagonal(Eigen::VectorXd::Ones(n), unused_vertex);
  const Eigen::SparseMatrix<double> A = M + t_ * K + unused;
  neumann_ = Factorize(A, "heat system");
  if (has_boundary_ && options.boundary != HeatBoundary::kNeumann) {
    dirichlet_ = Factorize(WithFixedVertices(A, boundary_vertex_), "Dirichlet heat system");
  }
  const double total_area = vertex_areas.sum();
  poisson_ = Factorize(K + (1e-8 / total_area) * M + unused, "Poisson system");
  FaceOperators(tri, s.NumFaces(), grad_, div_);
}

void HeatGeodesicSolver::SolveBlock(const int* sources, int count, Eigen::MatrixXd* out) const {
  const int n = surface_.NumVertices(), nf = static_cast<int>(faces_.rows());
  Eigen::MatrixXd delta = Eigen::MatrixXd::Zero(n, count);
  for (int c = 0; c < count; ++c) delta(sources[c], c) = 1.0;
  const Eigen::MatrixXd u_neumann = neumann_->solve(delta);
  Eigen::MatrixXd u;
  if (dirichlet_) {
    Eigen::MatrixXd delta_d = delta;
    for (int c = 0; c < count; ++c) {
      if (boundary_vertex_[sources[c]]) delta_d(sources[c], c) = 0.0;
    }
    const Eigen::MatrixXd u_dirichlet = dirichlet_->solve(delta_d);
    if (options_.boundary == HeatBoundary::kDirichlet) {
      u = u_dirichlet;
      // A Dirichlet solution from a boundary source vanishes: use the Neumann one there.
      for (int c = 0; c < count; ++c) {
        if (boundary_vertex_[sources[c]]) u.col(c) = u_neumann.col(c);
      }
    } else {
      u = 0.5 * (u_neumann + u_dirichlet);
    }
  } else {
    u = u_neumann;
  }
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, count);
  for (int c = 0; c < count; ++c) {
    for (int f = 0; f < nf; ++f) {
      const int a = faces_(f, 0), b = faces_(f, 1), d = faces_(f, 2);
      const Eigen::RowVector2d g =
          u(a, c) * grad_[0].row(f) + u(b, c) * grad_[1].row(f) + u(d, c) * grad_[2].row(f);
      const double norm = g.norm();
      if (!(norm > 0.0)) continue;
      const Eigen::RowVector2d X = -g / norm;
      // K phi = -div X (K is minus the paper's Laplacian).
      rhs(a, c) -= div_[0].row(f).dot(X);
      rhs(b, c) -= div_[1].row(f).dot(X);
      rhs(d, c) -= div_[2].row(f).dot(X);
    }
  }
  *out = poisson_->solve(rhs);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (int c = 0; c < count; ++c) {
    const double shift = (*out)(sources[c], c);
    for (int v = 0; v < n; ++v) {
      double& d = (*out)(v, c);
      d = (!used_vertex_[v] || u_neumann(v, c) == 0.0) ? kInf : std::max(d - shift, 0.0);
    }
  }
}

Eigen::MatrixXd HeatGeodesicSolver::Distances(const std::vector<int>& sources) const {
  const int n = surface_.NumVertices(), m = static_cast<int>(sources.size());
  for (int s : sources) {
    if (s < 0 || s >= n) {
      throw InvalidInputError("geodesic source " + std::to_string(s) +
                              " is not a vertex id in [0, " + std::to_string(n) + ")");
    }
  }
  Eigen::MatrixXd D(m, n);
  const int blocks = (m + kBlock - 1) / kBlock;
  ParallelFor(
      blocks,
      [&](int b) {
        const int begin = b * kBlock, count = std::min(kBlock, m - begin);
        Eigen::MatrixXd block;
        SolveBlock(sources.data() + begin, count, &block);
        D.middleRows(begin, count) = block.transpose();
      },
      options_.common.threads);
  return D;
}

Eigen::MatrixXd HeatDistances(const Surface& surface, const std::vector<int>& sources,
                              const HeatOptions& options) {
  return HeatGeodesicSolver(surface, options).Distances(sources);
}

}  // namespace symembed
